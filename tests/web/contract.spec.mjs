// Unit checks that the viewer's formulas agree with the tables generated from the server's C++ (web/js/contract.js).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadWebModules } from './support/web-modules.mjs';

const m = await loadWebModules(['contract.js', 'camera.js', 'geometry.js', 'orientation.js', 'colorbar.js',
  'view.js', 'hash.js']);
const contract = m['contract.js'];
const { formatCamera, normalize, parseCamera, viewName } = m['camera.js'];
const { viewDirection } = m['geometry.js'];
const { edgeLabels, imageAxes } = m['orientation.js'];
const { colorbarOf } = m['colorbar.js'];
const { initialView, reconcileRenderer } = m['view.js'];
const { parseHash } = m['hash.js'];

const near = (a, b, what) => a.forEach((v, i) => assert.ok(Math.abs(v - b[i]) < 1e-12, `${what}: [${a}] vs [${b}]`));

test('image right, up and the view direction of every named view are the server camera\'s', () => {
  assert.deepEqual(Object.keys(contract.VIEW_AXES), Object.keys(contract.VIEWS));
  for (const [name, axes] of Object.entries(contract.VIEW_AXES)) {
    const cam = parseCamera(name);
    const { right, up } = imageAxes(cam);
    near(right, axes.right, `${name} right`);
    near(up, axes.up, `${name} up`);
    near(viewDirection(cam), axes.forward, `${name} forward`);
    assert.equal(viewName(cam), name);
  }
});

test('the patient letters are LPS, and the anterior view shows the patient\'s left on the image\'s right', () => {
  assert.deepEqual(contract.PATIENT_LETTERS, [['L', 'R'], ['P', 'A'], ['S', 'I']]);
  const lps = { axes: [[1, 0, 0], [0, 1, 0], [0, 0, 1]] };
  const labels = edgeLabels(parseCamera('anterior'), lps);
  assert.deepEqual([labels.left, labels.right, labels.top, labels.bottom], ['R', 'L', 'S', 'I']);
});

test('the camera clamps to the server\'s ranges and starts from its default', () => {
  const L = contract.CAMERA_LIMITS;
  const wild = normalize({ az: 10, el: 1e9, zoom: 1e9, panX: -1e9, panY: 1e9, proj: 'fisheye', fov: 1e9 });
  assert.deepEqual(wild, { az: 10, el: L.el[1], zoom: L.zoom[1], panX: L.pan[0], panY: L.pan[1],
    proj: contract.DEFAULT_CAMERA.proj, fov: L.fov[1] });
  assert.deepEqual(parseCamera(''), { ...contract.DEFAULT_CAMERA });
  assert.deepEqual(initialView().cam, { ...contract.DEFAULT_CAMERA });
  assert.match(formatCamera(contract.DEFAULT_CAMERA), new RegExp(`proj=${contract.PROJECTIONS.ortho},`));
  assert.throws(() => parseCamera('proj=fisheye'), /ortho or persp/);
});

test('the names the viewer uses by name are among the server\'s, and its defaults are the server\'s', () => {
  for (const name of ['vots', 'grid']) assert.ok(contract.RENDERERS.includes(name), name);
  assert.ok(contract.MODES.includes('density') && !contract.GRID_MODES.includes('density'));
  const view = initialView();
  assert.deepEqual([view.mode, view.renderer, view.colormap],
    [contract.DEFAULT_MODE, contract.DEFAULT_RENDERER, contract.DEFAULT_COLORMAP]);
  const density = { ...view, mode: 'density', renderer: 'grid' };
  reconcileRenderer(density, 'renderer');
  assert.equal(density.mode, contract.DEFAULT_MODE);
});

test('an old link\'s mode name opens the mode and renderer the server reads it as', () => {
  const ds = { name: 'd', modality: 'CT', range: [0, 100], dims: [2, 2, 2], window: { level: 50, width: 100 } };
  for (const [name, wanted] of Object.entries(contract.LEGACY_MODES)) {
    const { view, problems } = parseHash(`#dataset=d&mode=${name}`, [ds], initialView());
    assert.deepEqual(problems, []);
    assert.deepEqual([view.mode, view.renderer], [wanted.mode, wanted.renderer]);
  }
  const { view, problems } = parseHash(`#dataset=d&degree=${contract.MAX_DEGREE + 1}`, [ds], initialView());
  assert.equal(view.degree, undefined, problems.join());
});

test('the colour bar is drawn from the server\'s colour map tables', () => {
  for (const map of contract.COLORMAPS) {
    const table = contract.COLORMAP_TABLES[map];
    assert.equal(table.length, 256, map);
    const bar = colorbarOf({ window: { level: 0, width: 1 }, colormap: map, mode: 'mip' }, null);
    const stops = bar.gradient.replace(/^linear-gradient\(to top, |\)$/g, '').split(', ');
    assert.equal(stops.length, 16, map);
    assert.deepEqual([stops[0], stops[5], stops[10], stops[15]], [table[0], table[85], table[170], table[255]], map);
  }
});
