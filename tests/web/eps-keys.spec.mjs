// Arrow keys on the eps slider: a run of steps fits once, for the eps the slider comes to rest on; a drag fits once.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

const PRESSES = 20;
const QUIET_MS = 1500; // after the fit: long enough for any late, uncoalesced fit request to show up

test('twenty arrow-key steps of the eps slider start one fit, for the final eps', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page, { log }) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'az=30,el=15,zoom=1,pan=0:0,proj=ortho,fov=30' });
    await viewer.waitForIdle();
    const position = Number(await viewer.epsSlider.inputValue());
    assert.ok(position + PRESSES <= Number(await viewer.epsSlider.getAttribute('max')), `the slider starts too far right (${position}) to step ${PRESSES} times`);

    const fits = viewer.recordFitRequests();
    const refused = [];
    page.on('response', (r) => {
      if (r.url().endsWith('/api/fit') && r.status() === 429) refused.push(r.status());
    });
    await viewer.stepEpsSlider(PRESSES);
    assert.equal(Number(await viewer.epsSlider.inputValue()), position + PRESSES, 'each press moved the slider a step');

    // The coalesced fit starts once the slider has rested; uncoalesced ones have started already.
    await viewer.waitForFitRequests(fits, 1, 'after the last press');
    await viewer.waitForIdle();
    await page.waitForTimeout(QUIET_MS);
    await viewer.waitForIdle();

    assert.equal(fits.length, 1, `expected one POST /api/fit for ${PRESSES} presses, saw ${JSON.stringify(fits)}`);
    assert.equal(fits[0].dataset, ds.name);
    assert.equal(Number((await viewer.hashParams()).eps), fits[0].eps, 'the fit is for the eps the link now holds');
    assert.ok(fits[0].eps > Number(ds.defaultEps), `the eps should have grown: ${fits[0].eps}`);
    assert.deepEqual(refused, [], 'the server refused fit jobs');
    assert.ok(!(await viewer.error.isVisible()), `an error is shown: ${await viewer.error.textContent()}\n${log.join('\n')}`);
  });
});

test('a mouse drag of the eps slider fits once, on release', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'az=30,el=15,zoom=1,pan=0:0,proj=ortho,fov=30' });
    await viewer.waitForIdle();
    const position = Number(await viewer.epsSlider.inputValue());
    const fits = viewer.recordFitRequests();
    await viewer.dragEpsSlider(60);
    const moved = Number(await viewer.epsSlider.inputValue());
    assert.ok(moved > position, `the drag did not move the slider (${position} -> ${moved})`);
    await viewer.waitForFitRequests(fits, 1, 'after the release');
    await viewer.waitForIdle();
    await page.waitForTimeout(QUIET_MS);
    assert.equal(fits.length, 1, `expected one POST /api/fit for one drag, saw ${JSON.stringify(fits)}`);
    assert.equal(Number((await viewer.hashParams()).eps), fits[0].eps, 'the fit is for the eps the link now holds');
  });
});
