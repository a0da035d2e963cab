// Negative cases: bad links and server failures show the error banner; superseded frames stay silent.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

test('a bad dataset name in the URL shows an error and falls back to a real dataset', async (t) => {
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open('#dataset=no-such-volume&cam=anterior');
    const text = await viewer.waitForError();
    assert.match(text, /no-such-volume/);
    await viewer.waitForIdle();
    await viewer.screenshotPage('error-bad-dataset');
    assert.ok(await viewer.error.isVisible(), 'the banner must stay until dismissed');
    assert.notEqual((await viewer.hashParams()).dataset, 'no-such-volume');
    await page.getByTestId('error-close').click();
    assert.ok(!(await viewer.error.isVisible()));
  });
});

test('a malformed camera in the URL is reported', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'az=abc,el=0' });
    assert.match(await viewer.waitForError(), /az/);
  });
});

test('a 4xx JSON error from /render is shown, with the server message', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await page.route('**/render?**', (route) => route.fulfill({
      status: 400, contentType: 'application/json', body: JSON.stringify({ error: 'size 99999x1 is too large' }),
    }));
    await viewer.open({ dataset: ds.name });
    const text = await viewer.waitForError();
    assert.match(text, /size 99999x1 is too large/);
    assert.match(text, /400/);
  });
});

test('the real server answers a bad dataset with a 4xx JSON error, which the page would show', async () => {
  const { BASE_URL } = await import('./support/browser.mjs');
  const res = await fetch(`${BASE_URL}/render?dataset=no-such-volume&cam=anterior&size=64x64&client=t`);
  assert.ok(res.status >= 400 && res.status < 500, `status ${res.status}`);
  const body = await res.json();
  assert.equal(typeof body.error, 'string');
});

test('a network failure is shown', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await page.route('**/render?**', (route) => route.abort('connectionrefused'));
    await viewer.open({ dataset: ds.name });
    assert.match(await viewer.waitForError(), /cannot reach the server/i);
  });
});

test('409 superseded answers are ignored silently', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    let first = true;
    await page.route('**/render?**', (route) => {
      if (first) {
        first = false;
        return route.fulfill({ status: 409, contentType: 'application/json', body: '{"error":"superseded"}' });
      }
      return route.continue();
    });
    await viewer.open({ dataset: ds.name });
    // The first frame was "superseded"; a later action renders normally and no banner ever appeared.
    await page.waitForFunction(() => document.querySelector('[data-testid="status"]').dataset.state === 'idle');
    assert.ok(!(await viewer.error.isVisible()), 'superseded must not show an error');
    await viewer.viewButton('posterior').click();
    await viewer.waitForIdle();
    assert.ok(!(await viewer.error.isVisible()));
  });
});
