// Moving the eps slider starts a refit: progress shows, then a new Vot count and a new image swap in.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

test('eps slider refits with progress, then shows a different Vot count and image', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'az=30,el=15,zoom=1,pan=0:0,proj=ortho,fov=30' });
    await viewer.waitForIdle();
    const countBefore = (await viewer.votCount.textContent()).trim();
    const before = await viewer.framePixels();
    await viewer.screenshotPage('eps-before');

    // A much larger eps: far fewer Vots, a visibly coarser image, and a fit no earlier test ran.
    await viewer.watchProgress();
    const fits = [];
    page.on('request', (r) => {
      if (r.url().endsWith('/api/fit') && r.method() === 'POST') fits.push(r.postDataJSON());
    });
    const target = await viewer.epsSliderPositionAfter(16);
    await viewer.setEpsSlider(target);
    await page.waitForFunction(() => document.querySelector('[data-testid="status"]').dataset.state === 'fitting'
      || window.__votsProgressSeen.visible, null, { timeout: 10000 }).catch(() => {});
    await viewer.screenshotPage('eps-fitting');
    await viewer.waitForIdle();
    await viewer.screenshotPage('eps-after');

    assert.equal(fits.length, 1, `expected one POST /api/fit, saw ${JSON.stringify(fits)}`);
    assert.equal(fits[0].dataset, ds.name);
    const h = await viewer.hashParams();
    assert.equal(Number(h.eps), fits[0].eps, 'the hash carries the new eps');
    assert.ok(fits[0].eps > Number(ds.defaultEps), `eps should have grown: ${fits[0].eps}`);
    assert.ok((await viewer.progressSeen()).visible, 'the progress bar never became visible during the fit');
    assert.ok(!(await viewer.progress.isVisible()), 'the progress bar should hide after the fit');

    const countAfter = (await viewer.votCount.textContent()).trim();
    assert.notEqual(countAfter, countBefore, `Vot count stayed ${countAfter}`);
    assert.match(await viewer.fitTime.textContent(), /\d/);
    assert.match(await viewer.epsValue.textContent(), /% of range/);
    const after = await viewer.framePixels();
    assert.notDeepEqual(after.data, before.data, 'the image did not change after the refit');
  });
});
