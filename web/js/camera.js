// Camera state and its `cam=` text form, plus the trackball maths for orbit/zoom/pan; no DOM, no network.

import { CAMERA_LIMITS, DEFAULT_CAMERA, PROJECTIONS, VIEWS } from './contract.js';

// The named views (degrees; image up follows elevation on the server side), the ranges the server
// accepts (anything outside would be a 400, so clamp before sending) and the default camera: all
// generated from the server's C++ (contract.js).
export { DEFAULT_CAMERA, VIEWS };
export const LIMITS = CAMERA_LIMITS;

const clamp = (v, [lo, hi]) => Math.min(hi, Math.max(lo, v));

// Short, stable decimal text so URLs stay readable and identical states give identical URLs.
function num(v, digits = 2) {
  const s = Number(v.toFixed(digits)).toString();
  return s === '-0' ? '0' : s;
}

// Keeps az in (-180, 180] so repeated orbiting never leaves the accepted [-360, 360].
function wrapAz(az) {
  let a = ((az + 180) % 360 + 360) % 360 - 180;
  if (a === -180) a = 180;
  return a;
}

// A camera the server accepts: what is missing or not a number takes the default, the rest is clamped.
export function normalize(cam) {
  const d = DEFAULT_CAMERA;
  return {
    az: wrapAz(Number.isFinite(cam.az) ? cam.az : d.az),
    el: clamp(Number.isFinite(cam.el) ? cam.el : d.el, LIMITS.el),
    zoom: clamp(Number.isFinite(cam.zoom) && cam.zoom > 0 ? cam.zoom : d.zoom, LIMITS.zoom),
    panX: clamp(Number.isFinite(cam.panX) ? cam.panX : d.panX, LIMITS.pan),
    panY: clamp(Number.isFinite(cam.panY) ? cam.panY : d.panY, LIMITS.pan),
    proj: Object.values(PROJECTIONS).includes(cam.proj) ? cam.proj : d.proj,
    fov: clamp(Number.isFinite(cam.fov) ? cam.fov : d.fov, LIMITS.fov),
  };
}

// Parses `az=30,el=20,zoom=1,pan=0:0,proj=ortho,fov=30` or a bare view name.
// Throws an Error naming the bad part, so a broken link shows a clear message.
export function parseCamera(text) {
  const t = String(text ?? '').trim();
  if (t === '') return { ...DEFAULT_CAMERA };
  if (Object.hasOwn(VIEWS, t)) return { ...DEFAULT_CAMERA, ...VIEWS[t] };
  const cam = { ...DEFAULT_CAMERA };
  for (const part of t.split(',')) {
    const eq = part.indexOf('=');
    if (eq < 0) throw new Error(`camera: '${part}' is not key=value`);
    const key = part.slice(0, eq).trim();
    const value = part.slice(eq + 1).trim();
    if (key === 'proj') {
      const words = Object.values(PROJECTIONS);
      if (!words.includes(value)) throw new Error(`camera: proj '${value}' is not ${words.join(' or ')}`);
      cam.proj = value;
    } else if (key === 'pan') {
      const [x, y] = value.split(':').map(Number);
      if (!Number.isFinite(x) || !Number.isFinite(y)) throw new Error(`camera: pan '${value}' is not x:y`);
      cam.panX = x;
      cam.panY = y;
    } else if (key === 'az' || key === 'el' || key === 'zoom' || key === 'fov') {
      const v = Number(value);
      if (value === '' || !Number.isFinite(v)) throw new Error(`camera: ${key} '${value}' is not a number`);
      cam[key] = v;
    } else {
      throw new Error(`camera: unknown key '${key}'`);
    }
  }
  return normalize(cam);
}

export function formatCamera(cam) {
  const c = normalize(cam);
  return `az=${num(c.az)},el=${num(c.el)},zoom=${num(c.zoom, 4)},pan=${num(c.panX, 4)}:${num(c.panY, 4)},proj=${c.proj},fov=${num(c.fov)}`;
}

// The named view the camera is looking from, if it is exactly one of the six.
export function viewName(cam) {
  const c = normalize(cam);
  for (const [name, v] of Object.entries(VIEWS)) {
    if (Math.abs(c.el - v.el) < 1e-6 && Math.abs(wrapAz(c.az - v.az)) < 1e-6) return name;
  }
  return null;
}

// Left-drag: right increases az, up increases el (clamped), like VTK's trackball camera.
// A drag across the shorter side of the view turns the volume by 180 degrees.
export function orbit(cam, dxPx, dyPx, viewW, viewH) {
  const degPerPx = 180 / Math.max(1, Math.min(viewW, viewH));
  return normalize({ ...cam, az: cam.az + dxPx * degPerPx, el: cam.el - dyPx * degPerPx });
}

// Shift- or middle-drag: the content follows the pointer. The server's pan moves the look-at point
// along image right/up (in visible half-heights), so the content moves the opposite way: hence the signs.
export function pan(cam, dxPx, dyPx, viewH) {
  const half = Math.max(1, viewH / 2);
  return normalize({ ...cam, panX: cam.panX - dxPx / half, panY: cam.panY + dyPx / half });
}

// Wheel: one notch (100 px of deltaY) zooms by 10 %; wheel towards the user zooms out.
export function zoomBy(cam, wheelDeltaPx) {
  return normalize({ ...cam, zoom: cam.zoom * Math.pow(1.1, -wheelDeltaPx / 100) });
}

// A named view keeps zoom and projection but recentres, as VTK's view buttons do.
export function toView(cam, name) {
  return normalize({ ...cam, ...VIEWS[name], panX: 0, panY: 0 });
}
