// Viewer controller: owns the view state, mirrors it into the URL hash and the controls, schedules frames and fits.
import { ApiError, fetchDatasets, fetchFrame, followJob, renderUrl, startFit } from './api.js';
import {
  DEFAULT_CAMERA, formatCamera, orbit, pan, parseCamera, toView, viewName, zoomBy,
} from './camera.js';

const MODES = ['mip', 'density', 'reference'];
const COLORMAPS = ['grey', 'bone', 'hot', 'viridis'];
const PRESET_LABELS = { bone: 'Bone', soft: 'Soft tissue', full: 'Full range' };
const MAX_FRAME_PX = 2048; // longest side of a requested frame, in device pixels
const DRAFT_DIVISOR = 3; // frames while dragging are this much smaller, scaled up by CSS
const SLIDER_STEPS = 1000; // eps-slider integer range, mapped log-linearly onto [epsMin, epsMax]
const HASH_WRITE_MS = 250; // Chrome throttles replaceState floods, so drags write the hash at most this often
const WHEEL_SETTLE_MS = 200; // after the last wheel event, send the full-quality frame

const $ = (id) => document.getElementById(id);
const el = {
  view: $('view'),
  image: $('image'),
  status: $('status'),
  error: $('error'),
  errorText: $('error-text'),
  errorClose: $('error-close'),
  dataset: $('dataset'),
  datasetMeta: $('dataset-meta'),
  mode: $('mode'),
  colormap: $('colormap'),
  preset: $('window-preset'),
  level: $('level'),
  width: $('width'),
  epsSlider: $('eps-slider'),
  epsValue: $('eps-value'),
  fitProgress: $('fit-progress'),
  progress: $('progress'),
  progressLabel: $('progress-label'),
  votCount: $('vot-count'),
  fitTime: $('fit-time'),
  projection: $('projection'),
  viewButtons: [...document.querySelectorAll('[data-view]')],
};

// One random id per page: the server answers 409 "superseded" to our older requests.
const CLIENT_ID = [...crypto.getRandomValues(new Uint8Array(8))].map((b) => b.toString(16).padStart(2, '0')).join('');

let datasets = [];
// What the user asked for; this is what the URL hash holds.
const state = {
  dataset: null, // dataset name
  cam: { ...DEFAULT_CAMERA },
  eps: null, // target error bound, data units
  degree: undefined, // only sent when the link carries one
  mode: 'mip',
  window: { level: 0, width: 1 }, // data units
  colormap: 'grey',
};
// eps values known to be fitted, per dataset; frames are rendered only with one of these.
const fitted = new Map();
let renderEps = null; // eps used for frames: the target once its fit is done, else the previous one
let errorSource = null;

// ---------- small helpers ----------

function fmtValue(v) {
  if (!Number.isFinite(v)) return '–';
  const a = Math.abs(v);
  if (a >= 1000 || Number.isInteger(v)) return String(Math.round(v * 100) / 100);
  return String(Number(v.toPrecision(3)));
}

// For values the user typed or that go into URLs: enough digits to round-trip, none of float noise.
function fmtExact(v) {
  return String(Number(Number(v).toPrecision(7)));
}

function fmtCount(n) {
  return Number.isFinite(n) ? Math.round(n).toLocaleString('en-US') : '–';
}

function fmtSeconds(s) {
  if (!Number.isFinite(s)) return '–';
  return s < 10 ? `${s.toFixed(2)} s` : `${s.toFixed(1)} s`;
}

function currentDataset() {
  return datasets.find((d) => d.name === state.dataset) || null;
}

function rangeSpan(ds) {
  const span = Number(ds.range[1]) - Number(ds.range[0]);
  return span > 0 ? span : 1;
}

// A dataset's default eps counts as fitted: the server fits it first, and /render waits for it anyway.
function isFitted(name, eps) {
  const ds = datasets.find((d) => d.name === name);
  if (ds && Number(ds.defaultEps) === eps) return true;
  return fitted.has(name) && fitted.get(name).has(eps);
}

function markFitted(name, eps) {
  if (!fitted.has(name)) fitted.set(name, new Set());
  fitted.get(name).add(eps);
}

// ---------- error banner ----------

// source: 'render' | 'fit' | 'link' | 'datasets'; a later success of the same source clears it.
function showError(message, source) {
  errorSource = source;
  el.errorText.textContent = message;
  el.error.hidden = false;
  updateStatus();
}

function clearError(source) {
  if (errorSource !== source) return;
  errorSource = null;
  el.error.hidden = true;
}

el.errorClose.addEventListener('click', () => {
  errorSource = null;
  el.error.hidden = true;
});

// ---------- URL hash ----------

// Keeps ',' ':' readable in links; everything else is percent-encoded.
function enc(v) {
  return encodeURIComponent(v).replace(/%2C/g, ',').replace(/%3A/g, ':');
}

function hashText() {
  const parts = [
    ['dataset', state.dataset],
    ['cam', formatCamera(state.cam)],
    ['eps', state.eps],
    ['mode', state.mode],
    ['window', `${fmtExact(state.window.level)},${fmtExact(state.window.width)}`],
    ['colormap', state.colormap],
  ];
  if (state.degree !== undefined) parts.push(['degree', state.degree]);
  return '#' + parts.map(([k, v]) => `${k}=${enc(String(v))}`).join('&');
}

let hashTimer = 0;
let lastHashWrite = 0;

function writeHash({ now = true } = {}) {
  clearTimeout(hashTimer);
  const write = () => {
    lastHashWrite = performance.now();
    const text = hashText();
    if (location.hash !== text) history.replaceState(null, '', text);
  };
  if (now || performance.now() - lastHashWrite >= HASH_WRITE_MS) write();
  else hashTimer = setTimeout(write, HASH_WRITE_MS);
}

// Applies the hash to `state`; bad parts fall back to defaults and are reported in the banner.
function applyHash() {
  const q = new URLSearchParams(location.hash.replace(/^#/, ''));
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
  const switching = !ds || ds.name !== state.dataset;
  // With no choice in the link, open the Cranium CT (the README's default dataset), else any CT.
  if (!ds) {
    ds = datasets.find((d) => d.name === state.dataset) || datasets.find((d) => d.name === 'cranium') ||
      datasets.find((d) => d.modality === 'CT') || datasets[0];
  }
  state.dataset = ds.name;

  try {
    state.cam = parseCamera(q.get('cam') ?? '');
  } catch (e) {
    problems.push(`${e.message}; using the default camera.`);
    state.cam = { ...DEFAULT_CAMERA };
  }

  // eps in data units, or as a percentage of the value range ("2%"), which the server also accepts.
  const epsText = q.get('eps') || '';
  let eps = Number(epsText.replace(/%$/, ''));
  if (epsText.endsWith('%')) eps = Number(((eps / 100) * rangeSpan(ds)).toPrecision(3));
  if (q.has('eps') && !(eps > 0)) problems.push(`eps '${epsText}' must be a positive number; using ${ds.defaultEps}.`);
  state.eps = eps > 0 ? eps : (switching || !(state.eps > 0) ? Number(ds.defaultEps) : state.eps);

  const degree = q.get('degree');
  state.degree = degree !== null && /^[0-3]$/.test(degree) ? Number(degree) : undefined;

  const mode = q.get('mode');
  if (mode !== null && !MODES.includes(mode)) problems.push(`Unknown mode '${mode}'; using MIP.`);
  state.mode = MODES.includes(mode) ? mode : 'mip';

  const cmap = q.get('colormap');
  if (cmap !== null && !COLORMAPS.includes(cmap)) problems.push(`Unknown colour map '${cmap}'; using grey.`);
  state.colormap = COLORMAPS.includes(cmap) ? cmap : 'grey';

  const win = (q.get('window') || '').split(',').map(Number);
  if (q.has('window') && !(win.length === 2 && Number.isFinite(win[0]) && win[1] > 0)) {
    problems.push(`window '${q.get('window')}' is not level,width with width > 0; using the dataset default.`);
  }
  state.window = win.length === 2 && Number.isFinite(win[0]) && win[1] > 0
    ? { level: win[0], width: win[1] }
    : { level: Number(ds.window.level), width: Number(ds.window.width) };

  if (problems.length) showError(problems.join(' '), 'link');
  else clearError('link');
}

// ---------- controls <-> state ----------

function epsBounds(ds) {
  const span = rangeSpan(ds);
  const def = Number(ds.defaultEps) > 0 ? Number(ds.defaultEps) : span * 0.02;
  return { min: Math.min(span * 1e-3, def), max: Math.max(span * 0.5, def) };
}

function epsToSlider(ds, eps) {
  const { min, max } = epsBounds(ds);
  const t = Math.log(Math.min(max, Math.max(min, eps)) / min) / Math.log(max / min);
  return Math.round(t * SLIDER_STEPS);
}

// Three significant digits keep URLs short and make equal slider positions hit the server's fit cache.
function sliderToEps(ds, pos) {
  const { min, max } = epsBounds(ds);
  return Number((min * Math.pow(max / min, pos / SLIDER_STEPS)).toPrecision(3));
}

function epsLabel(ds, eps) {
  const pct = (100 * eps) / rangeSpan(ds);
  const pctText = pct >= 10 ? pct.toFixed(0) : pct >= 1 ? pct.toFixed(1) : pct.toPrecision(2);
  return `${fmtValue(eps)} (${pctText} % of range)`;
}

function fillDatasetPicker() {
  el.dataset.replaceChildren(...datasets.map((d) => new Option(d.name, d.name)));
}

function fillPresets(ds) {
  const opts = [];
  for (const key of Object.keys(ds.presets || {})) opts.push(new Option(PRESET_LABELS[key] || key, key));
  // The dataset's own window gets an entry only when no named preset already is that window.
  const same = (a, b) => a && b && Number(a.level) === Number(b.level) && Number(a.width) === Number(b.width);
  if (!Object.values(ds.presets || {}).some((p) => same(p, ds.window))) {
    opts.unshift(new Option('Dataset default', 'default'));
  }
  opts.push(new Option('Custom', 'custom'));
  el.preset.replaceChildren(...opts);
}

function presetWindow(ds, key) {
  if (key === 'default') return ds.window;
  return (ds.presets || {})[key] || null;
}

function matchingPreset(ds) {
  const same = (w) => w && Math.abs(w.level - state.window.level) < 1e-6 && Math.abs(w.width - state.window.width) < 1e-6;
  for (const o of el.preset.options) {
    if (o.value !== 'custom' && same(presetWindow(ds, o.value))) return o.value;
  }
  return 'custom';
}

function syncControls() {
  const ds = currentDataset();
  if (!ds) return;
  el.dataset.value = ds.name;
  el.datasetMeta.textContent = `${ds.dims.join('×')} · ${ds.modality || 'other'} · range ${fmtValue(ds.range[0])}..${fmtValue(ds.range[1])}`;
  el.mode.value = state.mode;
  el.colormap.value = state.colormap;
  el.preset.value = matchingPreset(ds);
  el.level.value = fmtExact(state.window.level);
  el.width.value = fmtExact(state.window.width);
  el.epsSlider.value = String(epsToSlider(ds, state.eps));
  el.epsValue.textContent = epsLabel(ds, state.eps);
  el.projection.textContent = state.cam.proj === 'persp' ? 'Perspective' : 'Orthographic';
  el.projection.setAttribute('aria-pressed', String(state.cam.proj === 'persp'));
  el.projection.dataset.value = state.cam.proj;
  syncViewButtons();
}

// Cheap enough for every pointer move: only the six view buttons follow the camera while dragging.
function syncViewButtons() {
  const active = viewName(state.cam);
  for (const b of el.viewButtons) b.setAttribute('aria-pressed', String(b.dataset.view === active));
}

// ---------- frames ----------

let rafId = 0;
let wantDraft = false;
let inflight = null; // {url, draft, controller}
let draftPending = false; // a drag moved while a draft was in flight: send another when it lands
let shownUrl = null;
let shownObjectUrl = null;
let lastFrame = null; // {w, h, frameMs}
let resizeTimer = 0;

function frameSize(draft) {
  const r = el.view.getBoundingClientRect();
  const dpr = window.devicePixelRatio || 1;
  let w = Math.max(1, Math.round(r.width * dpr));
  let h = Math.max(1, Math.round(r.height * dpr));
  const s = Math.min(1, MAX_FRAME_PX / Math.max(w, h));
  w = Math.max(1, Math.round(w * s));
  h = Math.max(1, Math.round(h * s));
  if (draft) {
    w = Math.max(8, Math.round(w / DRAFT_DIVISOR));
    h = Math.max(8, Math.round(h / DRAFT_DIVISOR));
  }
  return { w, h };
}

function frameUrl(draft) {
  return renderUrl({
    dataset: state.dataset,
    cam: formatCamera(state.cam),
    size: frameSize(draft),
    eps: renderEps,
    degree: state.degree,
    mode: state.mode,
    window: { level: fmtExact(state.window.level), width: fmtExact(state.window.width) },
    colormap: state.colormap,
    client: CLIENT_ID,
  });
}

// Asks for a frame on the next animation frame; several changes in one frame cost one request.
function scheduleRender({ draft = false } = {}) {
  wantDraft = draft;
  if (!rafId) rafId = requestAnimationFrame(flushRender);
  updateStatus();
}

function flushRender() {
  rafId = 0;
  if (!state.dataset || renderEps === null) return updateStatus();
  const draft = wantDraft;
  const url = frameUrl(draft);
  if (inflight) {
    if (inflight.url === url) return updateStatus();
    // While dragging, let the current draft land (so frames keep coming) and then send the newest state.
    if (draft && inflight.draft) {
      draftPending = true;
      return updateStatus();
    }
    // Anything else makes the in-flight frame stale: drop it; the server drops it too (superseded).
    inflight.controller.abort();
    inflight = null;
  }
  if (url === shownUrl) return updateStatus();
  sendFrame(url, draft);
}

async function sendFrame(url, draft) {
  const mine = { url, draft, controller: new AbortController() };
  inflight = mine;
  if (!draft) draftPending = false;
  updateStatus();
  try {
    const frame = await fetchFrame(url, mine.controller.signal);
    if (inflight !== mine) return;
    const objectUrl = URL.createObjectURL(frame.blob);
    const probe = new Image();
    probe.src = objectUrl;
    try {
      await probe.decode();
    } catch {
      URL.revokeObjectURL(objectUrl);
      throw new ApiError('Rendering: the server sent an image the browser cannot decode');
    }
    if (inflight !== mine) {
      URL.revokeObjectURL(objectUrl);
      return;
    }
    el.image.src = objectUrl;
    el.image.dataset.quality = draft ? 'draft' : 'full';
    el.image.dataset.frameUrl = url;
    el.image.dataset.width = String(probe.naturalWidth);
    el.image.dataset.height = String(probe.naturalHeight);
    if (shownObjectUrl) URL.revokeObjectURL(shownObjectUrl);
    shownObjectUrl = objectUrl;
    shownUrl = url;
    lastFrame = { w: probe.naturalWidth, h: probe.naturalHeight, frameMs: frame.frameMs };
    if (frame.votCount !== null) el.votCount.textContent = fmtCount(frame.votCount);
    if (frame.fitSeconds !== null) el.fitTime.textContent = fmtSeconds(frame.fitSeconds);
    clearError('render');
  } catch (e) {
    if (inflight !== mine) return;
    if (!(e instanceof ApiError && e.isIgnorable)) showError(e.message, 'render');
  } finally {
    if (inflight === mine) {
      inflight = null;
      if (draftPending) {
        draftPending = false;
        scheduleRender({ draft: dragging !== null || wheelTimer !== 0 });
      }
    }
    updateStatus();
  }
}

// ---------- fits ----------

let fitToken = 0;
let fitFollow = null;
let fitting = null; // {eps, progress, stage}

function setProgress(progress, stage) {
  const p = Math.min(1, Math.max(0, Number(progress) || 0));
  fitting.progress = p;
  fitting.stage = stage || fitting.stage;
  el.progress.value = p;
  el.progressLabel.textContent = `${Math.round(p * 100)} %${fitting.stage ? ` ${fitting.stage}` : ''}`;
  updateStatus();
}

// Starts (or joins) the fit for state.eps; frames keep the old eps until it is done, then swap.
async function ensureFitted() {
  const name = state.dataset;
  const eps = state.eps;
  if (fitFollow) fitFollow.cancel();
  fitFollow = null;
  if (isFitted(name, eps)) {
    fitting = null;
    el.fitProgress.hidden = true;
    renderEps = eps;
    scheduleRender();
    return;
  }
  const token = ++fitToken;
  fitting = { eps, progress: 0, stage: 'queued' };
  el.fitProgress.hidden = false;
  setProgress(0, 'queued');
  try {
    const job = await startFit({ dataset: name, eps, degree: state.degree });
    if (token !== fitToken) return;
    let result = job;
    if (job.state !== 'done') {
      fitFollow = followJob(job.job, (p) => {
        if (token === fitToken) setProgress(p.progress, p.stage);
      });
      result = await fitFollow.done;
      if (token !== fitToken) return;
    }
    markFitted(name, eps);
    if (Number.isFinite(Number(result.votCount))) el.votCount.textContent = fmtCount(Number(result.votCount));
    if (Number.isFinite(Number(result.fitSeconds))) el.fitTime.textContent = fmtSeconds(Number(result.fitSeconds));
    clearError('fit');
    renderEps = eps;
    scheduleRender();
  } catch (e) {
    if (token !== fitToken) return;
    showError(e.message, 'fit');
  } finally {
    if (token === fitToken) {
      fitting = null;
      fitFollow = null;
      el.fitProgress.hidden = true;
      updateStatus();
    }
  }
}

// ---------- status line ----------

function updateStatus() {
  let s;
  let text;
  if (!datasets.length) {
    s = errorSource ? 'error' : 'loading';
    text = errorSource ? 'No datasets.' : 'Loading datasets…';
  } else if (fitting) {
    s = 'fitting';
    text = `Fitting ε = ${fmtValue(fitting.eps)}: ${Math.round(fitting.progress * 100)} % ${fitting.stage || ''}`;
  } else if (inflight || rafId || resizeTimer || draftPending) {
    s = 'rendering';
    text = 'Rendering…';
  } else if (errorSource && !shownUrl) {
    s = 'error';
    text = 'Error (see banner).';
  } else {
    s = 'idle';
    const c = state.cam;
    const size = lastFrame ? `${lastFrame.w}×${lastFrame.h} px` : '';
    const ms = lastFrame && Number.isFinite(lastFrame.frameMs) ? ` · ${Math.round(lastFrame.frameMs)} ms/frame` : '';
    text = `${size}${ms} · az ${fmtValue(c.az)}° el ${fmtValue(c.el)}° zoom ${fmtValue(c.zoom)} · ${c.proj}`;
  }
  el.status.dataset.state = s;
  el.status.textContent = text;
}

// ---------- user actions ----------

function commit({ refit = false } = {}) {
  writeHash();
  syncControls();
  if (refit) ensureFitted();
  else scheduleRender();
}

el.dataset.addEventListener('change', () => {
  const ds = datasets.find((d) => d.name === el.dataset.value);
  if (!ds) return;
  state.dataset = ds.name;
  state.cam = { ...DEFAULT_CAMERA, proj: state.cam.proj, fov: state.cam.fov };
  state.window = { level: Number(ds.window.level), width: Number(ds.window.width) };
  state.eps = Number(ds.defaultEps);
  fillPresets(ds);
  clearError('link');
  renderEps = null;
  commit({ refit: true });
});

el.mode.addEventListener('change', () => {
  state.mode = el.mode.value;
  commit();
});

el.colormap.addEventListener('change', () => {
  state.colormap = el.colormap.value;
  commit();
});

el.preset.addEventListener('change', () => {
  const w = presetWindow(currentDataset(), el.preset.value);
  if (!w) return syncControls(); // 'custom' only means "what the inputs say"
  state.window = { level: Number(w.level), width: Number(w.width) };
  commit();
});

function onWindowInput() {
  const level = Number(el.level.value);
  const width = Number(el.width.value);
  if (el.level.value === '' || !Number.isFinite(level) || !(width > 0)) {
    showError('Window: level must be a number and width a positive number.', 'input');
    return syncControls();
  }
  clearError('input');
  state.window = { level, width };
  commit();
}
el.level.addEventListener('change', onWindowInput);
el.width.addEventListener('change', onWindowInput);

el.epsSlider.addEventListener('input', () => {
  const ds = currentDataset();
  if (ds) el.epsValue.textContent = epsLabel(ds, sliderToEps(ds, Number(el.epsSlider.value)));
});

el.epsSlider.addEventListener('change', () => {
  const ds = currentDataset();
  if (!ds) return;
  state.eps = sliderToEps(ds, Number(el.epsSlider.value));
  commit({ refit: true });
});

for (const b of el.viewButtons) {
  b.addEventListener('click', () => {
    state.cam = toView(state.cam, b.dataset.view);
    commit();
  });
}

el.projection.addEventListener('click', () => {
  state.cam = { ...state.cam, proj: state.cam.proj === 'persp' ? 'ortho' : 'persp' };
  commit();
});

// ---------- mouse: VTK trackball habits ----------

let dragging = null; // {kind: 'orbit'|'pan'|'zoom', x, y, pointerId}

el.view.addEventListener('contextmenu', (e) => e.preventDefault());

el.view.addEventListener('pointerdown', (e) => {
  if (e.target.closest('#error')) return;
  let kind = null;
  if (e.button === 0) kind = e.shiftKey ? 'pan' : 'orbit';
  else if (e.button === 1) kind = 'pan';
  else if (e.button === 2) kind = 'zoom';
  if (!kind) return;
  e.preventDefault(); // no middle-click autoscroll, no text selection
  el.view.setPointerCapture(e.pointerId);
  el.view.classList.add('dragging');
  dragging = { kind, x: e.clientX, y: e.clientY, pointerId: e.pointerId };
});

el.view.addEventListener('pointermove', (e) => {
  if (!dragging || e.pointerId !== dragging.pointerId) return;
  const dx = e.clientX - dragging.x;
  const dy = e.clientY - dragging.y;
  if (dx === 0 && dy === 0) return;
  dragging.x = e.clientX;
  dragging.y = e.clientY;
  const r = el.view.getBoundingClientRect();
  if (dragging.kind === 'orbit') state.cam = orbit(state.cam, dx, dy, r.width, r.height);
  else if (dragging.kind === 'pan') state.cam = pan(state.cam, dx, dy, r.height);
  else state.cam = zoomBy(state.cam, dy * 2);
  writeHash({ now: false });
  syncViewButtons();
  scheduleRender({ draft: true });
});

function endDrag(e) {
  if (!dragging || e.pointerId !== dragging.pointerId) return;
  dragging = null;
  el.view.classList.remove('dragging');
  commit();
}
el.view.addEventListener('pointerup', endDrag);
el.view.addEventListener('pointercancel', endDrag);

let wheelTimer = 0;
el.view.addEventListener('wheel', (e) => {
  e.preventDefault();
  const lines = e.deltaMode === 1 ? 33 : e.deltaMode === 2 ? 400 : 1;
  state.cam = zoomBy(state.cam, e.deltaY * lines);
  writeHash({ now: false });
  scheduleRender({ draft: true });
  clearTimeout(wheelTimer);
  wheelTimer = setTimeout(() => {
    wheelTimer = 0;
    commit();
  }, WHEEL_SETTLE_MS);
}, { passive: false });

document.addEventListener('keydown', (e) => {
  if (e.target.closest('input, select, textarea') || e.ctrlKey || e.metaKey || e.altKey) return;
  if (e.key === 'r' || e.key === 'R') {
    state.cam = { ...DEFAULT_CAMERA, proj: state.cam.proj, fov: state.cam.fov };
    commit();
  }
});

new ResizeObserver(() => {
  clearTimeout(resizeTimer);
  resizeTimer = setTimeout(() => {
    resizeTimer = 0;
    scheduleRender();
  }, 100);
  updateStatus();
}).observe(el.view);

// A pasted or edited link changes the hash without a reload: adopt it.
window.addEventListener('hashchange', () => {
  if (!datasets.length || location.hash === hashText()) return;
  const before = state.dataset;
  applyHash();
  if (state.dataset !== before) fillPresets(currentDataset());
  writeHash();
  syncControls();
  ensureFitted();
});

// ---------- start ----------

async function start() {
  updateStatus();
  try {
    datasets = await fetchDatasets();
  } catch (e) {
    showError(e.message, 'datasets');
    return;
  }
  if (!datasets.length) {
    showError('The server has no datasets to show.', 'datasets');
    return;
  }
  fillDatasetPicker();
  applyHash();
  fillPresets(currentDataset());
  writeHash();
  syncControls();
  ensureFitted();
}

start();
