// A dataset the server's memory budget refuses ("fits": false in /api/datasets) is listed in the picker,
// disabled, with the server's reason; the viewer opens the others as usual and never requests it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

const REFUSED = {
  name: 'zz-too-large', fits: false, dims: [512, 512, 100000], sourceType: 'int16', memoryNeeded: 400 * 2 ** 30,
  error: "dataset 'zz-too-large' (512x512x100000 int16) needs about 400.0 GB of memory but the memory budget leaves 8.0 GB",
};

// The real list with one refused dataset added, as a server with a small --memory-budget would send it.
async function addRefusedDataset(page) {
  await page.route('**/api/datasets', async (route) => {
    const real = await (await route.fetch()).json();
    real.datasets.push(REFUSED);
    await route.fulfill({ status: 200, contentType: 'application/json', body: JSON.stringify(real) });
  });
}

test('a dataset over the memory budget is listed disabled with the reason, and the rest still work', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const asked = [];
    page.on('request', (req) => { if (req.url().includes(REFUSED.name)) asked.push(req.url()); });
    await addRefusedDataset(page);
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name });
    await viewer.waitForIdle();
    const option = viewer.dataset.locator(`option[value="${REFUSED.name}"]`);
    assert.ok(await option.isDisabled(), 'a dataset that does not fit cannot be chosen');
    assert.match(await option.textContent(), /needs 400 GB, too large for the server's memory/);
    assert.equal(await option.getAttribute('title'), REFUSED.error);
    assert.equal((await viewer.hashParams()).dataset, ds.name);
    assert.deepEqual(asked, [], 'the viewer must not ask the server to load or render it');
  });
});
