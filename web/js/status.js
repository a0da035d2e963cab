// The status line's state and text from what the viewer is doing; no DOM.
import { fmtValue } from './format.js';

// fitting: {eps, progress, stage} or null; previewing: the frames come from the grid while the fit runs;
// lastFrame: {w, h, frameMs, draftEps} or null; draftEps: the eps of the coarser fit a draft came from.
export function statusLine({ hasDatasets, errorShown, fitting, previewing, rendering, frameShown, lastFrame, cam }) {
  if (!hasDatasets) {
    return errorShown ? { state: 'error', text: 'No datasets.' } : { state: 'loading', text: 'Loading datasets…' };
  }
  if (fitting) {
    return {
      state: 'fitting',
      text: `Fitting ε = ${fmtValue(fitting.eps)}: ${Math.round(fitting.progress * 100)} % ${fitting.stage || ''}` +
        (previewing ? ' · exact grid shown meanwhile' : ''),
    };
  }
  if (rendering) return { state: 'rendering', text: 'Rendering…' };
  if (errorShown && !frameShown) return { state: 'error', text: 'Error (see banner).' };
  const size = lastFrame ? `${lastFrame.w}×${lastFrame.h} px` : '';
  const ms = lastFrame && Number.isFinite(lastFrame.frameMs) ? ` · ${Math.round(lastFrame.frameMs)} ms/frame` : '';
  const draft = lastFrame && Number.isFinite(lastFrame.draftEps) ? ` · draft ε ${fmtValue(lastFrame.draftEps)}` : '';
  return {
    state: 'idle',
    text: `${size}${ms}${draft} · az ${fmtValue(cam.az)}° el ${fmtValue(cam.el)}° zoom ${fmtValue(cam.zoom)} · ${cam.proj}`,
  };
}
