// The viewer socket (GET /api/stream): a drag shows JPEG drafts over the socket, the still after release is
// /render's PNG byte for byte, a paused drag gets its still before the release, and a page whose socket is
// refused falls back to /render; the drafts come from the draft rung's coarser fit.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset, BASE_URL } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

const START_CAM = 'az=10,el=5,zoom=1,pan=0:0,proj=ortho,fov=30';

// Every frame the page receives on its viewer socket: {header, bytes} in order.
function recordSocketFrames(page) {
  const frames = [];
  page.on('websocket', (ws) => {
    if (!ws.url().includes('/api/stream')) return;
    let header = null;
    ws.on('framereceived', ({ payload }) => {
      if (typeof payload === 'string') {
        const message = JSON.parse(payload);
        if (message.type === 'frame') header = message;
      } else if (header) {
        frames.push({ header, bytes: Buffer.from(payload) });
        header = null;
      }
    });
  });
  return frames;
}

// The /render URLs the page asks for from now on.
function recordRenders(page) {
  const renders = [];
  page.on('request', (r) => {
    if (r.url().includes('/render?')) renders.push(r.url());
  });
  return renders;
}

// The viewer on the socket transport, idle on its first full frame.
async function openIdle(page, dataset) {
  const viewer = new ViewerPage(page);
  await viewer.open({ dataset, cam: START_CAM }, { transport: 'socket' });
  await viewer.waitForIdle();
  return viewer;
}

test('a drag shows drafts over the socket and the still after release is /render\'s PNG', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const frames = recordSocketFrames(page);
    const renders = recordRenders(page);
    const viewer = await openIdle(page, ds.name);
    const rendersBefore = renders.length;
    const framesBefore = frames.length;

    await viewer.drag(150, -80);
    await viewer.waitForIdle();

    const during = frames.slice(framesBefore);
    const drafts = during.filter((f) => !f.header.still);
    assert.ok(drafts.length >= 2, `expected several drafts over the socket, got ${drafts.length}`);
    for (const d of drafts) {
      assert.equal(d.header.format, 'image/jpeg');
      assert.deepEqual([...d.bytes.subarray(0, 2)], [0xff, 0xd8], 'a draft that is no JPEG');
    }
    assert.equal(renders.length, rendersBefore, `the drag went through /render: ${renders.slice(rendersBefore)}`);
    const still = during.at(-1);
    assert.ok(still.header.still, 'the last frame after release is not the still');
    assert.equal(still.header.format, 'image/png');

    const shown = await page.evaluate(() => {
      const img = document.querySelector('[data-testid="image"]');
      return { url: img.dataset.frameUrl, transport: img.dataset.transport, draftHidden: document.querySelector('#draft').hidden };
    });
    assert.equal(shown.transport, 'socket');
    assert.ok(shown.draftHidden, 'the draft canvas still covers the still');
    const res = await page.request.get(`${BASE_URL}/${shown.url}`);
    assert.equal(res.status(), 200);
    const png = await res.body();
    assert.ok(png.equals(still.bytes), `the still (${still.bytes.length} bytes) differs from /render's PNG (${png.length})`);
    const size = new URL(shown.url, BASE_URL).searchParams.get('size');
    assert.equal(`${still.header.width}x${still.header.height}`, size);
  });
});

// Resolves once the server's warm-up fits have all run (the draft rung's is the first of them).
async function warmUpsDone() {
  for (let i = 0; i < 600; i++) {
    const warm = (await (await fetch(`${BASE_URL}/api/stats`)).json()).warmUps;
    if (warm.finished > 0 && !warm.running) return;
    await new Promise((r) => setTimeout(r, 100));
  }
  throw new Error('the warm-up fits did not finish within 60 s');
}

test('a drag\'s drafts come from the draft rung\'s coarser fit, and the still is at the view\'s eps', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const frames = recordSocketFrames(page);
    const viewer = await openIdle(page, ds.name);
    await warmUpsDone();
    await page.evaluate(() => {
      window.__shown = [];
      document.querySelector('[data-testid="image"]').addEventListener('vots:frame', (e) => {
        window.__shown.push({ eps: e.detail.eps, still: e.detail.still, votCount: e.detail.votCount });
      });
    });
    const before = frames.length;
    await viewer.drag(160, 60);
    await viewer.waitForIdle();

    const viewEps = Number((await viewer.hashParams()).eps);
    const during = frames.slice(before);
    const drafts = during.filter((f) => !f.header.still);
    assert.ok(drafts.length >= 2, `expected several drafts, got ${drafts.length}`);
    // The rung is about 4 x eps (at most a tenth of the range): coarser, with fewer Vots than the still.
    // The drag's first draft comes from it (nothing is measured yet); later ones may be drawn at eps where
    // drafts at eps would be full size within the budget (a fast host, a small volume).
    const still = during.at(-1);
    assert.ok(still.header.still && still.header.draftEps === undefined, JSON.stringify(still.header));
    const rungEps = drafts[0].header.draftEps;
    assert.ok(rungEps > 1.5 * viewEps, `the first draft is at the view's eps ${viewEps}: ${JSON.stringify(drafts[0].header)}`);
    for (const d of drafts.filter((f) => f.header.draftEps !== undefined)) {
      assert.equal(d.header.draftEps, rungEps);
      assert.ok(d.header.votCount < still.header.votCount, `a draft of no fewer Vots: ${JSON.stringify(d.header)}`);
    }
    // The page says what each frame shown was drawn at.
    const shown = await page.evaluate(() => window.__shown);
    assert.ok(shown.length >= 2, `frames shown: ${JSON.stringify(shown)}`);
    assert.ok(shown.some((f) => f.eps === rungEps), `no frame shown at the rung: ${JSON.stringify(shown)}`);
    for (const f of shown) assert.ok(f.eps === rungEps || f.eps === viewEps, `a frame shown at eps ${f.eps}`);
    assert.equal(shown.at(-1).eps, viewEps);
    assert.equal(shown.at(-1).still, true);
  });
});

test('a page whose socket is refused shows its frames through /render', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    // The socket opens and is closed at once, as a proxy that does not pass WebSockets would.
    await page.routeWebSocket(/\/api\/stream/, (ws) => ws.close({ code: 1011, reason: 'refused' }));
    const renders = recordRenders(page);
    const viewer = await openIdle(page, ds.name);
    await viewer.drag(100, 0);
    await viewer.waitForIdle();
    const transport = await page.evaluate(() => document.querySelector('[data-testid="image"]').dataset.transport);
    assert.equal(transport, 'render');
    assert.ok(renders.length >= 2, `expected /render frames, saw ${renders.length}`);
    const frame = await viewer.framePixels();
    assert.ok(frame.variance > 20, `frame looks blank: luminance variance ${frame.variance.toFixed(2)}`);
  });
});

test('while zooming over the socket the scale bar follows the frame shown, not the hand', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = await openIdle(page, ds.name);
    // The bar as drawn at each frame (after the page's own listener, registered first) and at each pointer
    // move (before the page's handler sees it, so it shows what the last move left), with the zoom of the
    // frame then on screen.
    await page.evaluate(() => {
      window.__bars = [];
      let frameZoom = null;
      const sample = () => {
        const bar = document.querySelector('[data-testid="scalebar"]');
        if (frameZoom !== null) window.__bars.push({ zoom: frameZoom, mm: Number(bar.dataset.mm), px: Number(bar.dataset.px) });
      };
      document.querySelector('[data-testid="image"]').addEventListener('vots:frame', (e) => {
        frameZoom = e.detail.view.cam.zoom;
        sample();
      });
      document.querySelector('#view').addEventListener('pointermove', sample, { capture: true });
    });
    await viewer.drag(0, -150, { button: 'right' });
    await viewer.waitForIdle();
    const bars = await page.evaluate(() => window.__bars);
    assert.ok(bars.length >= 3, `expected several frames during the zoom, got ${bars.length}`);
    const zooms = new Set(bars.map((b) => b.zoom));
    assert.ok(bars.length >= 10, `expected samples at the pointer moves too, got ${bars.length}`);
    assert.ok(zooms.size >= 2, 'the zoom did not change between frames');
    // Pixels per mm grow with the zoom of the frame's own camera: one ratio for every frame shown.
    const ratios = bars.map((b) => b.px / b.mm / b.zoom);
    for (const r of ratios) assert.ok(Math.abs(r / ratios[0] - 1) < 1e-3, `scale bar off its frame: ${JSON.stringify(bars)}`);
  });
});

// The views the page sends on its viewer socket: {seq, still} in order.
function recordSocketViews(page) {
  const views = [];
  page.on('websocket', (ws) => {
    if (!ws.url().includes('/api/stream')) return;
    ws.on('framesent', ({ payload }) => {
      if (typeof payload !== 'string') return;
      const message = JSON.parse(payload);
      if (message.type === 'view') views.push({ seq: message.seq, still: message.still });
    });
  });
  return views;
}

test('a drag that pauses gets its exact frame before the release, and the release asks for no other', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const frames = recordSocketFrames(page);
    const views = recordSocketViews(page);
    const viewer = await openIdle(page, ds.name);
    const seqBefore = views.length ? views.at(-1).seq : 0;
    const box = await viewer.image.boundingBox();
    const x = box.x + box.width / 2;
    const y = box.y + box.height / 2;
    await page.mouse.move(x, y);
    await page.mouse.down();
    for (let i = 1; i <= 10; i++) {
      await page.mouse.move(x + 8 * i, y);
      await page.waitForTimeout(15);
    }
    // The hand rests with the button held: the still of this camera comes now.
    const stillOfDrag = () => frames.find((f) => f.header.still && f.header.seq > seqBefore);
    const deadline = Date.now() + 60000;
    while (!stillOfDrag() && Date.now() < deadline) await page.waitForTimeout(50);
    const still = stillOfDrag();
    assert.ok(still, 'no still came while the drag paused');
    await page.waitForTimeout(200);
    const stillsAsked = views.filter((v) => v.still).length;
    await page.mouse.up();
    await viewer.waitForIdle();
    assert.equal(views.filter((v) => v.still).length, stillsAsked, 'the release asked for another still');
    const shown = await page.evaluate(() => document.querySelector('[data-testid="image"]').dataset.frameUrl);
    const res = await page.request.get(`${BASE_URL}/${shown}`);
    assert.equal(res.status(), 200);
    const png = await res.body();
    const last = frames.filter((f) => f.header.still).at(-1);
    assert.ok(png.equals(last.bytes), 'the still shown after the release is not /render\'s PNG of its camera');
  });
});
