// The view the user asked for (what the URL hash holds): its allowed values and its starting state; no DOM.
import { DEFAULT_CAMERA } from './camera.js';

// Projections the viewer offers; `reference` (a link's old word for mip on the grid) is read by hash.js.
export const MODES = ['mip', 'minip', 'aip', 'density'];
export const RENDERERS = ['vots', 'grid'];
export const COLORMAPS = ['grey', 'bone', 'hot', 'viridis'];

export function initialView() {
  return {
    dataset: null, // dataset name
    cam: { ...DEFAULT_CAMERA },
    eps: null, // target error bound, data units
    degree: undefined, // only sent when the link carries one
    mode: 'mip',
    renderer: 'vots',
    slab: null, // {offset, thickness} in mm along the view direction, or null for the whole ray
    window: { level: 0, width: 1 }, // data units
    colormap: 'grey',
  };
}

// The density view shows Vot sizes, which the grid does not have (the server answers 400): whichever of
// mode and renderer the user changed last wins, the other gives way.
export function reconcileRenderer(view, changed) {
  if (view.mode !== 'density' || view.renderer !== 'grid') return;
  if (changed === 'renderer') view.mode = 'mip';
  else view.renderer = 'vots';
}

// Back to the default camera, keeping the projection the user chose (R key, a new dataset).
export function homeCamera(cam) {
  return { ...DEFAULT_CAMERA, proj: cam.proj, fov: cam.fov };
}
