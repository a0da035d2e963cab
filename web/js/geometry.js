// The volume's box in the world as the server's camera sees it (render/src/Camera.cpp): its extent
// along the view, and how many mm the image height spans; no DOM, no network.
import { PROJECTIONS } from './contract.js';

const IDENTITY = [
  [1, 0, 0],
  [0, 1, 0],
  [0, 0, 1],
];

// Grid axis a in the world (LPS): the dataset's orientation, or index space taken as LPS without one.
function axesOf(ds) {
  return ds?.orientation?.axes ?? IDENTITY;
}

// The box's edge along grid axis a in mm; a flat axis counts as one spacing, as the server's bounds do.
function edgeMm(ds, a) {
  return Number(ds.spacing?.[a] ?? 1) * Math.max(Number(ds.dims[a]) - 1, 1);
}

// The direction the camera looks along (from the eye into the scene) for {az, el} in degrees.
export function viewDirection(cam) {
  const az = (cam.az * Math.PI) / 180;
  const el = (cam.el * Math.PI) / 180;
  return [-Math.sin(az) * Math.cos(el), Math.cos(az) * Math.cos(el), -Math.sin(el)];
}

// Half the box's depth along the view, in mm: a slab offset beyond it cuts nothing of the volume.
export function halfDepthAlongView(ds, cam) {
  const f = viewDirection(cam);
  const axes = axesOf(ds);
  let sum = 0;
  for (let a = 0; a < 3; a++) {
    const along = axes[a][0] * f[0] + axes[a][1] * f[1] + axes[a][2] * f[2];
    sum += Math.abs(along) * edgeMm(ds, a);
  }
  return sum / 2;
}

// The radius of the sphere round the box's world bounds, which zoom 1 fits into the image height.
export function sceneRadius(ds) {
  const axes = axesOf(ds);
  let sq = 0;
  for (let c = 0; c < 3; c++) {
    let width = 0;
    for (let a = 0; a < 3; a++) width += Math.abs(axes[a][c]) * edgeMm(ds, a);
    sq += width * width;
  }
  return Math.sqrt(sq) / 2;
}

// The mm the image height spans: exact for ortho; for perspective, in the plane through the volume's
// centre facing the camera (nearer things look bigger, farther ones smaller).
export function imageHeightMm(ds, cam) {
  const r = sceneRadius(ds);
  if (cam.proj !== PROJECTIONS.persp) return (2 * r) / cam.zoom;
  const halfFov = ((cam.fov * Math.PI) / 180) / 2;
  return (2 * r) / (cam.zoom * Math.cos(halfFov));
}
