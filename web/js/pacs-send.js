// The PACS panel's "Send to PACS": the view's slab sweep stored back on the PACS its dataset came from.
import { viewName } from './camera.js';
import { sendSweep } from './pacs-api.js';
import { isViewerRole } from './role.js';
import { DEFAULT_THICKNESS_MM } from './slab.js';

export const DEFAULT_STEP_MM = 5;
const SWEEP_MODES = ['mip', 'minip', 'aip'];
const MODE_LABELS = { mip: 'MIP', minip: 'MinIP', aip: 'AIP' };

// The PACS a dataset was opened from: the server names it "<service>-<SeriesInstanceUID, '_' for '.'>".
export function pacsServiceOf(datasetName, serviceNames) {
  for (const name of serviceNames) {
    const rest = String(datasetName || '').startsWith(`${name}-`) ? datasetName.slice(name.length + 1) : '';
    if (/^[0-9]+(_[0-9]+)+$/.test(rest)) return name;
  }
  return null;
}

// "Drawing 3 / 12 slabs", "Storing 12 images", "Stored 12 images: MIP 10 mm / 5 mm axial".
export function sendProgressText(store) {
  if (store.state === 'drawing') return `Drawing ${store.drawn} / ${store.total} slabs`;
  if (store.state === 'storing') return `Storing ${store.total} images`;
  if (store.state === 'done') return `Stored ${store.stored} images: ${store.description}`;
  return 'Waiting…';
}

// Why the view cannot be sent as a sweep, or '' when it can.
export function sweepRefusal(params) {
  if (!SWEEP_MODES.includes(params.mode)) return 'A sweep draws MIP, MinIP or AIP.';
  if (!/proj=ortho/.test(params.cam)) return 'A sweep needs the orthographic projection.';
  return '';
}

// el: the section's elements (index.html, #pacs-send). viewParams() gives the view's /render parameters
// (frames.viewParams: null before the first fit); slab() the view's slab or null.
export function createPacsSend({ el, viewParams, slab }) {
  let services = [];
  let sending = null; // the send in flight: {done, cancel()}
  let thicknessEdited = false;

  const service = () => pacsServiceOf(viewParams()?.dataset, services);

  function showError(message) {
    el.error.textContent = message;
    el.error.hidden = !message;
  }

  function numberOf(input) {
    const v = Number(input.value);
    return input.value.trim() !== '' && Number.isFinite(v) && v > 0 ? v : null;
  }

  // Shown for a dataset opened from a PACS; says what will be sent and whether it can be.
  function sync() {
    const params = viewParams();
    const target = params && service();
    el.root.hidden = !target;
    if (!target) return;
    if (!thicknessEdited) el.thickness.value = String(slab()?.thickness ?? DEFAULT_THICKNESS_MM);
    const view = viewName(params.cam);
    el.what.textContent = `${MODE_LABELS[params.mode] || params.mode} · ${view ? `${view} view` : 'this view'} · ` +
      `${params.size.w}×${params.size.h} → ${target}`;
    const refusal = sweepRefusal(params);
    el.note.textContent = refusal;
    el.note.hidden = !refusal;
    // A viewer's token keeps it greyed (role.js): the server would refuse the store with 403.
    el.send.disabled = Boolean(sending) || Boolean(refusal) || isViewerRole();
    el.cancel.hidden = !sending;
  }

  async function send() {
    const params = viewParams();
    const target = params && service();
    if (!target) return;
    const thickness = numberOf(el.thickness);
    const step = numberOf(el.step);
    showError('');
    if (thickness === null || step === null) {
      showError('Thickness and step are numbers of mm above 0.');
      return;
    }
    const show = (store) => {
      el.progress.max = Math.max(1, store.total);
      el.progress.value = store.state === 'drawing' ? store.drawn : (store.state === 'queued' ? 0 : el.progress.max);
      el.label.textContent = sendProgressText(store);
    };
    el.progressBox.hidden = false;
    el.result.textContent = '';
    sending = sendSweep(target, {
      dataset: params.dataset,
      cam: params.cam,
      mode: params.mode,
      thickness,
      step,
      size: `${params.size.w}x${params.size.h}`,
      renderer: params.renderer,
      eps: String(params.eps),
      ...(params.degree !== undefined ? { degree: String(params.degree) } : {}),
      window: `${params.window.level},${params.window.width}`,
    }, show);
    sync();
    try {
      const done = await sending.done;
      el.progressBox.hidden = true;
      el.result.textContent = `${sendProgressText(done)} (on ${target})`;
    } catch (e) {
      el.progressBox.hidden = true;
      if (e.aborted) el.result.textContent = 'Send cancelled: nothing stored.';
      else showError(e.message);
    } finally {
      sending = null;
      sync();
    }
  }

  el.thickness.addEventListener('input', () => { thicknessEdited = true; });
  el.step.value = String(DEFAULT_STEP_MM);
  el.send.addEventListener('click', send);
  el.cancel.addEventListener('click', () => sending?.cancel());

  return {
    setServices(names) {
      services = names;
      sync();
    },
    sync,
  };
}
