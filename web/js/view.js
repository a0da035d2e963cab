// The view the user asked for (what the URL hash holds): its allowed values and its starting state; no DOM.
import { DEFAULT_CAMERA } from './camera.js';
import { COLORMAPS, DEFAULT_COLORMAP, DEFAULT_MODE, DEFAULT_RENDERER, GRID_MODES, MODES, RENDERERS } from './contract.js';

// The names the server takes (generated from its C++); an old link's mode names are read by hash.js.
export { COLORMAPS, MODES, RENDERERS };

export function initialView() {
  return {
    dataset: null, // dataset name
    frame: 0, // the 3D volume of a 4D dataset (0-based)
    cam: { ...DEFAULT_CAMERA },
    eps: null, // target error bound, data units
    degree: undefined, // only sent when the link carries one
    mode: DEFAULT_MODE,
    renderer: DEFAULT_RENDERER,
    slab: null, // {offset, thickness} in mm along the view direction, or null for the whole ray
    window: { level: 0, width: 1 }, // data units
    colormap: DEFAULT_COLORMAP,
  };
}

// The grid draws only GRID_MODES (not the density view, which shows Vot sizes the grid does not have;
// the server answers 400): whichever of mode and renderer the user changed last wins, the other gives way.
export function reconcileRenderer(view, changed) {
  if (view.renderer !== 'grid' || GRID_MODES.includes(view.mode)) return;
  if (changed === 'renderer') view.mode = DEFAULT_MODE;
  else view.renderer = DEFAULT_RENDERER;
}

// Back to the default camera, keeping the projection the user chose (R key, a new dataset).
export function homeCamera(cam) {
  return { ...DEFAULT_CAMERA, proj: cam.proj, fov: cam.fov };
}
