// The PACS panel against a real Orthanc (the pacs fixture, VOTS_ORTHANC_STATE): search, a study's series,
// opening one with progress into a dataset the viewer shows, a refusal shown in the panel, and Send to PACS.
// Run by ctest as Pacs.WebStudyBrowser (tests/pacs/CMakeLists.txt); not in run.sh's default spec list.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { artifactPath, withPage } from '../support/browser.mjs';
import { CAN_START_OWN_SERVER, ownServerFolder, startOwnServer } from '../support/own-server.mjs';
import { ViewerPage } from '../pages/ViewerPage.mjs';

const STATE = process.env.VOTS_ORTHANC_STATE;
const CRANIUM_SERIES = '1.2.826.0.1.3680043.10.1234.202';
const CRANIUM_DATASET = `orthanc-${CRANIUM_SERIES.replaceAll('.', '_')}`;
const SEND_SERIES = '1.2.826.0.1.3680043.10.1234.207'; // pacs_setup.sh's send-source, in a study of its own
const SEND_DATASET = `orthanc-${SEND_SERIES.replaceAll('.', '_')}`;

let server = null;

// `vots serve` with the fixture's Orthanc twice: with its credentials ("orthanc") and without ("nocreds").
async function startPacsServer() {
  const port = fs.readFileSync(path.join(STATE, 'port'), 'utf8').trim();
  const url = `dicomweb+http://127.0.0.1:${port}/dicom-web`;
  const own = await startOwnServer(ownServerFolder(), ['--dicomweb', `orthanc=${url}`,
    '--dicomweb-auth', `orthanc=${path.join(STATE, 'auth')}`, '--dicomweb', `nocreds=${url}`]);
  return { ...own, base: own.url, password: fs.readFileSync(path.join(STATE, 'password'), 'utf8').trim() };
}

before(async () => {
  if (CAN_START_OWN_SERVER && STATE) server = await startPacsServer();
});

after(() => server?.stop());

test('search, list a study\'s series, open one with progress, and see it', async (t) => {
  assert.ok(server, 'needs VOTS_BIN, VOTS_DATA (run.sh) and VOTS_ORTHANC_STATE (the ctest Orthanc fixture)');
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    const opens = [];
    page.on('response', async (r) => {
      if (/\/api\/pacs\/(opens\/\d+|.*\/open)$/.test(new URL(r.url()).pathname)) opens.push(await r.json());
    });
    await page.goto(`${server.base}/`);
    const panel = viewer.byId('pacs');
    await panel.waitFor({ state: 'visible' });

    await viewer.byId('pacs-patient-name').fill('vots'); // a prefix, in any case
    await viewer.byId('pacs-modality').fill('ct');
    await viewer.byId('pacs-search').click();
    const study = viewer.byId('pacs-studies').locator(`li[data-study-uid="${CRANIUM_SERIES}.0"]`);
    await study.waitFor({ state: 'visible' });
    assert.match(await study.textContent(), /Vots, Phantom/);
    assert.match(await study.textContent(), /1 series, 108 images/);
    assert.ok(await viewer.byId('pacs-studies').locator('li').count() >= 3, 'the fixture holds three studies');

    await study.click();
    const series = viewer.byId('pacs-series').locator(`li[data-series-uid="${CRANIUM_SERIES}"]`);
    await series.waitFor({ state: 'visible' });
    assert.match(await series.textContent(), /Cranium/);
    assert.match(await series.textContent(), /CT · 108 images/);
    await panel.screenshot({ path: artifactPath('pacs-panel.png') });

    await series.getByRole('button', { name: 'Open' }).click();
    await viewer.byId('pacs-progress-box').waitFor({ state: 'visible' });
    await page.waitForFunction((name) => document.querySelector('[data-testid="dataset"]').value === name,
      CRANIUM_DATASET, { timeout: 120000 });
    await viewer.waitForIdle(120000);
    assert.match(await viewer.byId('pacs-progress-label').textContent(), /^Opened/);
    assert.equal(await viewer.byId('pacs-progress').getAttribute('value'), '108');
    const last = opens.at(-1);
    assert.equal(last.state, 'done');
    assert.equal(last.received, 108);
    assert.equal(last.total, 108);
    assert.ok(opens.every((o) => o.received <= o.total || o.total === 0), 'progress beyond the series');
    const frame = await viewer.framePixels();
    assert.ok(frame.variance > 20, `the opened series' frame looks blank (variance ${frame.variance.toFixed(2)})`);
    assert.equal((await viewer.hashParams()).dataset, CRANIUM_DATASET);
    assert.ok(!(await viewer.error.isVisible()), `unexpected error: ${await viewer.error.textContent()}`);
    await viewer.screenshotPage('pacs-opened-series');
  });
});

test('refused credentials show the PACS\'s 401 in the panel, never the password', async (t) => {
  assert.ok(server, 'needs VOTS_BIN, VOTS_DATA (run.sh) and VOTS_ORTHANC_STATE (the ctest Orthanc fixture)');
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await page.goto(`${server.base}/`);
    await viewer.byId('pacs').waitFor({ state: 'visible' });
    await viewer.byId('pacs-service').selectOption('nocreds');
    await viewer.byId('pacs-search').click();
    const error = viewer.byId('pacs-error');
    await error.waitFor({ state: 'visible' });
    const text = await error.textContent();
    assert.match(text, /refused the credentials/);
    assert.match(text, /HTTP 401/);
    assert.ok(!text.includes(server.password), 'the password is shown');
    assert.equal(await viewer.byId('pacs-studies').locator('li').count(), 0);
  });
});

test('a PACS dataset\'s view is sent back as a slab sweep with progress and a result line', async (t) => {
  assert.ok(server, 'needs VOTS_BIN, VOTS_DATA (run.sh) and VOTS_ORTHANC_STATE (the ctest Orthanc fixture)');
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    const stores = [];
    page.on('response', (r) => {
      if (!/\/api\/pacs\/(stores\/\d+|[^/]+\/store)$/.test(new URL(r.url()).pathname)) return;
      // A poll answered as the test ends has no body left to read once the page is closed: not a failure.
      r.json().then((store) => stores.push(store), () => {});
    });
    await page.goto(`${server.base}/`);
    await viewer.byId('pacs').waitFor({ state: 'visible' });
    const folderDataset = await viewer.byId('dataset').evaluate(
      (select) => [...select.options].map((o) => o.value).find((name) => !name.startsWith('orthanc-')));
    await viewer.byId('dataset').selectOption(folderDataset);
    await viewer.waitForIdle(120000);
    assert.ok(await viewer.byId('pacs-send').isHidden(), `Send to PACS offered for ${folderDataset} of the data folder`);

    await viewer.byId('pacs-search').click();
    const study = viewer.byId('pacs-studies').locator(`li[data-study-uid="${SEND_SERIES}.0"]`);
    await study.waitFor({ state: 'visible' });
    await study.click();
    const series = viewer.byId('pacs-series').locator(`li[data-series-uid="${SEND_SERIES}"]`);
    await series.getByRole('button', { name: 'Open' }).click();
    await page.waitForFunction((name) => document.querySelector('[data-testid="dataset"]').value === name,
      SEND_DATASET, { timeout: 120000 });
    await viewer.waitForIdle(120000);

    const section = viewer.byId('pacs-send');
    await section.waitFor({ state: 'visible' });
    assert.equal(await viewer.byId('pacs-send-thickness').inputValue(), '10');
    assert.equal(await viewer.byId('pacs-send-step').inputValue(), '5');
    assert.match(await viewer.byId('pacs-send-what').textContent(), /^MIP · .* → orthanc$/);
    await viewer.byId('pacs-send-step').fill('4');
    await viewer.byId('pacs-send-button').click();
    const result = viewer.byId('pacs-send-result');
    await page.waitForFunction(() => /^Stored/.test(document.querySelector('[data-testid="pacs-send-result"]').textContent),
      undefined, { timeout: 120000 });
    const text = await result.textContent();
    const last = stores.at(-1);
    assert.equal(last.state, 'done');
    assert.ok(last.total > 1, `a sweep of ${last.total} slabs`);
    assert.equal(last.stored, last.total);
    assert.equal(text, `Stored ${last.total} images: MIP 10 mm / 4 mm coronal (on orthanc)`);
    assert.ok(stores.every((s) => s.drawn <= s.total), 'progress beyond the sweep');
    assert.ok(await viewer.byId('pacs-send-error').isHidden(), await viewer.byId('pacs-send-error').textContent());
    await section.scrollIntoViewIfNeeded();
    await section.screenshot({ path: artifactPath('pacs-send.png') });

    // A send of many slabs, cancelled while they are drawn: it ends cancelled and the panel says so.
    assert.ok(await viewer.byId('pacs-send-cancel').isHidden(), 'Cancel offered with no send running');
    await viewer.byId('pacs-send-step').fill('0.15'); // about 140 slabs: under the sweep's pixel bound
    await viewer.byId('pacs-send-button').click();
    await viewer.byId('pacs-send-cancel').waitFor({ state: 'visible' });
    await page.waitForFunction(() => /^Drawing/.test(
      document.querySelector('[data-testid="pacs-send-progress-label"]').textContent), undefined, { timeout: 120000 });
    await viewer.byId('pacs-send-cancel').click();
    await page.waitForFunction(() => /cancelled/.test(document.querySelector('[data-testid="pacs-send-result"]').textContent),
      undefined, { timeout: 60000 });
    assert.equal(await result.textContent(), 'Send cancelled: nothing stored.');
    assert.ok(await viewer.byId('pacs-send-cancel').isHidden(), 'Cancel still offered after the send ended');
    assert.ok(await viewer.byId('pacs-send-error').isHidden(), await viewer.byId('pacs-send-error').textContent());
    const id = stores.at(-1).id;
    // The panel settles at once; the server's send ends at its next slab.
    const ended = await page.evaluate(async (storeId) => {
      for (let i = 0; i < 600; i += 1) {
        const store = await (await fetch(`api/pacs/stores/${storeId}`)).json();
        if (!['queued', 'drawing', 'storing'].includes(store.state)) return store;
        await new Promise((resolve) => { setTimeout(resolve, 100); });
      }
      return null;
    }, id);
    assert.ok(ended, 'the cancelled send never ended');
    assert.equal(ended.state, 'cancelled');
    assert.ok(ended.drawn < ended.total, `all ${ended.total} slabs drawn before the cancel`);
    assert.equal(ended.stored, 0);
  });
});
