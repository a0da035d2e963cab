// The viewer against a server that asks for a token: opened with #token=..., it renders, refits and keeps the
// token in its hash; opened without it, it says why nothing shows; its viewer socket asks for the token and
// refuses a page of another origin.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import crypto from 'node:crypto';
import fs from 'node:fs';
import http from 'node:http';
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
    await viewer.setEpsSlider(await viewer.epsSliderPositionAfter(13));
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

// Opens a WebSocket from the page to `url`: {opened, error} with the handshake's error as Chromium words
// it ("Unexpected response code: 403"), seen through Playwright's view of the page's sockets.
async function trySocket(page, url) {
  const errors = [];
  const listener = (ws) => ws.on('socketerror', (message) => errors.push(message));
  page.on('websocket', listener);
  const opened = await page.evaluate((u) => new Promise((resolve) => {
    const ws = new WebSocket(u);
    ws.onopen = () => {
      ws.close();
      resolve(true);
    };
    ws.onclose = () => resolve(false);
  }), url);
  page.off('websocket', listener);
  return { opened, error: errors.join(' ') };
}

test('the viewer socket opens with the token from the server\'s own page only', async (t) => {
  assert.ok(server, OWN_SERVER_NEEDS);
  const socketUrl = `${server.url.replace(/^http/, 'ws')}/api/stream`;
  await withPage(t, async (page) => {
    await page.goto(`${server.url}/`);
    const withToken = await trySocket(page, `${socketUrl}?token=${server.token}`);
    assert.ok(withToken.opened, `the own page with the token was refused: ${withToken.error}`);
    const without = await trySocket(page, socketUrl);
    assert.ok(!without.opened, 'a socket without the token opened');
    // Chromium words a 401 at the handshake as "HTTP Authentication failed; no valid credentials available".
    assert.match(without.error, /401|Authentication failed/);
  });
  await withPage(t, async (page) => {
    // A page of another origin that knows the token: its Origin is refused. It is served from another
    // loopback port by the test, since Chromium itself keeps a public site's page from opening sockets to
    // loopback (ERR_BLOCKED_BY_LOCAL_NETWORK_ACCESS_CHECKS) before the server is asked.
    const site = http.createServer((req, res) => res.end('<!doctype html><title>foreign</title>'));
    await new Promise((resolve) => site.listen(0, '127.0.0.1', resolve));
    await page.goto(`http://127.0.0.1:${site.address().port}/`);
    const foreign = await trySocket(page, `${socketUrl}?token=${server.token}`);
    site.close();
    assert.ok(!foreign.opened, 'a page of another origin opened the viewer socket');
    assert.match(foreign.error, /403/);
  });
});
