// Benchmark: a drag in headless Chromium at 1400x900 over the viewer socket and over GET /render, same run.
//
//   VOTS_URL=http://127.0.0.1:8080 [VOTS_BENCH_BROWSERS=separate] [VOTS_DRAG_HOLD_MS=MS] [VOTS_DRAG_PAUSE_MS=MS]
//       node bench/stream_drag.mjs [dataset] [runs] [drag ms] [pages]
// For each transport (alternating, so both see the same machine load) and run: frames/s shown while the
// mouse moves, their median size and how many came from a coarser fit (the socket's draft rung), release
// to the full-resolution lossless frame, and pointer move to the first frame that shows it (p50, p90).
// Medians over the runs. VOTS_DRAG_HOLD_MS: the hand holds the button still that long after its last move
// before the release (default 0: a release at the next move);
// VOTS_DRAG_PAUSE_MS: it stops that long halfway, and the first move after the pause is timed too
// (bench/drag.mjs). Needs a running `vots serve` and tests/web/node_modules (tests/web/run.sh installs it).
import { withPage, withPages } from '../tests/web/support/browser.mjs';
import { median, ms, quantile } from './stats.mjs';
import { ViewerPage } from '../tests/web/pages/ViewerPage.mjs';
import { dragAcrossImage } from './drag.mjs';

const dataset = process.argv[2] || 'cranium';
const runs = Number(process.argv[3] || 5);
const dragMs = Number(process.argv[4] || 2000);
// The two pages start at different cameras, and each invocation elsewhere, so that no frame is met in the
// server's frame cache (an earlier run's, or the other page's).
const START_AZ = Math.round((Date.now() / 1000) % 3600) / 10;
const CAMS = {
  socket: `az=${START_AZ},el=15,zoom=1,pan=0:0,proj=ortho,fov=30`,
  render: `az=${START_AZ + 90},el=10,zoom=1,pan=0:0,proj=ortho,fov=30`,
};

// A socket frame's parts: the server's wait before the draw, its render, the encoding (named encodedAs),
// the rest of the draw (preparing, the render queue), and the rest after it (send, transfer, decode, show).
function frameParts(f, encodedAs = 'encode') {
  return {
    wait: f.waitMs,
    render: f.frameMs,
    [encodedAs]: f.encodeMs,
    queue: f.drawMs - f.frameMs - f.encodeMs,
    deliver: f.shownAt - f.sentAt - f.waitMs - f.drawMs,
  };
}

// The medians of the frames' parts, part by part.
function framePartMedians(fs) {
  const parts = fs.map((f) => frameParts(f));
  return Object.fromEntries(Object.keys(parts[0]).map((k) => [k, median(parts.map((p) => p[k]))]));
}

// One drag: the page records its pointer moves and the frames it shows (vots:frame); returns the figures.
async function dragOnce(page, viewer, run) {
  await page.evaluate(() => {
    const view = document.querySelector('#view');
    const img = document.querySelector('[data-testid="image"]');
    window.__bench = { moves: [], frames: [], up: null };
    if (window.__benchListening) return; // once per page: each drag only resets what they record
    window.__benchListening = true;
    view.addEventListener('pointermove', () => window.__bench.moves.push(performance.now()), { capture: true });
    view.addEventListener('pointerup', () => { window.__bench.up = performance.now(); }, { capture: true });
    img.addEventListener('vots:frame', (e) => window.__bench.frames.push({ ...e.detail, shownAt: performance.now() }));
  });
  // Each drag ends at a camera not drawn before (no frame-cache hit for the exact frame).
  await dragAcrossImage(page, viewer, dragMs, 150 + 23 * run);
  await viewer.waitForIdle(120000);
  const { moves, frames, up } = await page.evaluate(() => window.__bench);
  const duringDrag = frames.filter((f) => f.shownAt >= moves[0] && f.shownAt <= up && !f.still);
  const socketDrafts = duringDrag.filter((f) => f.drawMs !== undefined); // (the server's times come with them)
  // The exact frame of the camera where the drag ended: asked for at release, or (socket) at a pause
  // before it, when it can be on screen before the release (0 ms).
  const still = frames.find((f) => f.still && f.sentAt >= moves.at(-1));
  // A move is shown by the first frame whose view was asked for after it.
  const latencies = [];
  let afterPause = NaN; // the first move after the longest gap between moves (VOTS_DRAG_PAUSE_MS)
  let longestGap = 0;
  moves.forEach((m, i) => {
    const f = frames.find((fr) => fr.sentAt >= m);
    if (f) latencies.push(f.shownAt - m);
    if (i > 0 && m - moves[i - 1] > longestGap) {
      longestGap = m - moves[i - 1];
      afterPause = f ? f.shownAt - m : NaN;
    }
  });
  return {
    fps: (duringDrag.length * 1000) / (up - moves[0]),
    width: median(duringDrag.map((f) => f.width)),
    height: median(duringDrag.map((f) => f.height)),
    releaseMs: still ? Math.max(0, still.shownAt - up) : NaN,
    fullSize: still ? `${still.width}x${still.height}` : '?',
    // The drafts' linear scale of the full frame (issue 37 asks for at least half).
    linear: still ? median(duringDrag.map((f) => f.width)) / still.width : NaN,
    // Drafts drawn from a coarser fit than the still's (the socket's draft rung) and that fit's eps.
    coarser: still ? duringDrag.filter((f) => f.eps !== still.eps).length : 0,
    coarserEps: still ? duringDrag.find((f) => f.eps !== still.eps)?.eps : undefined,
    drafts: duringDrag.length,
    p50: quantile(latencies, 0.5),
    afterPause,
    p90: quantile(latencies, 0.9),
    transport: still?.transport || frames.at(-1)?.transport,
    stillsWhileDragging: frames.filter((f) => f.still && f.shownAt >= moves[0] && f.shownAt <= up).length,
    stillDrawMs: still?.drawMs,
    // Where a draft's time goes (socket drafts, medians over the drag): the same parts as the still's.
    draftParts: socketDrafts.length ? framePartMedians(socketDrafts) : undefined,
    // Where release -> lossless goes (socket stills): the page's delay to ask, then the frame's parts (the
    // server's wait is behind a draft of this socket, the encoding is the PNG).
    stillParts: still && still.drawMs !== undefined ? { ask: still.sentAt - up, ...frameParts(still, 'png') } : undefined,
  };
}

const results = { socket: [], render: [] };
const pages = {};
const fakeTest = { name: 'stream-drag-bench' };
// Several viewers at once (the 4th argument, N > 0): N socket pages, each its own camera, dragged at the
// same time; per page frames/s and release -> lossless, and the refusals they met (HTTP 429/503 answers
// and the socket's error messages). Without it: the socket against /render, as above.
const manyPages = Number(process.argv[5] || 0);

// VOTS_BENCH_BROWSERS=separate: each page in a browser of its own (eight users on one machine), else all
// pages in one browser, each in a window of its own (eight views in one browser).
const separateBrowsers = process.env.VOTS_BENCH_BROWSERS === 'separate';

// Opens n fresh pages, then fn(pages).
function openPages(n, fn, opened = []) {
  if (!separateBrowsers) return withPages(n, fn);
  if (opened.length === n) return fn(opened);
  return withPage(fakeTest, (page) => openPages(n, fn, [...opened, page]));
}

async function dragManyAtOnce() {
  await openPages(manyPages, async (pageList) => {
    const opened = [];
    for (const [i, page] of pageList.entries()) {
      await page.setViewportSize({ width: 1400, height: 900 });
      const refusals = { count: 0 };
      page.on('response', (r) => {
        if (r.status() === 429 || r.status() === 503) refusals.count += 1;
      });
      page.on('websocket', (ws) => ws.on('framereceived', ({ payload }) => {
        if (typeof payload === 'string' && payload.includes('"type":"error"')) refusals.count += 1;
      }));
      const viewer = new ViewerPage(page);
      await viewer.open({ dataset, cam: `az=${START_AZ + 45 * i},el=15,zoom=1,pan=0:0,proj=ortho,fov=30` },
        { transport: 'socket' });
      opened.push({ page, viewer, refusals, fps: [], releaseMs: [] });
    }
    await Promise.all(opened.map(({ viewer }) => viewer.waitForIdle(600000)));
    for (let i = 0; i < runs; i++) {
      const rs = await Promise.all(opened.map(({ page, viewer }) => dragOnce(page, viewer, i)));
      rs.forEach((r, k) => {
        opened[k].fps.push(r.fps);
        opened[k].releaseMs.push(r.releaseMs);
      });
      console.log(`run ${i + 1}: frames/s per page ${rs.map((r) => r.fps.toFixed(1)).join(' ')}; drafts ` +
        `${rs.map((r) => `${r.width}x${r.height}`).join(' ')}; release -> lossless ` +
        `${rs.map((r) => r.releaseMs.toFixed(0)).join(' ')} ms`);
    }
    opened.forEach((o, k) => console.log(`page ${k + 1}: median ${median(o.fps).toFixed(1)} frames/s, release -> ` +
      `lossless ${median(o.releaseMs).toFixed(0)} ms, refusals ${o.refusals.count}`));
  });
}

if (manyPages > 0) {
  await dragManyAtOnce();
  process.exit(0);
}

await withPage(fakeTest, async (socketPage) => {
  await withPage(fakeTest, async (renderPage) => {
    for (const [transport, page] of [['socket', socketPage], ['render', renderPage]]) {
      await page.setViewportSize({ width: 1400, height: 900 });
      const viewer = new ViewerPage(page);
      await viewer.open({ dataset, cam: CAMS[transport] }, { transport });
      await viewer.waitForIdle(600000);
      pages[transport] = { page, viewer };
    }
    for (let i = 0; i < runs; i++) {
      for (const transport of ['socket', 'render']) {
        const { page, viewer } = pages[transport];
        const r = await dragOnce(page, viewer, i);
        results[transport].push(r);
        console.log(`${transport} run ${i + 1}: ${r.fps.toFixed(1)} frames/s at ${r.width}x${r.height} ` +
          `(full ${r.fullSize}, ${r.linear.toFixed(2)} linear), release -> lossless ${r.releaseMs.toFixed(0)} ms, move -> frame p50 ` +
          `${r.p50.toFixed(0)} ms p90 ${r.p90.toFixed(0)} ms, ${r.stillsWhileDragging} stills while dragging, ` +
          `${r.coarser} of ${r.drafts} drafts from a coarser fit${r.coarserEps === undefined ? '' : ` (eps ${r.coarserEps})`} [${r.transport}` +
          `${r.stillDrawMs === undefined ? '' : `, still drawn in ${r.stillDrawMs.toFixed(0)} ms`}]` +
          (r.stillParts ? ` still: ${Object.entries(r.stillParts).map(([k, v]) => `${k} ${ms(v)}`).join(', ')} ms` : '') +
          (r.draftParts ? `; drafts: ${Object.entries(r.draftParts).map(([k, v]) => `${k} ${ms(v)}`).join(', ')} ms` : ''));
      }
    }
  });
});
for (const transport of ['socket', 'render']) {
  const rs = results[transport];
  console.log(`median ${transport}: ${median(rs.map((r) => r.fps)).toFixed(1)} frames/s at ` +
    `${median(rs.map((r) => r.width))}x${median(rs.map((r) => r.height))} ` +
    `(${median(rs.map((r) => r.linear)).toFixed(2)} linear), release -> lossless ` +
    `${median(rs.map((r) => r.releaseMs)).toFixed(0)} ms, move -> frame p50 ${median(rs.map((r) => r.p50)).toFixed(0)} ms ` +
    `over ${rs.length} drags` +
    (process.env.VOTS_DRAG_PAUSE_MS ? `, the first move after the pause -> frame ${median(rs.map((r) => r.afterPause)).toFixed(0)} ms, ` +
      `stills shown while dragging ${rs.map((r) => r.stillsWhileDragging).join(' ')}` : ''));
  const parts = rs.map((r) => r.stillParts).filter(Boolean);
  if (parts.length) {
    console.log(`  ${transport} still, medians: ` +
      Object.keys(parts[0]).map((k) => `${k} ${ms(median(parts.map((p) => p[k])))}`).join(', ') + ' ms');
  }
}
