// A view whose Vot-Space is still being fitted shows the exact grid meanwhile, then swaps in the Vots.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { BASE_URL, withPage, pickDataset } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

test('while the first fit runs the exact grid is shown, and the Vots replace it once the fit is done', async (t) => {
  const ds = await pickDataset();
  // An eps no other spec fits, so the server has to fit it now (a fitted key would answer "done" at once).
  const eps = Number((Number(ds.defaultEps) * 1.37).toPrecision(6));
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    // Hold the fit's event stream: the page then knows only that the fit runs, however fast it really is.
    let release;
    const released = new Promise((r) => {
      release = r;
    });
    await page.route('**/api/jobs/*/events*', async (route) => {
      await released;
      await route.continue();
    });
    const renders = [];
    page.on('request', (r) => {
      if (r.url().includes('/render?')) renders.push(new URL(r.url()));
    });

    await viewer.open({ dataset: ds.name, eps: String(eps), cam: 'anterior' });
    await page.waitForFunction(() => document.querySelector('[data-testid="image"]')?.dataset.renderer === 'grid',
      null, { timeout: 30000 });
    assert.equal(await page.evaluate(() => document.querySelector('[data-testid="status"]').dataset.state), 'fitting');
    assert.match(await page.evaluate(() => document.querySelector('[data-testid="status"]').textContent),
      /exact grid shown meanwhile/);
    assert.ok((await viewer.framePixels()).variance > 20, 'the grid preview looks blank');
    assert.ok(renders.length > 0 && renders.every((u) => u.searchParams.get('renderer') === 'grid'),
      `before the fit is done every frame should come from the grid: ${renders.map((u) => u.search)}`);
    await viewer.screenshotPage('first-image-grid-while-fitting');

    release();
    await page.waitForFunction(() => document.querySelector('[data-testid="image"]')?.dataset.renderer === 'vots',
      null, { timeout: 60000 });
    await viewer.waitForIdle();
    const shown = new URL(await viewer.image.getAttribute('data-frame-url'), BASE_URL + '/');
    assert.equal(shown.searchParams.get('renderer'), null, 'the final frame is drawn from the Vots');
    assert.equal(Number(shown.searchParams.get('eps')), eps, 'at the eps the link asked for');
    assert.ok(Number((await viewer.votCount.textContent()).replace(/\D/g, '')) > 0, 'no Vot count after the fit');
    assert.ok(!(await viewer.error.isVisible()), `an error is shown: ${await viewer.error.textContent()}`);
    await viewer.screenshotPage('first-image-vots-after-fit');
  });
});
