// Benchmark: where the browser's own CPU goes while the viewer is dragged over its socket (a Chromium
// trace of one drag, summed by process and by event, self time).
//
//   VOTS_URL=http://127.0.0.1:8080 node bench/page_trace.mjs [dataset] [drag ms] [top N]
// Prints the trace's span, each Chromium process's summed self time, the number of compositor frames and
// the N events with the most self time. Needs a running `vots serve` and tests/web/node_modules
// (tests/web/run.sh installs it).
import { withPage } from '../tests/web/support/browser.mjs';
import { ViewerPage } from '../tests/web/pages/ViewerPage.mjs';
import { dragAcrossImage } from './drag.mjs';

const dataset = process.argv[2] || 'cranium';
const dragMs = Number(process.argv[3] || 4000);
const top = Number(process.argv[4] || 15);
const CATEGORIES = ['devtools.timeline', 'disabled-by-default-devtools.timeline', 'toplevel', 'v8', 'blink', 'cc',
  'viz', 'gpu', 'input', 'renderer.scheduler', 'skia'];

// Self time (the event's duration less its nested events') per [process, thread, event], in microseconds.
function selfTimes(events) {
  const names = new Map();
  for (const e of events) {
    if (e.ph !== 'M') continue;
    if (e.name === 'thread_name') names.set(`${e.pid}:${e.tid}`, e.args.name);
    if (e.name === 'process_name') names.set(`${e.pid}`, e.args.name);
  }
  const byThread = new Map();
  for (const e of events) {
    if (e.ph !== 'X' || e.dur === undefined) continue;
    const key = `${e.pid}:${e.tid}`;
    if (!byThread.has(key)) byThread.set(key, []);
    byThread.get(key).push(e);
  }
  const self = new Map();
  for (const [key, list] of byThread) {
    list.sort((a, b) => a.ts - b.ts || b.dur - a.dur);
    const children = new Map();
    const stack = [];
    for (const e of list) {
      while (stack.length && stack.at(-1).ts + stack.at(-1).dur <= e.ts) stack.pop();
      if (stack.length) children.set(stack.at(-1), (children.get(stack.at(-1)) || 0) + e.dur);
      stack.push(e);
    }
    const process = names.get(key.split(':')[0]) || '?';
    for (const e of list) {
      const k = `${process}\t${names.get(key) || '?'}\t${e.name}`;
      self.set(k, (self.get(k) || 0) + e.dur - (children.get(e) || 0));
    }
  }
  return self;
}

await withPage({ name: 'page-trace-bench' }, async (page) => {
  await page.setViewportSize({ width: 1400, height: 900 });
  const viewer = new ViewerPage(page);
  const az = Math.round((Date.now() / 1000) % 3600) / 10; // a camera path no earlier run drew
  await viewer.open({ dataset, cam: `az=${az},el=15,zoom=1,pan=0:0,proj=ortho,fov=30` }, { transport: 'socket' });
  await viewer.waitForIdle(600000);
  const cdp = await page.context().newCDPSession(page);
  const events = [];
  cdp.on('Tracing.dataCollected', (d) => { for (const e of d.value) events.push(e); });
  const complete = new Promise((resolve) => cdp.once('Tracing.tracingComplete', resolve));
  await cdp.send('Tracing.start', { transferMode: 'ReportEvents', traceConfig: { includedCategories: CATEGORIES } });
  await dragAcrossImage(page, viewer, dragMs, 200);
  await viewer.waitForIdle(120000);
  await cdp.send('Tracing.end');
  await complete;

  const timed = events.filter((e) => e.ph === 'X' && e.dur !== undefined);
  // (A loop, not Math.max(...list): a trace holds more events than a call's arguments may.)
  let first = Infinity;
  let last = -Infinity;
  for (const e of timed) {
    first = Math.min(first, e.ts);
    last = Math.max(last, e.ts + e.dur);
  }
  const span = (last - first) / 1e6;
  const self = selfTimes(events);
  const perProcess = new Map();
  for (const [k, us] of self) {
    const process = k.split('\t')[0];
    perProcess.set(process, (perProcess.get(process) || 0) + us);
  }
  const frames = timed.filter((e) => e.name === 'DirectRenderer::DrawFrame').length;
  console.log(`trace of ${span.toFixed(2)} s, ${frames} compositor frames; self time per process: ` +
    [...perProcess].map(([p, us]) => `${p} ${(us / 1e3).toFixed(0)} ms (${(us / 1e6 / span).toFixed(2)} of a core)`).join(', '));
  for (const [k, us] of [...self].sort((a, b) => b[1] - a[1]).slice(0, top)) {
    const [process, thread, name] = k.split('\t');
    console.log(`${(us / 1e3).toFixed(1).padStart(8)} ms  ${process} / ${thread}: ${name}`);
  }
});
