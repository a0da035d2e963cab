// The URL hash: the view as link text and back (bad parts fall back and are named), and throttled writing.
import { DEFAULT_CAMERA, formatCamera, parseCamera } from './camera.js';
import { defaultEpsOf, rangeSpan } from './eps.js';
import { fmtExact } from './format.js';
import { formatSlab, parseSlab } from './slab.js';
import { DEFAULT_COLORMAP, DEFAULT_MODE, DEFAULT_RENDERER, LEGACY_MODES, MAX_DEGREE } from './contract.js';
import { COLORMAPS, MODES, reconcileRenderer, RENDERERS } from './view.js';

const HASH_WRITE_MS = 250; // Chrome throttles replaceState floods, so drags write the hash at most this often

// Keeps ',' ':' readable in links; everything else is percent-encoded.
function enc(v) {
  return encodeURIComponent(v).replace(/%2C/g, ',').replace(/%3A/g, ':');
}

export function formatHash(view) {
  const parts = [['dataset', view.dataset], ['cam', formatCamera(view.cam)]];
  if (view.frame) parts.push(['frame', view.frame]); // frame 0 unsaid, so a 3D dataset's link reads as before
  // With no eps (the server sent no default and the user chose none) the link carries none either.
  if (view.eps !== null) parts.push(['eps', view.eps]);
  parts.push(['mode', view.mode]);
  // The defaults (the Vot renderer, the whole ray) stay out of the link, so older links read the same.
  if (view.renderer !== DEFAULT_RENDERER) parts.push(['renderer', view.renderer]);
  if (view.slab) parts.push(['slab', formatSlab(view.slab)]);
  parts.push(
    ['window', `${fmtExact(view.window.level)},${fmtExact(view.window.width)}`],
    ['colormap', view.colormap],
  );
  if (view.degree !== undefined) parts.push(['degree', view.degree]);
  return '#' + parts.map(([k, v]) => `${k}=${enc(String(v))}`).join('&');
}

// The view a hash asks for, given the datasets and the current view (kept where the link says nothing new).
// Returns {view, problems}: bad parts fall back to defaults and each gets a sentence in `problems`.
export function parseHash(hash, datasets, current) {
  const q = new URLSearchParams(hash.replace(/^#/, ''));
  const problems = [];
  let ds = null;
  const wanted = q.get('dataset');
  if (wanted !== null && wanted !== '') {
    ds = datasets.find((d) => d.name === wanted) || null;
    if (!ds) {
      const names = datasets.map((d) => d.name).join(', ');
      problems.push(`Unknown dataset '${wanted}' in the link (available: ${names}).`);
    }
  }
  const switching = !ds || ds.name !== current.dataset;
  // With no choice in the link, open the Cranium CT (the README's default dataset), else any CT.
  if (!ds) {
    ds = datasets.find((d) => d.name === current.dataset) || datasets.find((d) => d.name === 'cranium') ||
      datasets.find((d) => d.modality === 'CT') || datasets[0];
  }

  let cam;
  try {
    cam = parseCamera(q.get('cam') ?? '');
  } catch (e) {
    problems.push(`${e.message}; using the default camera.`);
    cam = { ...DEFAULT_CAMERA };
  }

  // eps in data units, or as a percentage of the value range ("2%"), which the server also accepts.
  const epsText = q.get('eps') || '';
  let eps = Number(epsText.replace(/%$/, ''));
  if (epsText.endsWith('%')) eps = Number(((eps / 100) * rangeSpan(ds)).toPrecision(3));
  // Without a usable eps in the link, the current eps stays on the same dataset; a new one starts at its default.
  const keptEps = switching || !(current.eps > 0) ? defaultEpsOf(ds) : current.eps;
  if (q.has('eps') && !(eps > 0)) {
    problems.push(`eps '${epsText}' must be a positive number; ${keptEps === null ? 'the server sent no default' : `using ${keptEps}`}.`);
  }

  const degree = q.get('degree');
  // An old link's mode name that also chooses the renderer (`reference`, from before the renderer
  // choice: MIP on the grid).
  const legacy = Object.hasOwn(LEGACY_MODES, q.get('mode') ?? '') ? LEGACY_MODES[q.get('mode')] : null;
  const mode = legacy ? legacy.mode : q.get('mode');
  if (mode !== null && !MODES.includes(mode)) problems.push(`Unknown mode '${mode}'; using MIP.`);
  const rendererText = q.get('renderer');
  if (rendererText !== null && !RENDERERS.includes(rendererText)) {
    problems.push(`Unknown renderer '${rendererText}'; using the Vots.`);
  }
  const renderer = legacy ? legacy.renderer : RENDERERS.includes(rendererText) ? rendererText : DEFAULT_RENDERER;
  const slab = q.has('slab') ? parseSlab(q.get('slab')) : null;
  if (q.has('slab') && !slab) {
    problems.push(`slab '${q.get('slab')}' is not offset,thickness in mm with thickness > 0; showing the whole volume.`);
  }
  const cmap = q.get('colormap');
  if (cmap !== null && !COLORMAPS.includes(cmap)) problems.push(`Unknown colour map '${cmap}'; using grey.`);

  const win = (q.get('window') || '').split(',').map(Number);
  const winOk = win.length === 2 && Number.isFinite(win[0]) && win[1] > 0;
  if (q.has('window') && !winOk) {
    problems.push(`window '${q.get('window')}' is not level,width with width > 0; using the dataset default.`);
  }

  const frames = Math.max(1, Number(ds.frames) || 1);
  const frame = q.has('frame') ? Number(q.get('frame')) : 0;
  const frameOk = Number.isInteger(frame) && frame >= 0 && frame < frames;
  if (!frameOk) problems.push(`frame '${q.get('frame')}' is not one of the ${frames} of '${ds.name}'; showing frame 0.`);

  const view = {
    dataset: ds.name,
    frame: frameOk ? frame : 0,
    cam,
    eps: eps > 0 ? eps : keptEps,
    degree: degree !== null && /^\d$/.test(degree) && Number(degree) <= MAX_DEGREE ? Number(degree) : undefined,
    mode: MODES.includes(mode) ? mode : DEFAULT_MODE,
    renderer,
    slab,
    window: winOk ? { level: win[0], width: win[1] } : { level: Number(ds.window.level), width: Number(ds.window.width) },
    colormap: COLORMAPS.includes(cmap) ? cmap : DEFAULT_COLORMAP,
  };
  reconcileRenderer(view, 'mode'); // a link asking for density on the grid gets the Vots
  return { view, problems };
}

// Writes text() into the hash with replaceState (no history entries); `now: false` throttles to HASH_WRITE_MS.
export function createHashWriter(text) {
  let timer = 0;
  let lastWrite = 0;
  return function writeHash({ now = true } = {}) {
    clearTimeout(timer);
    const write = () => {
      lastWrite = performance.now();
      const t = text();
      if (location.hash !== t) history.replaceState(null, '', t);
    };
    if (now || performance.now() - lastWrite >= HASH_WRITE_MS) write();
    else timer = setTimeout(write, HASH_WRITE_MS);
  };
}
