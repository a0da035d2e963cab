// The viewer against a server that asks for a token: opened with #token=..., it renders, refits and keeps the
// token in its hash; opened without it, it says why nothing shows.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import crypto from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';
import { withPage, pickDataset } from './support/browser.mjs';
import { CAN_START_OWN_SERVER, OWN_SERVER_NEEDS, ownServerFolder, startOwnServer } from './support/own-server.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

// A second `vots serve` on a free loopback port that requires a token from a file.
let server = null;

async function startTokenServer() {
  const dir = ownServerFolder();
  const token = crypto.randomBytes(16).toString('hex');
  fs.writeFileSync(path.join(dir, 'token'), `${token}\n`);
  const own = await startOwnServer(dir, ['--token-file', path.join(dir, 'token')]);
  return { ...own, token };
}

before(async () => {
  if (CAN_START_OWN_SERVER) server = await startTokenServer();
});

after(() => server?.stop());

test('opened with #token=..., the viewer renders, refits and keeps the token in its hash', async (t) => {
  assert.ok(server, OWN_SERVER_NEEDS);
  const ds = await pickDataset();
  const denied = await fetch(`${server.url}/api/datasets`);
  assert.equal(denied.status, 401, 'the server must ask for the token');
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    const statuses = [];
    page.on('response', (r) => {
      if (r.url().startsWith(server.url)) statuses.push([new URL(r.url()).pathname, r.status()]);
    });
    await page.goto(`${server.url}/#dataset=${encodeURIComponent(ds.name)}&token=${server.token}`);
    await viewer.waitForIdle();
    const frame = await viewer.framePixels();
    assert.ok(frame.variance > 20, `frame looks blank: luminance variance ${frame.variance.toFixed(2)}`);
    assert.equal((await viewer.hashParams()).token, server.token, 'the view hash dropped the token');

    // A refit: POST /api/fit with the header, and its event stream with token= (EventSource sends no headers).
    const position = Number(await viewer.epsSlider.inputValue());
    await viewer.setEpsSlider(Math.min(1000, position + 200));
    await viewer.waitForIdle();
    assert.ok(!(await viewer.error.isVisible()), `unexpected error: ${await viewer.error.textContent()}`);
    const refused = statuses.filter(([, s]) => s >= 400);
    assert.deepEqual(refused, [], `refused requests: ${JSON.stringify(refused)}`);
    // Frames come over the viewer socket (opened with token=) once it is open, else from /render.
    const transport = await page.evaluate(() => document.querySelector('[data-testid="image"]').dataset.transport);
    assert.ok(['socket', 'render'].includes(transport), `no frame shown: ${transport}`);
    for (const wanted of ['/api/datasets', '/api/fit', ...(transport === 'render' ? ['/render'] : [])]) {
      assert.ok(statuses.some(([p, s]) => p === wanted && s < 300), `no answered ${wanted}: ${JSON.stringify(statuses)}`);
    }
    assert.ok(statuses.some(([p, s]) => /^\/api\/jobs\/\d+\/events$/.test(p) && s === 200),
      `the fit's event stream was not answered: ${JSON.stringify(statuses)}`);
    assert.equal((await viewer.hashParams()).token, server.token, 'the hash lost the token after the refit');
  });
  assert.ok(!server.output().includes(server.token), 'the token appears in the server output');
});

test('opened without the token, the viewer names the refusal', async (t) => {
  assert.ok(server, OWN_SERVER_NEEDS);
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await page.goto(`${server.url}/`); // the shell itself loads without the token
    const message = await viewer.waitForError(20000);
    assert.match(message, /401/);
    assert.match(message, /token/);
  });
});
