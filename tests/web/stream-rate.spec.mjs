// The viewer socket on a fast display: a drag's views go out at most every 8 ms, whatever the frame rate,
// so the page stays inside the server's 240 messages a second and keeps its socket (not cut off with 1008
// and sent back to /render).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

const DISPLAY_HZ = 500; // well past any display sold, so the page's own cap is what holds the rate
const DRAG_MS = 2500;
const MAX_VIEWS_PER_SECOND = 1000 / 8 + 5; // the page's 8 ms gap, and a little for the timing of the count

// Animation frames every 1000/hz ms, as a display of hz frames a second gives them: a MessageChannel loop,
// since timers are clamped to 4 ms when nested. Runs in the page before its scripts.
function fastDisplay(hz) {
  const pending = new Map();
  let nextId = 1;
  let last = performance.now();
  let running = false;
  const channel = new MessageChannel();
  channel.port1.onmessage = () => {
    const now = performance.now();
    if (now - last >= 1000 / hz && pending.size) {
      last = now;
      const callbacks = [...pending.values()];
      pending.clear();
      callbacks.forEach((cb) => cb(now));
    }
    running = pending.size > 0;
    if (running) channel.port2.postMessage(0);
  };
  window.requestAnimationFrame = (cb) => {
    const id = nextId++;
    pending.set(id, cb);
    if (!running) {
      running = true;
      channel.port2.postMessage(0);
    }
    return id;
  };
  window.cancelAnimationFrame = (id) => pending.delete(id);
}

test('a drag on a fast display keeps its socket: at most a view every 8 ms', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    await page.addInitScript(fastDisplay, DISPLAY_HZ);
    const sent = [];
    let closedAt = null;
    page.on('websocket', (ws) => {
      if (!ws.url().includes('/api/stream')) return;
      ws.on('framesent', ({ payload }) => sent.push({ at: Date.now(), text: String(payload) }));
      ws.on('close', () => {
        closedAt = Date.now();
      });
    });
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'az=10,el=5,zoom=1,pan=0:0,proj=ortho,fov=30' }, { transport: 'socket' });
    await viewer.waitForIdle();

    const box = await viewer.image.boundingBox();
    const x = box.x + box.width / 2;
    const y = box.y + box.height / 2;
    await page.mouse.move(x, y);
    await page.mouse.down(); // a real press, so the view captures the pointer
    const start = Date.now();
    // One pointer move per animation frame, as Chromium aligns them to the display's frames.
    await page.evaluate(
      ([x0, y0, ms]) =>
        new Promise((done) => {
          const view = document.querySelector('#view');
          const t0 = performance.now();
          let i = 0;
          const move = () => {
            i += 1;
            view.dispatchEvent(new PointerEvent('pointermove', {
              clientX: x0 + i * 0.25, clientY: y0 + 20 * Math.sin(i / 40),
              pointerId: 1, pointerType: 'mouse', buttons: 1, bubbles: true,
            }));
            if (performance.now() - t0 < ms) requestAnimationFrame(move);
            else done();
          };
          requestAnimationFrame(move);
        }),
      [x, y, DRAG_MS],
    );
    const end = Date.now();
    await page.mouse.up();
    await viewer.waitForIdle();

    assert.equal(closedAt, null, `the socket was closed ${closedAt - start} ms into the drag`);
    const views = sent.filter((m) => m.at >= start && m.at <= end && m.text.includes('"type":"view"'));
    const perSecond = (views.length * 1000) / (end - start);
    assert.ok(views.length > 10, `only ${views.length} views went out during the drag`);
    assert.ok(perSecond <= MAX_VIEWS_PER_SECOND, `${perSecond.toFixed(0)} views a second, over ${MAX_VIEWS_PER_SECOND}`);
    assert.equal(await viewer.image.getAttribute('data-transport'), 'socket', 'the still came over /render');
  });
});
