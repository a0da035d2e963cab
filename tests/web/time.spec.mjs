// A 4D dataset's frame slider and time cine: shown only for a dataset of several frames, the slider draws the
// frame it names (the server's /render of that frame), the cine steps through the frames and stops on a press.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { BASE_URL, withPage, pickDataset, comparePixels } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

const PLAY_MS = 180000; // every frame is fitted on its first showing, on a software renderer

// run.sh serves nibabel's functional.nii (17x21x3, 20 frames) beside the 3D volumes.
async function fourDimensionalDataset() {
  const res = await fetch(`${BASE_URL}/api/datasets`);
  const four = (await res.json()).datasets.find((d) => d.fits !== false && d.frames > 1);
  assert.ok(four, 'the server lists no 4D dataset (frames > 1); run.sh serves functional.nii');
  return four;
}

// The frame each image shown was drawn from, read from the image's frame URL whenever it changes.
async function watchShownFrames(page) {
  await page.evaluate(() => {
    window.__votsShownFrames = [];
    const img = document.querySelector('[data-testid="image"]');
    new MutationObserver(() => {
      const frame = Number(new URLSearchParams(img.dataset.frameUrl.split('?')[1]).get('frame') ?? 0);
      if (window.__votsShownFrames.at(-1) !== frame) window.__votsShownFrames.push(frame);
    }).observe(img, { attributes: true, attributeFilter: ['data-frame-url'] });
  });
}

test('the frame slider shows only for a 4D dataset and draws the frame it names', async (t) => {
  const flat = await pickDataset();
  assert.equal(flat.frames, 1);
  const four = await fourDimensionalDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: flat.name, eps: Number(flat.defaultEps) });
    await viewer.waitForIdle();
    assert.equal(await viewer.byId('time').isVisible(), false, 'a 3D dataset shows a frame slider');

    await viewer.open({ dataset: four.name, eps: Number(four.defaultEps) });
    await viewer.waitForIdle();
    const slider = viewer.byId('frame-slider');
    assert.equal(await viewer.byId('time').isVisible(), true, 'a 4D dataset shows no frame slider');
    assert.equal(await slider.getAttribute('max'), String(four.frames - 1));
    assert.match(await viewer.byId('frame-value').textContent(), /^0 /);
    const first = await viewer.framePixels();

    await slider.fill('7');
    await viewer.waitForIdle();
    assert.equal((await viewer.hashParams()).frame, '7');
    const url = await viewer.image.getAttribute('data-frame-url');
    assert.equal(new URLSearchParams(url.split('?')[1]).get('frame'), '7', `not frame 7: ${url}`);
    assert.match(await viewer.byId('frame-value').textContent(), /^7 /);
    const seventh = await viewer.framePixels();
    assert.ok(comparePixels(first, seventh).maxDiff > 0, 'frame 7 draws as frame 0 does');
    await viewer.screenshotPage('time-frame-7');

    // Back to the frame the link names after a reload: the link carries the frame.
    await page.reload();
    await viewer.waitForIdle();
    assert.equal(await slider.inputValue(), '7');
    assert.equal(comparePixels(seventh, await viewer.framePixels()).maxDiff, 0);
  });
});

test('the time cine plays the frames in order, wraps, and stops on a second press', async (t) => {
  const four = await fourDimensionalDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: four.name, eps: Number(four.defaultEps) });
    await viewer.waitForIdle();
    const cam = await viewer.cam();
    await watchShownFrames(page);
    const cine = viewer.byId('time-cine');
    await cine.click();
    assert.equal(await cine.getAttribute('aria-pressed'), 'true');
    const wanted = four.frames + 3; // one pass and a few frames of the next
    await page.waitForFunction((n) => window.__votsShownFrames.length >= n, wanted, { timeout: PLAY_MS, polling: 100 });
    await cine.click();
    assert.equal(await cine.getAttribute('aria-pressed'), 'false');
    const shown = await page.evaluate(() => window.__votsShownFrames);
    const steps = shown.slice(1).map((f, i) => (f - shown[i] + four.frames) % four.frames);
    assert.ok(steps.every((s) => s === 1), `the frames did not step one by one: ${shown.join(' ')}`);
    assert.ok(shown.includes(four.frames - 1) && shown.lastIndexOf(0) > 0, `no wrap: ${shown.join(' ')}`);
    assert.equal(await viewer.cam(), cam, 'the time cine moved the camera');

    await viewer.waitForIdle();
    const stoppedAt = (await viewer.hashParams()).frame;
    await page.waitForTimeout(1500);
    assert.equal((await viewer.hashParams()).frame, stoppedAt, 'the frames kept changing after the press');
  });
});
