// Patient-direction letters (L/R/A/P/S/I) for the image edges, from the camera, or grid axes (+x, -y, ...)
// for a volume whose file gives no orientation; no DOM, no network.

import { PATIENT_LETTERS } from './contract.js';

// The world is patient LPS (+x left, +y posterior, +z superior), the same as the server's camera
// (render/include/vots/render/Camera.h), whatever order the dataset stores its axes in: the letters of
// +x, +y, +z and of -x, -y, -z come from the server's C++ (contract.js).
const LETTERS = PATIENT_LETTERS;

// A component below sin(22.5 deg) of the edge direction does not get a letter: "L" up to 22.5 deg off,
// then "LA" (the larger first) the way radiology viewers label oblique views.
const MIN_COMPONENT = Math.sin(Math.PI / 8);

// Grid index axes, signed: without an orientation the server takes index space as the world.
const GRID_AXES = [
  ['+x', '−x'],
  ['+y', '−y'],
  ['+z', '−z'],
];

function namesOf(v, names) {
  return [0, 1, 2]
    .filter((c) => Math.abs(v[c]) >= MIN_COMPONENT)
    .sort((a, b) => Math.abs(v[b]) - Math.abs(v[a]))
    .slice(0, 2)
    .map((c) => names[c][v[c] > 0 ? 0 : 1])
    .join('');
}

const neg = (v) => v.map((x) => -x);

// Image right and up in the world for a camera {az, el} in degrees (the server's formulas).
export function imageAxes(cam) {
  const az = (cam.az * Math.PI) / 180;
  const el = (cam.el * Math.PI) / 180;
  const toEye = [Math.sin(az) * Math.cos(el), -Math.cos(az) * Math.cos(el), Math.sin(el)];
  const up = [-Math.sin(az) * Math.sin(el), Math.cos(az) * Math.sin(el), Math.cos(el)];
  const f = neg(toEye); // forward
  const right = [f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]];
  return { right, up };
}

// {kind, left, right, top, bottom}: kind 'patient' with letters, or 'grid' with signed index axes for a
// dataset whose file gives no orientation (its index axes are only taken as LPS, so patient letters
// would claim what nobody knows, while the axes are what the file does say).
export function edgeLabels(cam, orientation) {
  const names = orientation ? LETTERS : GRID_AXES;
  const { right, up } = imageAxes(cam);
  return {
    kind: orientation ? 'patient' : 'grid',
    left: namesOf(neg(right), names),
    right: namesOf(right, names),
    top: namesOf(up, names),
    bottom: namesOf(neg(up), names),
  };
}
