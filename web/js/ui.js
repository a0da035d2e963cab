// Viewer wiring: looks up the page's elements, owns the view and the dataset list, and connects the modules.
import { adoptToken, tokenHashPart } from './access.js';
import { fetchDatasets } from './api.js';
import { toView } from './camera.js';
import { PROJECTIONS } from './contract.js';
import { createBanner } from './banner.js';
import { createCine } from './cine.js';
import { fillChoices, fillDatasetPicker, fillPresets, presetWindow, syncControls, syncViewButtons } from './controls.js';
import { setData, setText } from './dom.js';
import { syncDownloads } from './downloads.js';
import { defaultEpsOf } from './eps.js';
import { attachEpsSlider } from './eps-slider.js';
import { createFits } from './fits.js';
import { fmtCount, fmtSeconds } from './format.js';
import { createFrames } from './frames.js';
import { createHashWriter, formatHash, parseHash } from './hash.js';
import { attachInput } from './input.js';
import { watchSize } from './view-size.js';
import { fitViewToDataset, isVotsDataset } from './kind.js';
import { showOverlays } from './overlays.js';
import { attachPacsPanels } from './pacs-panels.js';
import { applyRole } from './role.js';
import { attachSlabControl } from './slab-control.js';
import { statusLine } from './status.js';
import { attachTimeControl } from './time.js';
import { homeCamera, initialView, reconcileRenderer } from './view.js';

const $ = (id) => document.getElementById(id);
const el = {
  view: $('view'),
  image: $('image'),
  draftCanvas: $('draft'),
  status: $('status'),
  error: $('error'),
  errorText: $('error-text'),
  errorClose: $('error-close'),
  dataset: $('dataset'),
  datasetMeta: $('dataset-meta'),
  mode: $('mode'),
  renderer: $('renderer'),
  slabOn: $('slab-on'),
  slabThickness: $('slab-thickness'),
  slabOffset: $('slab-offset'),
  slabOffsetValue: $('slab-offset-value'),
  cine: $('cine'),
  downloads: { png: $('download-png'), turn: $('download-turn') },
  colorbar: $('colorbar'),
  colorbarRamp: $('colorbar-ramp'),
  colorbarHigh: $('colorbar-high'),
  colorbarLow: $('colorbar-low'),
  scalebar: $('scalebar'),
  scalebarLine: $('scalebar-line'),
  scalebarLabel: $('scalebar-label'),
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
  edgeLabels: [...document.querySelectorAll('[data-edge]')],
};

let datasets = [];
const view = initialView(); // what the user asked for; this is what the URL hash holds

const findDataset = (name) => datasets.find((d) => d.name === name) || null;
const currentDataset = () => findDataset(view.dataset);

// Vot count and fit time of the latest frame or fit; undefined leaves a fact as it is.
function showFacts({ votCount, fitSeconds }) {
  if (votCount !== undefined) setText(el.votCount, fmtCount(votCount));
  if (fitSeconds !== undefined) setText(el.fitTime, fmtSeconds(fitSeconds));
}

const banner = createBanner({ box: el.error, text: el.errorText, closeButton: el.errorClose, onShow: updateStatus });
const viewHash = () => formatHash(view) + tokenHashPart(); // the token stays for reloads and copied links
const writeHash = createHashWriter(viewHash);
const viewSize = watchSize(el.view);
const input = attachInput({
  viewEl: el.view,
  viewSize,
  keyTarget: document,
  view,
  onDraft() {
    cine.stop(); // any orbit of the user's own ends the turn
    draft();
  },
  onCommit() {
    cine.stop();
    commit();
  },
});

// A change while a gesture goes on: the hash throttled, a draft frame; the overlays follow the frames shown.
function draft() {
  slabControl.sync(); // first: it keeps the slab inside the volume, which the hash then says
  writeHash({ now: false });
  syncViewButtons(el.viewButtons, view.cam);
  frames.schedule({ draft: true });
}
const frames = createFrames({
  viewEl: el.view, viewSize, image: el.image, draftCanvas: el.draftCanvas, view, banner, showFacts, isMoving: input.isMoving, onChange: updateStatus,
});
const fits = createFits({
  progress: { box: el.fitProgress, bar: el.progress, label: el.progressLabel },
  banner,
  showFacts,
  onStart(eps) {
    frames.previewWhileFitting(eps);
  },
  onReady(eps, { refitted = false } = {}) {
    frames.useEps(eps, { refitted });
    syncDownloads(el.downloads, frames.viewParams());
    pacsSend.sync();
    frames.schedule();
  },
  onChange: updateStatus,
});

function updateStatus() {
  const { state, text } = statusLine({
    hasDatasets: datasets.length > 0,
    errorShown: banner.source() !== null,
    fitting: fits.fitting(),
    previewing: frames.previewing(),
    rendering: frames.busy(),
    frameShown: frames.hasShownFrame(),
    lastFrame: frames.lastFrame(),
    cam: view.cam,
  });
  setData(el.status, 'state', state);
  setText(el.status, text);
}

const slabControl = attachSlabControl({
  el, view, dataset: currentDataset, banner, onDraft: draft, onCommit: () => commit(),
});

// Cine frames are full frames (the server caches them for the next turn), with the hash throttled.
const cine = createCine({
  view,
  frames,
  onStep() {
    slabControl.sync();
    writeHash({ now: false });
    syncViewButtons(el.viewButtons, view.cam);
    showViewOverlays();
    frames.schedule();
  },
  onChange(running) {
    if (running) time.stop(); // one cine at a time
    if (!running) writeHash(); // the throttled write of the last step may still wait: the link is now
    el.cine.setAttribute('aria-pressed', String(running));
    el.cine.textContent = running ? 'Stop cine' : 'Cine';
  },
});

// A 4D dataset's volume: shown as a new dataset's is, the exact grid while its fit runs.
const time = attachTimeControl({
  el: { box: $('time'), slider: $('frame-slider'), value: $('frame-value'), cine: $('time-cine') },
  view,
  dataset: currentDataset,
  busy: () => frames.busy() || fits.fitting() !== null,
  showFrame() {
    frames.useEps(null);
    commit({ refit: true });
  },
  stopTurn: () => cine.stop(),
});

// The labels and bars of the frame on screen, not of a camera the hand has moved on from.
el.image.addEventListener('vots:frame', (e) => showOverlays(el, e.detail.view, currentDataset()));

function showViewOverlays() {
  showOverlays(el, view, currentDataset());
  syncDownloads(el.downloads, frames.viewParams());
}

function syncPanel() {
  const ds = currentDataset();
  if (ds) syncControls(el, ds, view);
  time.sync();
  slabControl.sync();
  showViewOverlays();
  pacsSend.sync();
}

function ensureFitted() {
  fits.ensure({ dataset: view.dataset, frame: view.frame, eps: view.eps, degree: view.degree, fixedEps: isVotsDataset(currentDataset()) });
}

// Adopts the URL hash into the view; problems with the link go to the banner.
function applyHash() {
  const { view: linked, problems } = parseHash(location.hash, datasets, view);
  Object.assign(view, linked);
  fitViewToDataset(view, currentDataset()); // a link cannot ask a .vots dataset for what it cannot draw
  if (problems.length) banner.show(problems.join(' '), 'link');
  else banner.clear('link');
}

// ---------- user actions ----------

const epsSlider = attachEpsSlider({
  slider: el.epsSlider,
  label: el.epsValue,
  currentDataset,
  view,
  refit: () => commit({ refit: true }),
});

function commit({ refit = false } = {}) {
  // A keyboard step still settling is part of what the user chose: a commit now takes it along.
  refit = epsSlider.takeSettling() || refit;
  syncPanel(); // before the hash: the slab may have been moved back inside the volume
  writeHash();
  if (refit) ensureFitted();
  else frames.schedule();
}

el.dataset.addEventListener('change', () => {
  const ds = findDataset(el.dataset.value);
  if (!ds) return;
  epsSlider.cancel(); // a step on the old dataset's slider means nothing for the new one
  view.dataset = ds.name;
  view.frame = 0;
  view.cam = homeCamera(view.cam);
  view.window = { level: Number(ds.window.level), width: Number(ds.window.width) };
  view.eps = defaultEpsOf(ds);
  fitViewToDataset(view, ds);
  fillPresets(el.preset, ds);
  banner.clear('link');
  frames.useEps(null);
  commit({ refit: true });
});

el.mode.addEventListener('change', () => {
  view.mode = el.mode.value;
  reconcileRenderer(view, 'mode');
  commit();
});

el.renderer.addEventListener('change', () => {
  view.renderer = el.renderer.value;
  reconcileRenderer(view, 'renderer');
  commit();
});

el.cine.addEventListener('click', () => cine.toggle());

window.addEventListener('resize', showViewOverlays); // the scale bar's mm per pixel follows the view's size

el.colormap.addEventListener('change', () => {
  view.colormap = el.colormap.value;
  commit();
});

el.preset.addEventListener('change', () => {
  const w = presetWindow(currentDataset(), el.preset.value);
  if (!w) return syncPanel(); // 'custom' only means "what the inputs say"
  view.window = { level: Number(w.level), width: Number(w.width) };
  commit();
});

function onWindowInput() {
  const level = Number(el.level.value);
  const width = Number(el.width.value);
  if (el.level.value === '' || !Number.isFinite(level) || !(width > 0)) {
    banner.show('Window: level must be a number and width a positive number.', 'input');
    return syncPanel();
  }
  banner.clear('input');
  view.window = { level, width };
  commit();
}
el.level.addEventListener('change', onWindowInput);
el.width.addEventListener('change', onWindowInput);

for (const b of el.viewButtons) {
  b.addEventListener('click', () => {
    cine.stop();
    view.cam = toView(view.cam, b.dataset.view);
    commit();
  });
}

el.projection.addEventListener('click', () => {
  cine.stop();
  view.cam = { ...view.cam, proj: view.cam.proj === PROJECTIONS.persp ? PROJECTIONS.ortho : PROJECTIONS.persp };
  commit();
});

// A pasted or edited link changes the hash without a reload: adopt it.
window.addEventListener('hashchange', () => {
  if (!datasets.length || location.hash === viewHash()) return;
  adoptToken(location.hash);
  epsSlider.cancel(); // the link says what the view is now
  const before = view.dataset;
  applyHash();
  if (view.dataset !== before) fillPresets(el.preset, currentDataset());
  cine.stop(); // the link says where the camera is
  syncPanel();
  writeHash();
  ensureFitted();
});

// The server's datasets, all of them, with `datasets` set to those that can be opened: the ones over the
// server's memory budget are listed (disabled, with the reason) but never opened. Null, with the banner
// shown, when the list cannot be fetched.
async function listDatasets() {
  let listed;
  try {
    listed = await fetchDatasets();
  } catch (e) {
    banner.show(e.message, 'datasets');
    return null;
  }
  datasets = listed.filter((d) => d.fits !== false);
  return listed;
}

// A PACS series the study browser opened is a dataset now: list it and show it as if picked.
async function showOpenedDataset(name) {
  const listed = await listDatasets();
  if (!listed) return;
  fillDatasetPicker(el.dataset, listed);
  banner.clear('datasets');
  el.dataset.value = name;
  el.dataset.dispatchEvent(new Event('change'));
}

const { pacsSend, studyBrowser } = attachPacsPanels({
  viewParams: () => frames.viewParams(),
  slab: () => view.slab,
  onOpened: showOpenedDataset,
});

// ---------- start ----------

async function start() {
  fillChoices(el);
  adoptToken(location.hash); // before the first request: a server beyond loopback asks for it
  applyRole([el.epsSlider, $('pacs-send-button')]);
  updateStatus();
  studyBrowser.start();
  const listed = await listDatasets();
  if (!listed) return;
  if (!datasets.length) {
    const refused = listed.find((d) => d.fits === false);
    banner.show(refused ? refused.error : 'The server has no datasets to show.', 'datasets');
    return;
  }
  fillDatasetPicker(el.dataset, listed);
  applyHash();
  fillPresets(el.preset, currentDataset());
  syncPanel();
  writeHash();
  ensureFitted();
}

start();
