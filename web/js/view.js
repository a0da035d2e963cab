// The view the user asked for (what the URL hash holds): its allowed values and its starting state; no DOM.
import { DEFAULT_CAMERA } from './camera.js';

export const MODES = ['mip', 'density', 'reference'];
export const COLORMAPS = ['grey', 'bone', 'hot', 'viridis'];

export function initialView() {
  return {
    dataset: null, // dataset name
    cam: { ...DEFAULT_CAMERA },
    eps: null, // target error bound, data units
    degree: undefined, // only sent when the link carries one
    mode: 'mip',
    window: { level: 0, width: 1 }, // data units
    colormap: 'grey',
  };
}

// Back to the default camera, keeping the projection the user chose (R key, a new dataset).
export function homeCamera(cam) {
  return { ...DEFAULT_CAMERA, proj: cam.proj, fov: cam.fov };
}
