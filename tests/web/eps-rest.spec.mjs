// A hand that holds the eps slider still: the value under it is fitted and drawn before the release, and
// the release there starts no second fit; moving on asks for the new value, as the same viewer.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

const QUIET_MS = 1500; // after the fit: long enough for a late second fit request to show up

test('a pointer resting on the eps slider fits and draws that eps before the release', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page, { log }) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'az=30,el=15,zoom=1,pan=0:0,proj=ortho,fov=30' });
    await viewer.waitForIdle();
    const countBefore = await viewer.votCount.textContent();
    const fits = viewer.recordFitRequests();

    await viewer.holdEpsSlider(60);
    await viewer.waitForFitRequests(fits, 1, 'the button still down');
    // Still held: the fit ends and the image at the new eps is shown.
    await viewer.waitForIdle();
    assert.equal(Number((await viewer.hashParams()).eps), fits[0].eps, 'the view took the rested eps');
    assert.notEqual(await viewer.votCount.textContent(), countBefore, 'the Vot count of the new fit is shown');
    assert.match(fits[0].client ?? '', /^[0-9a-f]{16}$/, 'the fit names the viewer');

    await page.mouse.up();
    await page.waitForTimeout(QUIET_MS);
    await viewer.waitForIdle();
    assert.equal(fits.length, 1, `the release where the hand rested asked again: ${JSON.stringify(fits)}`);
    assert.ok(!(await viewer.error.isVisible()), `an error is shown: ${await viewer.error.textContent()}\n${log.join('\n')}`);
  });
});

test('resting, then moving on: the release asks for its own eps, as the same viewer', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'az=30,el=15,zoom=1,pan=0:0,proj=ortho,fov=30' });
    await viewer.waitForIdle();
    const fits = viewer.recordFitRequests();

    await viewer.holdEpsSlider(40);
    await viewer.waitForFitRequests(fits, 1, 'the first rest');
    await viewer.moveHeldEpsSlider(40); // 15 ms apart: no rest on the way
    await page.mouse.up();
    await viewer.waitForFitRequests(fits, 2, 'the release');
    await viewer.waitForIdle();
    await page.waitForTimeout(QUIET_MS);

    assert.equal(fits.length, 2, `one fit for the rest, one for the release: ${JSON.stringify(fits)}`);
    assert.ok(fits[1].eps > fits[0].eps, `the release moved on: ${JSON.stringify(fits)}`);
    assert.equal(fits[1].client, fits[0].client, 'both fits come from the one viewer');
    assert.equal(Number((await viewer.hashParams()).eps), fits[1].eps, 'the view shows the release\'s eps');
    assert.ok(!(await viewer.error.isVisible()), `an error is shown: ${await viewer.error.textContent()}`);
  });
});
