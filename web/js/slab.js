// The thick slab of the view: its `slab=OFFSET,THICKNESS` text (mm) and its limits; no DOM.
import { fmtExact } from './format.js';
import { halfDepthAlongView } from './geometry.js';

export const DEFAULT_THICKNESS_MM = 10;

export function formatSlab(slab) {
  return `${fmtExact(slab.offset)},${fmtExact(slab.thickness)}`;
}

// {offset, thickness} from "OFFSET,THICKNESS", or null when it is not two finite numbers with thickness > 0.
export function parseSlab(text) {
  const parts = String(text ?? '').split(',');
  if (parts.length !== 2 || parts.some((p) => p.trim() === '')) return null;
  const [offset, thickness] = parts.map(Number);
  if (!Number.isFinite(offset) || !Number.isFinite(thickness) || !(thickness > 0)) return null;
  return { offset, thickness };
}

// The slab's middle kept inside the volume's depth along the current view, so that turning the camera
// never leaves the slab cutting nothing (a black image with no hint why).
export function clampSlabToView(slab, ds, cam) {
  if (!slab || !ds) return slab;
  const half = halfDepthAlongView(ds, cam);
  if (Math.abs(slab.offset) <= half) return slab;
  // Rounded towards the centre to 0.1 mm, so the link stays short and the slab inside.
  return { ...slab, offset: Math.sign(slab.offset) * Math.floor(half * 10) / 10 };
}
