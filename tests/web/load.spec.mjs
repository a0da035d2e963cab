// The viewer loads with nothing in the console's errors, fills the view with a non-blank frame at the view's
// size, and writes its state into the hash.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset, VIEWPORT } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

test('page loads and shows a non-blank image that fills the view', async (t) => {
  await withPage(t, async (page) => {
    // A resource the page asks for and does not get (its icon was one) is an error in every user's console.
    const consoleErrors = [];
    page.on('console', (m) => {
      if (m.type() === 'error') consoleErrors.push(`${m.text()} (${m.location().url})`);
    });
    const viewer = new ViewerPage(page);
    await viewer.open();
    await viewer.waitForIdle();
    const icon = await page.request.get(new URL('favicon.svg', page.url()).href);
    assert.equal(icon.status(), 200);
    assert.equal(icon.headers()['content-type'], 'image/svg+xml');
    await viewer.screenshotPage('load-page');

    const frame = await viewer.framePixels();
    assert.ok(frame.variance > 20, `frame looks blank: luminance variance ${frame.variance.toFixed(2)}`);

    // DPR is pinned to 1, so the request size equals the view's CSS size.
    const g = await viewer.imageGeometry();
    assert.ok(g.cssWidth > VIEWPORT.width / 2 && g.cssHeight === VIEWPORT.height, `view is ${g.cssWidth}x${g.cssHeight}`);
    assert.equal(g.naturalWidth, Math.round(g.cssWidth));
    assert.equal(g.naturalHeight, Math.round(g.cssHeight));

    const h = await viewer.hashParams();
    for (const key of ['dataset', 'cam', 'eps', 'mode', 'window', 'colormap']) assert.ok(h[key], `hash lacks ${key}: ${JSON.stringify(h)}`);
    assert.match(await viewer.votCount.textContent(), /\d/);
    assert.ok(!(await viewer.error.isVisible()), `unexpected error: ${await viewer.error.textContent()}`);
    assert.deepEqual(consoleErrors, [], 'errors in the console');
  });
});

test('every control named in the contract has its data-testid', async (t) => {
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open();
    await viewer.waitForIdle();
    const ids = ['dataset', 'mode', 'colormap', 'window-preset', 'level', 'width', 'eps-slider', 'eps-value',
      'progress', 'vot-count', 'fit-time', 'projection', 'image', 'error', 'status',
      ...['anterior', 'posterior', 'left', 'right', 'superior', 'inferior'].map((v) => `view-${v}`)];
    for (const id of ids) assert.equal(await page.getByTestId(id).count(), 1, `data-testid="${id}"`);
  });
});

test('controls change the frame: colour map, mode, window preset, view buttons, projection', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'az=20,el=10,zoom=1,pan=0:0,proj=ortho,fov=30' });
    await viewer.waitForIdle();
    let before = await viewer.framePixels();
    const changed = async (what, action, hashCheck) => {
      await action();
      await viewer.waitForIdle();
      const after = await viewer.framePixels();
      assert.notDeepEqual(after.data, before.data, `${what} did not change the frame`);
      if (hashCheck) hashCheck(await viewer.hashParams());
      before = after;
    };
    await changed('colour map', () => viewer.colormap.selectOption('hot'), (h) => assert.equal(h.colormap, 'hot'));
    await viewer.screenshotView('controls-hot');
    await changed('mode', () => viewer.mode.selectOption('density'), (h) => assert.equal(h.mode, 'density'));
    await viewer.mode.selectOption('mip');
    await viewer.waitForIdle();
    before = await viewer.framePixels();
    await changed('window width', async () => {
      await viewer.width.fill(String(Number(ds.window.width) / 4));
      await viewer.width.press('Enter');
    }, (h) => assert.equal(Number(h.window.split(',')[1]), Number(ds.window.width) / 4));
    await changed('view button', () => viewer.viewButton('left').click(), (h) => assert.match(h.cam, /az=90,el=0/));
    assert.equal(await viewer.viewButton('left').getAttribute('aria-pressed'), 'true');
    await changed('projection', () => viewer.projection.click(), (h) => assert.match(h.cam, /proj=persp/));
    await viewer.screenshotView('controls-left-persp');
  });
});
