// Benchmark: time from an eps slider release to the first image at the new eps and to the sharp one.
//
//   VOTS_URL=http://127.0.0.1:8080 node bench/eps_change.mjs [dataset] [runs] [pause ms]
// The pause (default 0) is how long the "user" looks at each new image before the next move: the
// server's warm-up fits (FitJobs.h) run in such pauses. VOTS_TEST_TRANSPORT=socket draws over the viewer
// socket (the viewer's default); without it the page keeps to GET /render (ViewerPage's default, as in
// the earlier figures of bench/RESULTS.md).
// Per move: "new image after" is the sharp (full-quality) image at the new eps with the new count shown,
// the column of the earlier figures; "first image" is the first image at the new eps of any quality;
// "parts" splits the way there (page clock from the slider's change event, and the server's own times).
// VOTS_EPS_GESTURE says how the slider moves: `set` (default: its value set and `change` fired at once, as
// a click on the track), `drag` (the thumb dragged by the mouse in 15 ms steps and let go at once) or
// `rest:MS` (dragged, held still MS ms, then let go). Times are from the `change` event, except for
// `rest:MS`: from the hand's last move, the moment it chose (the release comes MS later).
// VOTS_EPS_IDLE=1 also waits, before each move, until the server's warm-up fits have ended (/api/stats,
// 60 s at most): a user who looked at the image long enough for them, where the pause is a fixed time.
// needs a running `vots serve` and tests/web/node_modules (tests/web/run.sh installs it).
import { BASE_URL, withPage } from '../tests/web/support/browser.mjs';
import { median, ms } from './stats.mjs';
import { ViewerPage } from '../tests/web/pages/ViewerPage.mjs';

const dataset = process.argv[2] || 'cranium';
const runs = Number(process.argv[3] || 5);
const pauseMs = Number(process.argv[4] || 0);
const fakeTest = { name: 'eps-change-bench' };
const gesture = process.env.VOTS_EPS_GESTURE || 'set';
const restMs = gesture.startsWith('rest:') ? Number(gesture.slice(5)) : 0;
const waitForIdleServer = process.env.VOTS_EPS_IDLE === '1';

// Until the server runs no warm-up fit (and has had a moment to start the next one), 60 s at most.
async function serverIdle() {
  const until = Date.now() + 60000;
  for (let quietPolls = 0; quietPolls < 3 && Date.now() < until;) {
    const stats = await (await fetch(`${BASE_URL}/api/stats`)).json();
    quietPolls = stats.warmUps?.running ? 0 : quietPolls + 1;
    await new Promise((r) => setTimeout(r, 200));
  }
}
if (!['set', 'drag'].includes(gesture) && !(restMs >= 0)) throw new Error(`VOTS_EPS_GESTURE ${gesture}: set, drag or rest:MS`);

// Installed before the page's own scripts: the times of the fit's answer and its end, and of each frame
// request's answer with the server's times, on the page's clock.
function recordTimes() {
  window.__epsMarks = { fitAnswered: [], fitDone: [], renders: [], frames: [] };
  window.__lastPointerMove = NaN; // the hand's last move (the `rest:MS` gesture's clock starts there)
  window.addEventListener('pointermove', () => { window.__lastPointerMove = performance.now(); }, { capture: true });
  const marks = () => window.__epsMarks;
  const plainFetch = window.fetch.bind(window);
  window.fetch = async (input, init) => {
    const url = String(input instanceof Request ? input.url : input);
    const sentAt = performance.now();
    const res = await plainFetch(input, init);
    const at = performance.now();
    const header = (name) => (res.headers.get(name) === null ? NaN : Number(res.headers.get(name)));
    if (url.includes('api/fit')) marks().fitAnswered.push(at);
    if (url.includes('render?')) {
      marks().renders.push({
        url, sentAt, at, frameMs: header('X-Vots-Frame-Ms'), uploadMs: header('X-Vots-Upload-Ms'),
        encodeMs: header('X-Vots-Encode-Ms'), cache: res.headers.get('X-Vots-Frame-Cache'),
      });
    }
    return res;
  };
  const PlainEventSource = window.EventSource;
  window.EventSource = class extends PlainEventSource {
    constructor(...args) {
      super(...args);
      // Registered before the page's listener: the time the page hears of the fit's end.
      this.addEventListener('done', (e) => {
        let fitSeconds = NaN;
        try {
          fitSeconds = Number(JSON.parse(e.data).fitSeconds);
        } catch { /* no figure */ }
        marks().fitDone.push({ at: performance.now(), fitSeconds });
      });
    }
  };
}

// The parts of one move, from what the page recorded (times from the change event).
function partsOf(marks, t0, newEps) {
  const after = (t) => t - t0;
  const fitAnswered = marks.fitAnswered.find((t) => t >= t0);
  const fitDone = marks.fitDone.find((d) => d.at >= t0);
  const epsOfUrl = (url) => Number(new URLSearchParams(url.split('?')[1]).get('eps'));
  // A frame at the new eps: its eps says so (frames of this build); an older build's say none, and
  // there the first frame after the fit's end is the first at the new eps (it draws none meanwhile).
  const atNewEps = (f) => (f.eps !== undefined ? f.eps === newEps : fitDone !== undefined && f.shownAt >= fitDone.at);
  const frames = marks.frames.filter((f) => f.shownAt >= t0 && atNewEps(f));
  const first = frames[0];
  const sharp = frames.find((f) => f.still);
  const render = sharp && sharp.transport === 'render'
    ? marks.renders.find((r) => r.sentAt >= sharp.sentAt - 1 && epsOfUrl(r.url) === newEps && !r.url.includes('grid'))
    : undefined;
  return {
    fitAnswered: fitAnswered !== undefined ? after(fitAnswered) : NaN,
    fitMs: fitDone ? 1000 * fitDone.fitSeconds : NaN,
    fitDone: fitDone ? after(fitDone.at) : NaN,
    firstAsked: first ? after(first.sentAt) : NaN,
    first: first ? after(first.shownAt) : NaN,
    firstKind: first ? `${first.still ? 'still' : 'draft'} ${first.width}x${first.height}` : '?',
    sharpSent: sharp ? after(sharp.sentAt) : NaN,
    frameMs: sharp ? (sharp.frameMs ?? render?.frameMs) : NaN,
    uploadMs: sharp ? (sharp.uploadMs ?? render?.uploadMs) : NaN,
    encodeMs: sharp ? (sharp.encodeMs ?? render?.encodeMs) : NaN,
    sharpAnswered: render ? after(render.at) : NaN,
    sharp: sharp ? after(sharp.shownAt) : NaN,
    // After the page heard of the fit's end: what the fit's own time (noisy on a loaded box) leaves out.
    firstAfterFit: first && fitDone ? first.shownAt - fitDone.at : NaN,
    sharpAfterFit: sharp && fitDone ? sharp.shownAt - fitDone.at : NaN,
  };
}

await withPage(fakeTest, async (page) => {
  await page.addInitScript(recordTimes);
  const viewer = new ViewerPage(page);
  await viewer.open({ dataset, cam: 'az=30,el=15,zoom=1,pan=0:0,proj=ortho,fov=30' });
  await viewer.waitForIdle(600000);
  await page.evaluate(() => {
    document.querySelector('[data-testid="image"]').addEventListener('vots:frame', (e) => {
      window.__epsMarks.frames.push({ ...e.detail, shownAt: performance.now() });
    });
  });
  const start = Number(await viewer.epsSlider.inputValue());
  const times = [];
  const firsts = [];
  const rows = [];
  for (let i = 1; i <= runs; i++) {
    // A new eps each time, alternating around the start one step further each other move: +1, -1, +2, -2
    // ... steps of the server's ladder (about 10 % apart). The server's warm-ups fit the ten nearest the
    // last fit ahead when it is idle; `--no-warm-up` on the server times every move as a refit.
    const position = start + (i % 2 ? 1 : -1) * Math.ceil(i / 2);
    if (pauseMs > 0) await page.waitForTimeout(pauseMs);
    if (waitForIdleServer) await serverIdle();
    const countBefore = await viewer.votCount.textContent();
    // Timed inside the page, from the slider's change event to the first moment the new count, the idle
    // state and the loaded full-quality image are all there (DOM mutations and the image's load event).
    // Node only looks every 200 ms: polling the page every few ms from here would take a share of the
    // cores the fit needs and slow what it measures.
    await page.evaluate((before) => {
      window.__epsDoneAt = null;
      window.__epsT0 = null;
      const ready = () => {
        const s = document.querySelector('[data-testid="status"]');
        const img = document.querySelector('[data-testid="image"]');
        const count = document.querySelector('[data-testid="vot-count"]').textContent;
        return count !== before && s?.dataset.state === 'idle' && img?.dataset.quality === 'full' && img.complete;
      };
      // An absolute time: a rest's fit can be drawn before the release fires `change`.
      const check = () => {
        if (window.__epsDoneAt === null && ready()) window.__epsDoneAt = performance.now();
      };
      // The last move's watchers go: their `before` is an older count, which the slider's label changes of
      // a drag (many tasks, each its own mutations) would find "changed" at once.
      const img = document.querySelector('[data-testid="image"]');
      window.__epsWatch?.observer.disconnect();
      if (window.__epsWatch) img.removeEventListener('load', window.__epsWatch.check);
      const observer = new MutationObserver(check);
      observer.observe(document.body, { subtree: true, childList: true, attributes: true, characterData: true });
      img.addEventListener('load', check);
      window.__epsWatch = { observer, check };
      // Capture phase on window: before the viewer's own change handler runs.
      window.addEventListener('change', () => { window.__epsT0 = performance.now(); }, { once: true, capture: true });
    }, countBefore);
    if (gesture === 'set') {
      await viewer.setEpsSlider(position);
    } else {
      const from = Number(await viewer.epsSlider.inputValue());
      await viewer.holdEpsSlider(await viewer.epsSliderPixels(position - from));
      if (restMs > 0) await page.waitForTimeout(restMs);
      await page.mouse.up();
    }
    await page.waitForFunction(() => window.__epsDoneAt !== null && window.__epsT0 !== null, null,
      { timeout: 600000, polling: 200 });
    // From the release, or from the hand's stop when it rested first.
    const t0 = await page.evaluate((rest) => (rest > 0 ? window.__lastPointerMove : window.__epsT0), restMs);
    const done = (await page.evaluate(() => window.__epsDoneAt)) - t0;
    const newEps = await page.evaluate(() => Number(new URLSearchParams(location.hash.slice(1)).get('eps')));
    const parts = await page.evaluate(
      ([fn, eps, from]) => new Function(`return (${fn})`)()(window.__epsMarks, from, eps),
      [partsOf.toString(), newEps, t0]);
    times.push(done);
    firsts.push(parts.first);
    rows.push(parts);
    console.log(`eps position ${position}: ${(await viewer.epsValue.textContent()).trim()}, ` +
      `${(await viewer.votCount.textContent()).trim()} Vots, new image after ${done.toFixed(0)} ms, ` +
      `first image after ${ms(parts.first)} ms (${parts.firstKind})`);
    console.log(`  parts (ms from the change): fit answered ${ms(parts.fitAnswered)}, fit ${ms(parts.fitMs)} on the ` +
      `server, fit done ${ms(parts.fitDone)}, first asked ${ms(parts.firstAsked)}, sharp asked ${ms(parts.sharpSent)}, its frame ${ms(parts.frameMs)} ` +
      `(upload ${ms(parts.uploadMs)}), PNG ${ms(parts.encodeMs)}, answered ${ms(parts.sharpAnswered)}, ` +
      `shown ${ms(parts.sharp)}`);
  }
  const col = (name) => median(rows.map((r) => r[name]));
  console.log(`median parts (ms): fit answered ${ms(col('fitAnswered'))}, fit ${ms(col('fitMs'))}, fit done ` +
    `${ms(col('fitDone'))}, first asked ${ms(col('firstAsked'))}, first image ${ms(col('first'))}, sharp asked ${ms(col('sharpSent'))}, frame ` +
    `${ms(col('frameMs'))} (upload ${ms(col('uploadMs'))}), PNG ${ms(col('encodeMs'))}, answered ` +
    `${ms(col('sharpAnswered'))}, shown ${ms(col('sharp'))}`);
  console.log(`median after the fit's end (ms): first image ${ms(col('firstAfterFit'))}, sharp image ` +
    `${ms(col('sharpAfterFit'))}`);
  const from = restMs > 0 ? `the hand's stop (${gesture})` : `eps change (${gesture})`;
  console.log(`median ${from} -> first image at the new eps: ${ms(median(firsts))} ms over ${runs} runs`);
  console.log(`median ${from} -> new image: ${median(times).toFixed(0)} ms over ${runs} runs`);
});
