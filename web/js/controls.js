// The panel's controls from the view: choice lists, dataset picker, window presets, window inputs, eps slider, projection, views.
import { viewName } from './camera.js';
import { COLORMAPS, MODES, PROJECTIONS, RENDERERS } from './contract.js';
import { setAttr } from './dom.js';
import { epsLabel, epsToSlider, sliderMax } from './eps.js';
import { fmtExact, fmtValue } from './format.js';
import { syncKindLimits } from './kind.js';

const PRESET_LABELS = { bone: 'Bone', soft: 'Soft tissue', full: 'Full range' };
const MODE_LABELS = { mip: 'MIP', minip: 'MinIP', aip: 'Average', density: 'Vot density' };
const RENDERER_LABELS = { vots: 'Vots', grid: 'Grid reference' };
const COLORMAP_LABELS = { grey: 'Grey', bone: 'Bone', hot: 'Hot', viridis: 'Viridis' };

// The mode, renderer and colour map lists hold the names the server takes (contract.js, generated from its
// C++); a name without a label here shows as it is.
export function fillChoices(el) {
  const fill = (select, names, labels) => select.replaceChildren(...names.map((n) => new Option(labels[n] || n, n)));
  fill(el.mode, MODES, MODE_LABELS);
  fill(el.renderer, RENDERERS, RENDERER_LABELS);
  fill(el.colormap, COLORMAPS, COLORMAP_LABELS);
}

// A dataset the server's memory budget refuses ("fits": false) is listed, disabled, with the reason.
export function fillDatasetPicker(select, datasets) {
  select.replaceChildren(...datasets.map((d) => {
    if (d.fits !== false) return new Option(d.name, d.name);
    const gb = Number(d.memoryNeeded) / 2 ** 30;
    const needs = Number.isFinite(gb) ? `needs ${gb >= 10 ? gb.toFixed(0) : gb.toFixed(1)} GB, ` : '';
    const option = new Option(`${d.name} (${needs}too large for the server's memory)`, d.name);
    option.disabled = true;
    option.title = d.error || '';
    return option;
  }));
}

export function fillPresets(select, ds) {
  const opts = [];
  for (const key of Object.keys(ds.presets || {})) opts.push(new Option(PRESET_LABELS[key] || key, key));
  // The dataset's own window gets an entry only when no named preset already is that window.
  const same = (a, b) => a && b && Number(a.level) === Number(b.level) && Number(a.width) === Number(b.width);
  if (!Object.values(ds.presets || {}).some((p) => same(p, ds.window))) {
    opts.unshift(new Option('Dataset default', 'default'));
  }
  opts.push(new Option('Custom', 'custom'));
  select.replaceChildren(...opts);
}

// The window a preset entry stands for; null for 'custom'.
export function presetWindow(ds, key) {
  if (key === 'default') return ds.window;
  return (ds.presets || {})[key] || null;
}

function matchingPreset(select, ds, window) {
  const same = (w) => w && Math.abs(w.level - window.level) < 1e-6 && Math.abs(w.width - window.width) < 1e-6;
  for (const o of select.options) {
    if (o.value !== 'custom' && same(presetWindow(ds, o.value))) return o.value;
  }
  return 'custom';
}

// el: the panel's elements (ui.js looks them up); ds: the view's dataset.
export function syncControls(el, ds, view) {
  el.dataset.value = ds.name;
  el.datasetMeta.textContent = `${ds.dims.join('×')} · ${ds.modality || 'other'} · range ${fmtValue(ds.range[0])}..${fmtValue(ds.range[1])}`;
  el.mode.value = view.mode;
  el.renderer.value = view.renderer;
  el.colormap.value = view.colormap;
  el.preset.value = matchingPreset(el.preset, ds, view.window);
  el.level.value = fmtExact(view.window.level);
  el.width.value = fmtExact(view.window.width);
  el.epsSlider.max = String(sliderMax(ds));
  el.epsSlider.value = String(epsToSlider(ds, view.eps));
  el.epsValue.textContent = epsLabel(ds, view.eps);
  syncKindLimits(el, ds);
  const persp = view.cam.proj === PROJECTIONS.persp;
  el.projection.textContent = persp ? 'Perspective' : 'Orthographic';
  el.projection.setAttribute('aria-pressed', String(persp));
  el.projection.dataset.value = view.cam.proj;
  syncViewButtons(el.viewButtons, view.cam);
}

// Cheap enough for every pointer move: only the six view buttons follow the camera while dragging.
export function syncViewButtons(buttons, cam) {
  const active = viewName(cam);
  for (const b of buttons) setAttr(b, 'aria-pressed', String(b.dataset.view === active));
}
