// The projection menu, the renderer choice and the slab: each changes the image and the URL hash, and a
// reload restores them.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset, comparePixels } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

const CAM = 'az=30,el=20,zoom=1,pan=0:0,proj=ortho,fov=30';

function assertDiffers(a, b, what) {
  const c = comparePixels(a, b);
  assert.ok(c.sameSize && c.diffFraction > 0.01, `${what}: only ${(c.diffFraction * 100).toFixed(2)} % of pixels changed`);
}

function assertSame(a, b, what) {
  const c = comparePixels(a, b);
  assert.ok(c.sameSize && c.maxDiff <= 2, `${what}: max channel diff ${c.maxDiff}`);
}

const shownParam = (page, key) => page.evaluate(
  (k) => new URLSearchParams(document.querySelector('[data-testid="image"]').dataset.frameUrl.split('?')[1]).get(k), key);

test('MinIP, Average and a slab on the Vots change the image and the hash; a reload restores them', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: CAM, eps: Number(ds.defaultEps) });
    await viewer.waitForIdle();
    const mip = await viewer.framePixels();
    const shown = { mip };
    for (const mode of ['minip', 'aip']) {
      await viewer.mode.selectOption(mode);
      await viewer.waitForIdle();
      assert.equal((await viewer.hashParams()).mode, mode);
      assert.equal(await shownParam(page, 'mode'), mode, 'the shown frame was not rendered in that mode');
      shown[mode] = await viewer.framePixels();
      assertDiffers(shown[mode], mip, `${mode} against mip`);
    }
    assertDiffers(shown.minip, shown.aip, 'minip against aip');
    // Per pixel, minimum <= mean <= maximum of the same ray: with a grey map the brightness keeps that order.
    // Up to the background: a ray that meets only cells the fit left as background has no MIP (black), while
    // minip and aip count those cells as the background value (docs/API.md), which the window maps to a few
    // grey levels above black.
    const levelsPerUnit = 255 / Number(ds.window.width);
    const slack = Math.ceil((Number(ds.background) - Number(ds.range[0])) * levelsPerUnit) + 1;
    const lum = (img, i) => img.data[i * 4];
    let misordered = 0;
    const n = mip.width * mip.height;
    for (let i = 0; i < n; i++) {
      if (lum(shown.minip, i) > lum(shown.aip, i) + 1 || lum(shown.aip, i) > lum(shown.mip, i) + slack) misordered++;
    }
    assert.ok(misordered <= n * 0.001, `${misordered} pixels break minip <= aip <= mip`);
    await viewer.screenshotView('mode-aip');

    // A slab on the Vots: a thinner average than the whole ray's.
    await viewer.byId('slab-on').check();
    await viewer.waitForIdle();
    assert.equal(await shownParam(page, 'slab'), '0,10');
    const slab = await viewer.framePixels();
    assertDiffers(slab, shown.aip, 'aip of a 10 mm slab against the whole ray');

    await page.reload();
    await viewer.waitForIdle();
    assert.equal(await viewer.mode.inputValue(), 'aip');
    assertSame(await viewer.framePixels(), slab, 'aip slab after reload');
  });
});

test('the grid renderer is chosen in the panel and kept in the hash; density takes the Vots back', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: CAM, eps: Number(ds.defaultEps) });
    await viewer.waitForIdle();
    const renderer = viewer.byId('renderer');
    await renderer.selectOption('grid');
    await viewer.waitForIdle();
    assert.equal((await viewer.hashParams()).renderer, 'grid');
    assert.equal(await shownParam(page, 'renderer'), 'grid');
    await page.reload();
    await viewer.waitForIdle();
    assert.equal(await renderer.inputValue(), 'grid');
    // Density shows Vot sizes, which only the Vots have.
    await viewer.mode.selectOption('density');
    await viewer.waitForIdle();
    assert.equal(await renderer.inputValue(), 'vots');
    assert.equal((await viewer.hashParams()).renderer, undefined);
    assert.equal(await shownParam(page, 'renderer'), null);
    // An old link's mode=reference opens as MIP on the grid.
    await viewer.open({ dataset: ds.name, cam: CAM, mode: 'reference' });
    await viewer.waitForIdle();
    assert.equal(await viewer.mode.inputValue(), 'mip');
    assert.equal(await renderer.inputValue(), 'grid');
  });
});

test('the slab changes the image and the hash, its slider follows the camera, and a reload restores it', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'anterior', eps: Number(ds.defaultEps) });
    await viewer.waitForIdle();
    const whole = await viewer.framePixels();
    const slabOn = viewer.byId('slab-on');
    const thickness = viewer.byId('slab-thickness');
    const offset = viewer.byId('slab-offset');
    assert.equal(await offset.isDisabled(), true, 'the position slider works only with a slab');

    await slabOn.check();
    await viewer.waitForIdle();
    assert.equal((await viewer.hashParams()).slab, '0,10');
    assert.ok((await shownParam(page, 'slab')) === '0,10', 'the frame was not asked with the slab');
    const centre = await viewer.framePixels();
    assertDiffers(centre, whole, 'a 10 mm slab against the whole volume');

    await thickness.fill('4');
    await thickness.dispatchEvent('change');
    await viewer.waitForIdle();
    assert.equal((await viewer.hashParams()).slab, '0,4');
    const thin = await viewer.framePixels();
    assertDiffers(thin, centre, '4 mm against 10 mm');

    // The slider spans the volume's depth along the view: the y extent from the front.
    const halfY = ((ds.dims[1] - 1) * ds.spacing[1]) / 2;
    assert.ok(Math.abs(Number(await offset.getAttribute('max')) - halfY) <= 0.1, 'slider max is not the half depth along y');
    const to = Math.round(halfY / 2);
    await offset.evaluate((s, v) => {
      s.value = String(v);
      s.dispatchEvent(new Event('input', { bubbles: true }));
      s.dispatchEvent(new Event('change', { bubbles: true }));
    }, to);
    await viewer.waitForIdle();
    assert.equal((await viewer.hashParams()).slab, `${to},4`);
    const moved = await viewer.framePixels();
    assertDiffers(moved, thin, 'the slab moved back by a quarter of the depth');
    await viewer.screenshotView('slab-moved');

    await page.reload();
    await viewer.waitForIdle();
    assert.equal(await slabOn.isChecked(), true);
    assert.equal(Number(await thickness.inputValue()), 4);
    assert.equal(Number(await offset.inputValue()), to);
    assertSame(await viewer.framePixels(), moved, 'slab after reload');

    // From above, the depth is the z extent: the slider's range follows the camera.
    await viewer.viewButton('superior').click();
    await viewer.waitForIdle();
    const halfZ = ((ds.dims[2] - 1) * ds.spacing[2]) / 2;
    assert.ok(Math.abs(Number(await offset.getAttribute('max')) - halfZ) <= 0.1, 'slider max did not follow the camera');

    await slabOn.uncheck();
    await viewer.waitForIdle();
    assert.equal((await viewer.hashParams()).slab, undefined);
    assert.equal(await shownParam(page, 'slab'), null);
  });
});
