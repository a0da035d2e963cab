// A .vots dataset ("kind": "vots" in /api/datasets) opens with the eps slider and the grid renderer
// disabled, each saying why in its tooltip, and the viewer asks for no fit and no other eps.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

// The real list with the test dataset presented as a .vots file fitted at its default eps: the server
// draws it at that eps, so every frame the viewer asks for still renders.
async function presentAsVots(page, name) {
  await page.route('**/api/datasets', async (route) => {
    const real = await (await route.fetch()).json();
    for (const d of real.datasets) if (d.name === name) Object.assign(d, { kind: 'vots', eps: d.defaultEps });
    await route.fulfill({ status: 200, contentType: 'application/json', body: JSON.stringify(real) });
  });
}

test('a .vots dataset disables the eps slider and the grid renderer, with the reason', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const fits = [];
    page.on('request', (req) => { if (req.url().includes('/api/fit')) fits.push(req.url()); });
    await presentAsVots(page, ds.name);
    const viewer = new ViewerPage(page);
    // A link that asks for another eps and reference mode: the viewer keeps to what the file can draw.
    await viewer.open(`#dataset=${ds.name}&eps=${ds.defaultEps * 4}&mode=reference`);
    await viewer.waitForIdle();
    assert.ok(await viewer.epsSlider.isDisabled(), 'the eps slider is disabled');
    assert.match(await viewer.epsSlider.getAttribute('title'), /Vot-Space file/);
    const grid = viewer.byId('renderer').locator('option[value="grid"]');
    assert.ok(await grid.isDisabled(), 'the grid renderer cannot be chosen');
    assert.match(await grid.getAttribute('title'), /grid/);
    assert.equal(await viewer.mode.inputValue(), 'mip');
    assert.equal(await viewer.byId('renderer').inputValue(), 'vots');
    const hash = await viewer.hashParams();
    assert.equal(Number(hash.eps), ds.defaultEps);
    assert.equal(hash.mode ?? 'mip', 'mip');
    assert.equal(hash.renderer, undefined, 'the link must not keep asking for the grid');
    assert.deepEqual(fits, [], 'a .vots dataset is never refitted');
  });
});
