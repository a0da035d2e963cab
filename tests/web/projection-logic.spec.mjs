// Unit checks of the projection tools' DOM-free modules: mode, renderer and slab in the hash, the slab's
// depth along the view, the scale bar's mm per pixel, the colour bar's units, oblique edge labels.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadWebModules } from './support/web-modules.mjs';

const m = await loadWebModules(['hash.js', 'view.js', 'geometry.js', 'slab.js', 'scalebar.js', 'colorbar.js',
  'orientation.js']);
const { formatHash, parseHash } = m['hash.js'];
const { initialView, reconcileRenderer } = m['view.js'];
const { halfDepthAlongView, imageHeightMm, sceneRadius } = m['geometry.js'];
const { clampSlabToView, parseSlab } = m['slab.js'];
const { roundDown125, scaleBarOf } = m['scalebar.js'];
const { colorbarOf } = m['colorbar.js'];
const { edgeLabels } = m['orientation.js'];

// The Cranium's grid as /api/datasets would give it without its patient axes (index space).
const CRANIUM = {
  name: 'cranium', modality: 'CT', range: [-1024, 2986], defaultEps: 80, dims: [256, 256, 108],
  spacing: [0.9570312, 0.9570312, 1.5], orientation: null, window: { level: 981, width: 4010 }, presets: {},
};
const LPS = { axes: [[1, 0, 0], [0, 1, 0], [0, 0, 1]], directions: ['L', 'P', 'S'] };
const cam = (c) => ({ az: 0, el: 0, zoom: 1, panX: 0, panY: 0, proj: 'ortho', fov: 30, ...c });
const near = (a, b, what, tol = 1e-9) => assert.ok(Math.abs(a - b) <= tol * Math.max(1, Math.abs(b)), `${what}: ${a} vs ${b}`);

test('mode, renderer and slab go into the hash and back; defaults stay out of it', () => {
  const view = { ...initialView(), dataset: 'cranium', eps: 80, mode: 'minip', renderer: 'grid',
    slab: { offset: -12.5, thickness: 20 }, window: { level: -500, width: 1000 } };
  const text = formatHash(view);
  assert.match(text, /&mode=minip&renderer=grid&slab=-12\.5,20&window=/);
  const { view: back, problems } = parseHash(text, [CRANIUM], initialView());
  assert.deepEqual(problems, []);
  assert.deepEqual(back, view);
  const plain = formatHash({ ...view, mode: 'aip', renderer: 'vots', slab: null });
  assert.doesNotMatch(plain, /renderer=|slab=/);
  assert.match(plain, /&mode=aip&/);
});

test('an old link\'s mode=reference is MIP on the grid; bad renderer and slab fall back and are named', () => {
  const ref = parseHash('#dataset=cranium&mode=reference', [CRANIUM], initialView()).view;
  assert.equal(ref.mode, 'mip');
  assert.equal(ref.renderer, 'grid');
  const bad = parseHash('#dataset=cranium&renderer=gpu&slab=3,0', [CRANIUM], initialView());
  assert.equal(bad.view.renderer, 'vots');
  assert.equal(bad.view.slab, null);
  assert.equal(bad.problems.length, 2);
  assert.match(bad.problems.join(' '), /renderer 'gpu'/);
  assert.match(bad.problems.join(' '), /slab '3,0'/);
  assert.equal(parseSlab('1,2,3'), null);
  assert.equal(parseSlab('x,2'), null);
  assert.deepEqual(parseSlab('-4.5,7'), { offset: -4.5, thickness: 7 });
  // Density is Vot sizes: a link asking for it on the grid gets the Vots.
  assert.equal(parseHash('#dataset=cranium&mode=density&renderer=grid', [CRANIUM], initialView()).view.renderer, 'vots');
});

test('density and the grid exclude each other: the choice made last wins', () => {
  const a = { mode: 'density', renderer: 'grid' };
  reconcileRenderer(a, 'renderer');
  assert.deepEqual(a, { mode: 'mip', renderer: 'grid' });
  const b = { mode: 'density', renderer: 'grid' };
  reconcileRenderer(b, 'mode');
  assert.deepEqual(b, { mode: 'density', renderer: 'vots' });
  const c = { mode: 'aip', renderer: 'grid' };
  reconcileRenderer(c, 'mode');
  assert.deepEqual(c, { mode: 'aip', renderer: 'grid' });
});

test('the slab slider spans the volume\'s depth along the view, and the slab stays inside it as the camera turns', () => {
  near(halfDepthAlongView(CRANIUM, cam({})), (255 * 0.9570312) / 2, 'anterior: depth along y');
  near(halfDepthAlongView(CRANIUM, cam({ el: 90 })), (107 * 1.5) / 2, 'superior: depth along z');
  near(halfDepthAlongView(CRANIUM, cam({ az: 90 })), (255 * 0.9570312) / 2, 'left: depth along x');
  const d = Math.SQRT1_2 * 255 * 0.9570312; // az 45: x and y both count
  near(halfDepthAlongView(CRANIUM, cam({ az: 45 })), d, 'az 45');
  // An oriented volume whose grid x is the patient's y: the depth follows the patient axes.
  const swapped = { ...CRANIUM, dims: [100, 50, 20], spacing: [1, 1, 1],
    orientation: { axes: [[0, 1, 0], [1, 0, 0], [0, 0, 1]] } };
  near(halfDepthAlongView(swapped, cam({})), 99 / 2, 'anterior on a swapped grid');
  const slab = { offset: 100, thickness: 10 };
  assert.equal(clampSlabToView(slab, CRANIUM, cam({})), slab, 'inside: unchanged');
  assert.deepEqual(clampSlabToView(slab, CRANIUM, cam({ el: 90 })), { offset: 80.2, thickness: 10 });
  assert.deepEqual(clampSlabToView({ offset: -100, thickness: 3 }, CRANIUM, cam({ el: -90 })), { offset: -80.2, thickness: 3 });
});

test('the scale bar: the image height in mm is exact for ortho and at the centre\'s depth for perspective', () => {
  const r = sceneRadius(CRANIUM);
  near(r, 0.5 * Math.hypot(255 * 0.9570312, 255 * 0.9570312, 107 * 1.5), 'radius of the box');
  near(imageHeightMm(CRANIUM, cam({ zoom: 2 })), r, 'ortho zoom 2');
  // Perspective: the eye sits where the sphere fits the fov (render/src/Camera.cpp), at distance
  // r / (zoom sin(fov/2)); the image height at that depth is 2 distance tan(fov/2).
  const half = (40 * Math.PI) / 360;
  const distance = r / (1.5 * Math.sin(half));
  near(imageHeightMm(CRANIUM, cam({ proj: 'persp', fov: 40, zoom: 1.5 })), 2 * distance * Math.tan(half), 'persp');

  assert.equal(roundDown125(7.3), 5);
  assert.equal(roundDown125(19.99), 10);
  assert.equal(roundDown125(2), 2);
  near(roundDown125(0.031), 0.02, '0.031');
  const bar = scaleBarOf(CRANIUM, cam({}), 700);
  const mmPerPx = imageHeightMm(CRANIUM, cam({})) / 700;
  near(bar.px * mmPerPx, bar.mm, 'bar width times mm per pixel');
  assert.ok(bar.px <= 120 && bar.px > 120 / 2.5, `bar ${bar.px} px`);
  assert.equal(bar.label, '5 cm'); // 120 px are 65 mm at zoom 1 in a 700 px view
  assert.equal(scaleBarOf(CRANIUM, cam({ zoom: 4 }), 700).label, '1 cm');
  assert.equal(scaleBarOf(CRANIUM, cam({ zoom: 8 }), 700).label, '5 mm');
  assert.equal(scaleBarOf(CRANIUM, cam({ zoom: 80 }), 700).label, '0.5 mm');
  // In perspective the bar holds at the volume's centre only, and its label says so.
  const persp = scaleBarOf(CRANIUM, cam({ proj: 'persp', fov: 30 }), 700);
  near(persp.px * (imageHeightMm(CRANIUM, cam({ proj: 'persp', fov: 30 })) / 700), persp.mm, 'persp bar');
  assert.equal(persp.label, `${persp.mm / 10} cm at centre`);
});

test('the colour bar gives the window\'s ends in HU for CT and no unit for the density view', () => {
  const view = { window: { level: 40, width: 400 }, colormap: 'hot', mode: 'minip' };
  const bar = colorbarOf(view, CRANIUM);
  assert.deepEqual([bar.low, bar.high, bar.unit], [-160, 240, 'HU']);
  // 16 evenly spaced stops of the server's table: black, then hot's pure red at a third (entry 85).
  assert.match(bar.gradient, /^linear-gradient\(to top, #000000, (#[0-9a-f]{6}, ){4}#ff0000, (#[0-9a-f]{6}, ){9}#ffffff\)$/);
  assert.equal(colorbarOf({ ...view, mode: 'density' }, CRANIUM).unit, '');
  assert.equal(colorbarOf(view, { ...CRANIUM, modality: 'other' }).unit, '');
  assert.equal(colorbarOf(view, { ...CRANIUM, modality: 'other', units: 'a.u.' }).unit, 'a.u.');
});

test('oblique views get two letters, the larger component first, as radiology viewers show them', () => {
  assert.equal(edgeLabels(cam({ az: -45 }), LPS).right, 'LA');
  assert.equal(edgeLabels(cam({ az: -30 }), LPS).right, 'LA');
  assert.equal(edgeLabels(cam({ az: -60 }), LPS).right, 'AL');
  assert.equal(edgeLabels(cam({ az: -10 }), LPS).right, 'L'); // under 22.5 degrees off: one letter
  const up = edgeLabels(cam({ az: -90, el: 30 }), LPS);
  assert.equal(up.top, 'SL');
  assert.equal(up.bottom, 'IR');
  assert.equal(edgeLabels(cam({ az: 90, el: 30 }), LPS).top, 'SR');
  assert.equal(edgeLabels(cam({ el: 60 }), LPS).bottom, 'AI');
});
