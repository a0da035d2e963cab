// Cine: the button turns the camera about the vertical axis with server frames, the second turn comes from
// the server's frame cache, and a second press or an orbit stops it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset, comparePixels } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

const TURN_MS = 120000; // a whole turn of 36 frames on a software renderer

// Azimuths of the frames shown from now on, read from the image's frame URL whenever it changes.
async function watchShownAz(page) {
  await page.evaluate(() => {
    window.__votsShownAz = [];
    const img = document.querySelector('[data-testid="image"]');
    new MutationObserver(() => {
      const cam = new URLSearchParams(img.dataset.frameUrl.split('?')[1]).get('cam');
      const az = Number(/az=(-?[\d.]+)/.exec(cam)[1]);
      if (window.__votsShownAz.at(-1) !== az) window.__votsShownAz.push(az);
    }).observe(img, { attributes: true, attributeFilter: ['data-frame-url'] });
  });
}
const shownAz = (page) => page.evaluate(() => window.__votsShownAz);

test('cine turns the image about the vertical axis and stops on a second press', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'az=0,el=15,zoom=1,pan=0:0,proj=ortho,fov=30', eps: Number(ds.defaultEps) });
    await viewer.waitForIdle();
    const first = await viewer.framePixels();
    const cache = [];
    page.on('response', (r) => {
      if (r.url().includes('/render?')) cache.push(r.headers()['x-vots-frame-cache']);
    });
    await watchShownAz(page);
    const cine = viewer.byId('cine');
    await cine.click();
    assert.equal(await cine.getAttribute('aria-pressed'), 'true');
    // A whole turn and a few frames of the next: the azimuth steps by 10 degrees, elevation stays.
    await page.waitForFunction(() => window.__votsShownAz.length >= 40, null, { timeout: 2 * TURN_MS, polling: 100 });
    const turned = await viewer.framePixels();
    await cine.click();
    assert.equal(await cine.getAttribute('aria-pressed'), 'false');
    const az = await shownAz(page);
    const steps = az.slice(1).map((a, i) => ((a - az[i] + 540) % 360) - 180);
    assert.ok(steps.every((s) => Math.abs(s - 10) < 1e-6), `the azimuth did not step by 10 degrees: ${az.join(' ')}`);
    assert.match(await viewer.cam(), /el=15,/);
    assert.ok(comparePixels(first, turned).diffFraction > 0.01, 'the image did not turn');
    // The second turn asks for the frames of the first again: the server answers them from its cache.
    assert.ok(cache.slice(-3).every((c) => c === 'hit'), `second-turn frames were not cache hits: ${cache.slice(-6).join(' ')}`);

    await viewer.waitForIdle();
    const stoppedAt = await viewer.cam();
    const before = cache.length;
    await page.waitForTimeout(1500);
    assert.equal(await viewer.cam(), stoppedAt, 'the camera kept turning after the second press');
    assert.equal(cache.length, before, 'frames kept coming after the second press');
  });
});

test('an orbit of the user stops the cine', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'anterior', eps: Number(ds.defaultEps) });
    await viewer.waitForIdle();
    await watchShownAz(page);
    const cine = viewer.byId('cine');
    await cine.click();
    await page.waitForFunction(() => window.__votsShownAz.length >= 3, null, { timeout: TURN_MS, polling: 100 });
    await viewer.drag(0, -60);
    await viewer.waitForIdle();
    assert.equal(await cine.getAttribute('aria-pressed'), 'false');
    const cam = await viewer.cam();
    await page.waitForTimeout(1000);
    assert.equal(await viewer.cam(), cam, 'the camera turned on after the orbit');
  });
});
