// The default eps is the server's alone: without one the viewer says so and fits nothing until the user picks an eps.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

test('a dataset listed without defaultEps shows why nothing renders, then the slider fits and renders', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await page.route('**/api/datasets', async (route) => {
      const res = await route.fetch();
      const body = await res.json();
      for (const d of body.datasets) delete d.defaultEps;
      await route.fulfill({ response: res, json: body });
    });
    const asked = [];
    page.on('request', (r) => {
      if (r.url().includes('/render?') || r.url().endsWith('/api/fit')) asked.push(`${r.method()} ${r.url()}`);
    });
    await viewer.open({ dataset: ds.name, cam: 'anterior' });
    assert.match(await viewer.waitForError(), /no default/);
    await page.waitForFunction(() => document.querySelector('[data-testid="status"]').dataset.state === 'error');
    assert.match(await viewer.epsValue.textContent(), /no default/);
    assert.equal((await viewer.hashParams()).eps, undefined, 'the link carries an eps nobody chose');
    await page.waitForTimeout(500); // a frame or fit the page wrongly sent would have left by now
    assert.deepEqual(asked, [], 'with no eps the page must neither fit nor render');

    const fits = [];
    page.on('request', (r) => {
      if (r.url().endsWith('/api/fit') && r.method() === 'POST') fits.push(r.postDataJSON());
    });
    await viewer.setEpsSlider(40); // the ladder's 4.7 % of the range
    await viewer.waitForIdle();
    assert.equal(fits.length, 1, `expected one POST /api/fit, saw ${JSON.stringify(fits)}`);
    assert.ok(fits[0].eps > 0);
    assert.equal(Number((await viewer.hashParams()).eps), fits[0].eps);
    assert.match(await viewer.epsValue.textContent(), /% of range/);
    assert.ok(!(await viewer.error.isVisible()), 'the fit succeeded, so its banner should be gone');
    assert.ok((await viewer.framePixels()).variance > 20, 'the frame looks blank');
  });
});
