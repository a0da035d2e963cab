// The URL hash holds the whole view: reloading, or opening the copied link in a fresh browser, shows the same image.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset, comparePixels } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

// The renderer is deterministic for one request; allow a little slack for GPU/llvmpipe jitter.
const MAX_DIFF = 2;
const MAX_DIFF_FRACTION = 0.001;

function assertSameImage(a, b, what) {
  const c = comparePixels(a, b);
  assert.ok(c.sameSize, `${what}: sizes differ ${a.width}x${a.height} vs ${b.width}x${b.height}`);
  assert.ok(c.maxDiff <= MAX_DIFF || c.diffFraction <= MAX_DIFF_FRACTION,
    `${what}: max channel diff ${c.maxDiff}, ${(c.diffFraction * 100).toFixed(3)} % of pixels differ`);
}

test('reload restores dataset, camera, eps, mode, window and colour map, and the same image', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    const level = Number(ds.window.level);
    const width = Number(ds.window.width) / 2;
    await viewer.open({
      dataset: ds.name,
      cam: 'az=30,el=20,zoom=1.3,pan=0:0,proj=ortho,fov=30',
      eps: Number(ds.defaultEps),
      mode: 'mip',
      window: `${level},${width}`,
      colormap: 'bone',
    });
    await viewer.waitForIdle();
    // Orbit a little so the restored state is one the page wrote itself.
    await viewer.drag(60, -30);
    await viewer.waitForIdle();
    const url = page.url();
    const hashBefore = await viewer.hashParams();
    const before = await viewer.framePixels();
    await viewer.screenshotView('reload-before');

    await page.reload();
    await viewer.waitForIdle();
    await viewer.screenshotView('reload-after');
    assert.deepEqual(await viewer.hashParams(), hashBefore, 'reload changed the hash');
    assert.equal(await viewer.colormap.inputValue(), 'bone');
    assert.equal(Number(await viewer.width.inputValue()), width);
    assertSameImage(before, await viewer.framePixels(), 'after reload');

    // The copied link in a new page: same view.
    const other = await page.context().newPage();
    const second = new ViewerPage(other);
    await other.goto(url);
    await second.waitForIdle();
    assertSameImage(before, await second.framePixels(), 'copied link');
  });
});

test('a link with a non-default eps refits first and reproduces the same image on reload', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    const eps = Number((Number(ds.defaultEps) * 1.5).toPrecision(3));
    await viewer.open({ dataset: ds.name, cam: 'left', eps, colormap: 'viridis' });
    await viewer.waitForIdle();
    assert.equal(Number((await viewer.hashParams()).eps), eps);
    assert.match((await viewer.hashParams()).cam, /^az=90,el=0,/);
    const before = await viewer.framePixels();
    await page.reload();
    await viewer.waitForIdle();
    assertSameImage(before, await viewer.framePixels(), 'after reload with eps');
  });
});
