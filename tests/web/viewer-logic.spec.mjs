// Unit checks of the viewer's DOM-free modules under node: the URL hash both ways, and the eps slider scale.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadWebModules } from './support/web-modules.mjs';

const m = await loadWebModules(['hash.js', 'eps.js', 'view.js', 'access.js', 'orientation.js', 'kind.js']);
const { formatHash, parseHash } = m['hash.js'];
const { epsLabel, epsSteps, epsToSlider, sliderMax, sliderToEps } = m['eps.js'];
const { initialView } = m['view.js'];
const access = m['access.js'];
const { edgeLabels } = m['orientation.js'];
const kind = m['kind.js'];

const CT = {
  name: 'cranium', modality: 'CT', range: [-1000, 3000], defaultEps: 80, epsSteps: [4, 40, 72, 80, 88, 2000],
  window: { level: 40, width: 400 }, presets: {},
};
const MR = { name: 'head', modality: 'MR', range: [0, 255], defaultEps: 5.1, window: { level: 100, width: 200 } };
const NO_DEFAULT = { ...MR, name: 'bare', defaultEps: undefined };
const FMRI = { ...MR, name: 'fmri', frames: 20 };
const DATASETS = [MR, CT, NO_DEFAULT, FMRI];

test('a hash the viewer writes reads back as the same view', () => {
  const view = {
    dataset: 'head', frame: 0, cam: { az: 30, el: -20, zoom: 1.25, panX: 0.5, panY: -0.25, proj: 'persp', fov: 40 },
    eps: 7.5, degree: 2, mode: 'density', renderer: 'vots', slab: null, window: { level: 12.5, width: 80 },
    colormap: 'bone',
  };
  const text = formatHash(view);
  assert.equal(text, '#dataset=head&cam=az%3D30,el%3D-20,zoom%3D1.25,pan%3D0.5:-0.25,proj%3Dpersp,fov%3D40&eps=7.5' +
    '&mode=density&window=12.5,80&colormap=bone&degree=2');
  const { view: back, problems } = parseHash(text, DATASETS, initialView());
  assert.deepEqual(problems, []);
  assert.deepEqual(back, view);
});

test('the frame of a 4D dataset is in the link (frame 0 unsaid) and one it does not hold is named', () => {
  const view = { ...initialView(), dataset: 'fmri', frame: 7, eps: 7.5, window: { level: 12.5, width: 80 } };
  const text = formatHash(view);
  assert.match(text, /^#dataset=fmri&cam=[^&]*&frame=7&eps=/);
  assert.deepEqual(parseHash(text, DATASETS, initialView()).view, view);
  assert.doesNotMatch(formatHash({ ...view, frame: 0 }), /frame=/);
  for (const bad of ['20', '-1', 'x', '1.5']) {
    const { view: back, problems } = parseHash(`#dataset=fmri&frame=${bad}`, DATASETS, initialView());
    assert.equal(back.frame, 0, bad);
    assert.deepEqual(problems, [`frame '${bad}' is not one of the 20 of 'fmri'; showing frame 0.`]);
  }
  // A 3D dataset has frame 0 alone.
  assert.equal(parseHash('#dataset=head&frame=1', DATASETS, initialView()).problems.length, 1);
});

test('an empty hash opens the Cranium CT at its server default eps and window', () => {
  const { view, problems } = parseHash('', DATASETS, initialView());
  assert.deepEqual(problems, []);
  assert.equal(view.dataset, 'cranium');
  assert.equal(view.eps, 80);
  assert.deepEqual(view.window, { level: 40, width: 400 });
  assert.equal(view.degree, undefined);
});

test('eps as a percentage of the range becomes data units with three digits', () => {
  assert.equal(parseHash('#dataset=cranium&eps=1.5%25', DATASETS, initialView()).view.eps, 60);
  assert.equal(parseHash('#dataset=head&eps=1%25', DATASETS, initialView()).view.eps, 2.55);
});

test('bad parts fall back and are each named, in the order of the link', () => {
  const { view, problems } = parseHash('#dataset=nope&cam=az=x&eps=-1&mode=x&colormap=y&window=1', DATASETS,
    initialView());
  assert.equal(view.dataset, 'cranium');
  assert.equal(view.eps, 80);
  assert.equal(view.mode, 'mip');
  assert.equal(view.colormap, 'grey');
  assert.deepEqual(view.window, { level: 40, width: 400 });
  assert.equal(problems.length, 6);
  assert.match(problems[0], /Unknown dataset 'nope'.*head, cranium, bare/);
  assert.match(problems[1], /az/);
  assert.match(problems[2], /eps '-1' must be a positive number; using 80/);
  assert.match(problems[3], /mode 'x'/);
  assert.match(problems[4], /colour map 'y'/);
  assert.match(problems[5], /window '1'/);
});

test('a link without eps keeps the current eps on the same dataset and takes the default on another', () => {
  const current = { ...initialView(), dataset: 'cranium', eps: 120 };
  assert.equal(parseHash('#dataset=cranium', DATASETS, current).view.eps, 120);
  assert.equal(parseHash('#dataset=head', DATASETS, current).view.eps, 5.1);
});

test('a bad eps in the link names the eps that stays: the current one on the same dataset', () => {
  const current = { ...initialView(), dataset: 'cranium', eps: 120 };
  const same = parseHash('#dataset=cranium&eps=abc', DATASETS, current);
  assert.equal(same.view.eps, 120);
  assert.match(same.problems[0], /eps 'abc' must be a positive number; using 120\./);
  const other = parseHash('#dataset=head&eps=0', DATASETS, current);
  assert.equal(other.view.eps, 5.1);
  assert.match(other.problems[0], /eps '0' must be a positive number; using 5\.1\./);
  const bare = parseHash('#dataset=bare&eps=-2', DATASETS, { ...initialView(), dataset: 'bare', eps: 3 });
  assert.equal(bare.view.eps, 3);
  assert.match(bare.problems[0], /using 3\./);
});

test('with no server default there is no client-made eps: the view has none and the hash says none', () => {
  const { view, problems } = parseHash('#dataset=bare', DATASETS, initialView());
  assert.deepEqual(problems, []);
  assert.equal(view.eps, null);
  assert.doesNotMatch(formatHash(view), /eps=/);
  assert.match(parseHash('#dataset=bare&eps=0', DATASETS, initialView()).problems[0], /server sent no default/);
  assert.equal(epsLabel(NO_DEFAULT, null), '– (no default from the server)');
});

test("the eps slider's positions are the server's steps, an eps between them shown at the nearest", () => {
  assert.equal(sliderMax(CT), 5);
  assert.deepEqual([0, 1, 2, 3, 4, 5].map((pos) => sliderToEps(CT, pos)), CT.epsSteps);
  for (let pos = 0; pos <= 5; pos++) assert.equal(epsToSlider(CT, sliderToEps(CT, pos)), pos);
  assert.equal(sliderToEps(CT, -3), 4, 'below the ends clamps');
  assert.equal(sliderToEps(CT, 99), 2000, 'beyond the ends clamps');
  assert.equal(epsToSlider(CT, 1e9), 5);
  assert.equal(epsToSlider(CT, 76), 3, 'nearest on a log scale: 76 is nearer 80 than 72');
  assert.equal(epsToSlider(CT, 75.8), 2, '75.8 is nearer 72 (x1.053) than 80 (x1.055)');
  assert.deepEqual(epsSteps(MR), [5.1], 'a server that sends no steps offers the default alone');
  assert.deepEqual(epsSteps(NO_DEFAULT), []);
  assert.equal(sliderToEps(NO_DEFAULT, 0), null);
  assert.equal(epsLabel(CT, 80), '80 (2.0 % of range)');
});

test('the access token: taken from the hash, kept when a link lacks it, sent as a header and as token=', () => {
  assert.equal(access.tokenHashPart(), '');
  assert.deepEqual(access.withToken({ cache: 'no-store' }), { cache: 'no-store' }); // none: requests unchanged
  assert.equal(access.withTokenQuery('api/jobs/1/events'), 'api/jobs/1/events');
  assert.equal(access.adoptToken('#dataset=head&token=a%2Bb/c'), 'a+b/c');
  assert.equal(access.adoptToken('#dataset=head'), 'a+b/c'); // a pasted link without one keeps it
  assert.equal(access.tokenHashPart(), '&token=a%2Bb%2Fc');
  const init = access.withToken({ method: 'POST', headers: { 'Content-Type': 'application/json' } });
  assert.deepEqual(init.headers, { 'Content-Type': 'application/json', Authorization: 'Bearer a+b/c' });
  assert.equal(init.method, 'POST');
  assert.equal(access.withTokenQuery('api/jobs/1/events'), 'api/jobs/1/events?token=a%2Bb%2Fc');
  assert.equal(access.withTokenQuery('render?dataset=x'), 'render?dataset=x&token=a%2Bb%2Fc');
  // The view hash plus the token still reads back as the same view.
  const view = { ...initialView(), dataset: 'head', eps: 7.5, window: { level: 12.5, width: 80 } };
  const { view: back, problems } = parseHash(formatHash(view) + access.tokenHashPart(), DATASETS, initialView());
  assert.deepEqual(problems, []);
  assert.deepEqual(back, view);
});

test('edge labels follow the six views of the contract, and grid axes without orientation', () => {
  const oriented = { axes: [[1, 0, 0], [0, 1, 0], [0, 0, 1]], directions: ['L', 'P', 'S'] };
  const at = (az, el) => {
    const { kind: labelKind, ...edges } = edgeLabels({ az, el }, oriented);
    assert.equal(labelKind, 'patient');
    return edges;
  };
  assert.deepEqual(at(0, 0), { left: 'R', right: 'L', top: 'S', bottom: 'I' }); // anterior
  assert.deepEqual(at(180, 0), { left: 'L', right: 'R', top: 'S', bottom: 'I' }); // posterior
  assert.deepEqual(at(90, 0), { left: 'A', right: 'P', top: 'S', bottom: 'I' }); // left
  assert.deepEqual(at(-90, 0), { left: 'P', right: 'A', top: 'S', bottom: 'I' }); // right
  assert.deepEqual(at(0, 90), { left: 'R', right: 'L', top: 'P', bottom: 'A' }); // superior
  assert.deepEqual(at(0, -90), { left: 'R', right: 'L', top: 'A', bottom: 'P' }); // inferior
  assert.equal(at(45, 0).right, 'LP'); // oblique: two letters
  const grid = edgeLabels({ az: 0, el: 0 }, null);
  assert.deepEqual(grid, { kind: 'grid', left: '\u2212x', right: '+x', top: '+z', bottom: '\u2212z' });
  assert.equal(edgeLabels({ az: 45, el: 0 }, null).right, '+x+y');
});

test('a .vots dataset keeps the view at its own eps and off the grid renderer, and says why in tooltips', () => {
  const VOTS = { ...MR, name: 'fitted', kind: 'vots', eps: 7.65, defaultEps: 7.65 };
  const view = { dataset: 'fitted', eps: 2, mode: 'minip', renderer: 'grid' };
  kind.fitViewToDataset(view, VOTS);
  assert.deepEqual(view, { dataset: 'fitted', eps: 7.65, mode: 'minip', renderer: 'vots' });
  const volumeView = { dataset: 'head', eps: 2, mode: 'mip', renderer: 'grid' };
  kind.fitViewToDataset(volumeView, { ...MR, kind: 'volume' });
  assert.deepEqual(volumeView, { dataset: 'head', eps: 2, mode: 'mip', renderer: 'grid' });

  const reference = { disabled: false, title: '' };
  const el = { epsSlider: { disabled: false, title: '' }, renderer: { title: '', querySelector: () => reference } };
  kind.syncKindLimits(el, VOTS);
  assert.equal(el.epsSlider.disabled, true);
  assert.equal(reference.disabled, true);
  assert.match(el.epsSlider.title, /refit/);
  assert.match(reference.title, /grid/);
  kind.syncKindLimits(el, { ...MR, kind: 'volume' });
  assert.equal(el.epsSlider.disabled, false);
  assert.equal(reference.disabled, false);
  assert.equal(el.epsSlider.title, '');
});
