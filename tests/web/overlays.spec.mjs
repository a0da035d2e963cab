// What the viewer draws over the image: patient letters (or grid axes) at the edges for the six views, the
// colour bar in data units, the scale bar in mm; and the download links of the view.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

// What a radiology viewer shows for each of the six views (image left, right, top, bottom).
const PATIENT = {
  anterior: ['R', 'L', 'S', 'I'],
  posterior: ['L', 'R', 'S', 'I'],
  left: ['A', 'P', 'S', 'I'],
  right: ['P', 'A', 'S', 'I'],
  superior: ['R', 'L', 'P', 'A'],
  inferior: ['R', 'L', 'A', 'P'],
};

async function edges(viewer) {
  const out = [];
  for (const edge of ['left', 'right', 'top', 'bottom']) {
    const label = viewer.byId(`edge-${edge}`);
    out.push((await label.isVisible()) ? (await label.textContent()).trim() : null);
  }
  return out;
}

// The datasets as the server lists them, with the patient axes of an LPS file added to `name`'s entry: what
// /api/datasets sends for an oriented volume (docs/API.md), without needing one in the test data.
async function serveAsOriented(page, name) {
  await page.route('**/api/datasets', async (route) => {
    const res = await route.fetch();
    const body = await res.json();
    for (const d of body.datasets) {
      if (d.name === name) d.orientation = { axes: [[1, 0, 0], [0, 1, 0], [0, 0, 1]], directions: ['L', 'P', 'S'] };
    }
    await route.fulfill({ response: res, json: body });
  });
}

test('the edge labels read A/P/L/R/S/I for the six view buttons and follow an orbit', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    await serveAsOriented(page, ds.name);
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'anterior', eps: Number(ds.defaultEps) });
    await viewer.waitForIdle();
    for (const [view, want] of Object.entries(PATIENT)) {
      await viewer.viewButton(view).click();
      await viewer.waitForIdle();
      assert.deepEqual(await edges(viewer), want, `labels of the ${view} view`);
    }
    await viewer.screenshotPage('labels-inferior');
    // Orbit from the front by about 30 degrees towards the patient's right: the right edge becomes a mix.
    await viewer.viewButton('anterior').click();
    await viewer.waitForIdle();
    const box = await viewer.image.boundingBox();
    await viewer.drag(-Math.min(box.width, box.height) / 6, 0);
    await viewer.waitForIdle();
    const az = (await viewer.camValues()).az;
    assert.ok(az < -25 && az > -40, `az after the drag: ${az}`);
    assert.equal((await edges(viewer))[1], 'LA', 'the right edge of an oblique view from the right front');
  });
});

test('without orientation the edges name the grid axes', async (t) => {
  const ds = await pickDataset();
  assert.equal(ds.orientation ?? null, null, 'this check wants a dataset without orientation');
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'anterior', eps: Number(ds.defaultEps) });
    await viewer.waitForIdle();
    assert.deepEqual(await edges(viewer), ['\u2212x', '+x', '+z', '\u2212z']);
    await viewer.viewButton('left').click();
    await viewer.waitForIdle();
    assert.deepEqual(await edges(viewer), ['\u2212y', '+y', '+z', '\u2212z']);
  });
});

test('the colour bar gives the window in data units and the scale bar halves with twice the zoom', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'anterior', eps: Number(ds.defaultEps), window: '100,80', colormap: 'hot' });
    await viewer.waitForIdle();
    const unit = ds.modality === 'CT' ? ' HU' : '';
    assert.equal((await viewer.byId('colorbar-high').textContent()).trim(), `140${unit}`);
    assert.equal((await viewer.byId('colorbar-low').textContent()).trim(), `60${unit}`);
    assert.equal(await viewer.byId('colorbar').getAttribute('data-colormap'), 'hot');

    const bar = viewer.byId('scalebar');
    const mmPerPx = async () => Number(await bar.getAttribute('data-mm')) / Number(await bar.getAttribute('data-px'));
    const drawn = (await viewer.byId('scalebar-line').boundingBox()).width;
    assert.ok(Math.abs(drawn - Number(await bar.getAttribute('data-px'))) < 1.5, 'the line is not as wide as it says');
    // Zoom 1 fits the volume's bounding sphere into the view's height (render/src/Camera.cpp).
    const edge = (a) => ds.spacing[a] * Math.max(ds.dims[a] - 1, 1);
    const diameter = Math.hypot(edge(0), edge(1), edge(2));
    const viewHeight = await page.evaluate(() => document.getElementById('view').clientHeight);
    const at1 = await mmPerPx();
    // data-px has three decimals: the relative error of mm/px is at most half a thousandth of a pixel over
    // the bar's width.
    const tolerance = async () => 0.0005 / Number(await bar.getAttribute('data-px')) + 1e-9;
    const within1 = await tolerance();
    assert.ok(Math.abs(at1 - diameter / viewHeight) < within1 * at1, `mm per px ${at1}, want ${diameter / viewHeight}`);
    await viewer.open({ dataset: ds.name, cam: 'az=0,el=0,zoom=2', eps: Number(ds.defaultEps) });
    await viewer.waitForIdle();
    const within2 = within1 + (await tolerance());
    assert.ok(Math.abs((await mmPerPx()) - at1 / 2) < within2 * at1, 'zoom 2 should halve the mm per pixel');
  });
});

test('Download PNG is the view\'s /render URL; Download turn asks /turntable for the same view', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'az=30,el=20,zoom=1,pan=0:0,proj=ortho,fov=30', eps: Number(ds.defaultEps) });
    await viewer.waitForIdle();
    const png = await viewer.byId('download-png').getAttribute('href');
    const shown = await viewer.image.getAttribute('data-frame-url');
    const noClient = (u) => {
      const q = new URLSearchParams(u.split('?')[1]);
      q.delete('client');
      return q.toString();
    };
    assert.ok(png.startsWith('render?'), png);
    assert.equal(noClient(png), noClient(shown), 'the PNG link is not the shown frame');
    const res = await page.request.get(new URL(png, page.url()).href);
    assert.equal(res.status(), 200);
    assert.equal(res.headers()['content-type'], 'image/png');
    const turn = await viewer.byId('download-turn').getAttribute('href');
    assert.ok(turn.startsWith('turntable?'), turn);
    const q = new URLSearchParams(turn.split('?')[1]);
    assert.equal(q.get('frames'), '36');
    q.delete('frames');
    assert.equal(q.toString(), noClient(shown));
  });
});
