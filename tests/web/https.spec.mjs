// The viewer over HTTPS (`vots serve --tls-cert/--tls-key`, a certificate made here by the openssl
// command): Chromium trusts exactly that key (--ignore-certificate-errors-spki-list pins it; without the
// pin it refuses the page), and the frames come over the wss:// socket, not the /render fallback.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import path from 'node:path';
import { withPage, pickDataset } from './support/browser.mjs';
import { CAN_START_OWN_SERVER, OWN_SERVER_NEEDS, ownServerFolder, startOwnServer } from './support/own-server.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

let server = null;
let pin = '';

// A self-signed certificate for 127.0.0.1 and the base64 SHA-256 of its public key (what Chromium pins).
function makeCertificate(dir) {
  const cert = path.join(dir, 'site.pem');
  const key = path.join(dir, 'site.key');
  execFileSync('openssl', ['req', '-x509', '-newkey', 'ec', '-pkeyopt', 'ec_paramgen_curve:prime256v1', '-nodes',
    '-keyout', key, '-out', cert, '-days', '2', '-subj', '/CN=127.0.0.1', '-addext', 'subjectAltName=IP:127.0.0.1'],
  { stdio: 'ignore' });
  const publicKey = execFileSync('openssl', ['x509', '-in', cert, '-noout', '-pubkey']);
  const der = execFileSync('openssl', ['pkey', '-pubin', '-outform', 'der'], { input: publicKey });
  const digest = execFileSync('openssl', ['dgst', '-sha256', '-binary'], { input: der });
  return { cert, key, spki: digest.toString('base64') };
}

before(async () => {
  if (!CAN_START_OWN_SERVER) return;
  const dir = ownServerFolder();
  const { cert, key, spki } = makeCertificate(dir);
  pin = spki;
  server = await startOwnServer(dir, ['--tls-cert', cert, '--tls-key', key]);
});

after(() => server?.stop());

test('over HTTPS the viewer draws its frames from the wss:// socket', async (t) => {
  assert.ok(server, OWN_SERVER_NEEDS);
  assert.match(server.url, /^https:\/\//);
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    const sockets = [];
    page.on('websocket', (ws) => {
      const seen = { url: ws.url(), frames: 0, closed: false };
      ws.on('framereceived', () => { seen.frames += 1; });
      ws.on('close', () => { seen.closed = true; });
      sockets.push(seen);
    });
    await page.goto(`${server.url}/#dataset=${encodeURIComponent(ds.name)}`);
    await viewer.waitForIdle();
    const frame = await viewer.framePixels();
    assert.ok(frame.variance > 20, `frame looks blank: luminance variance ${frame.variance.toFixed(2)}`);
    const transport = await page.evaluate(() => document.querySelector('[data-testid="image"]').dataset.transport);
    assert.equal(transport, 'socket', 'the shown frame came from /render, not the socket');
    const secure = sockets.filter((s) => s.url.startsWith(`${server.url.replace('https:', 'wss:')}/api/stream`));
    assert.equal(secure.length, 1, `no wss:// viewer socket: ${JSON.stringify(sockets)}`);
    assert.ok(secure[0].frames >= 2, `no frames over the socket: ${JSON.stringify(secure[0])}`);
    assert.ok(!secure[0].closed, 'the socket closed');
  }, { args: [`--ignore-certificate-errors-spki-list=${pin}`] });
});

test('without the pinned key Chromium refuses the certificate', async (t) => {
  assert.ok(server, OWN_SERVER_NEEDS);
  await withPage(t, async (page) => {
    await assert.rejects(page.goto(`${server.url}/`), /ERR_CERT_AUTHORITY_INVALID/);
  });
});
