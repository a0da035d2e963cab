// Benchmark: time from an eps slider release to the refitted full-quality image in headless Chromium.
//
//   VOTS_URL=http://127.0.0.1:8080 node bench/eps_change.mjs [dataset] [runs] [pause ms]
// The pause (default 0) is how long the "user" looks at each new image before the next move: the
// server's warm-up fits (FitJobs.h) run in such pauses.
// needs a running `vots serve` and tests/web/node_modules (tests/web/run.sh installs it).
import { withPage } from '../tests/web/support/browser.mjs';
import { ViewerPage } from '../tests/web/pages/ViewerPage.mjs';

const dataset = process.argv[2] || 'cranium';
const runs = Number(process.argv[3] || 5);
const pauseMs = Number(process.argv[4] || 0);
const fakeTest = { name: 'eps-change-bench' };

await withPage(fakeTest, async (page) => {
  const viewer = new ViewerPage(page);
  await viewer.open({ dataset, cam: 'az=30,el=15,zoom=1,pan=0:0,proj=ortho,fov=30' });
  await viewer.waitForIdle(600000);
  const start = Number(await viewer.epsSlider.inputValue());
  const times = [];
  for (let i = 1; i <= runs; i++) {
    // A new eps each time (no cache hit on the whole Vot-Space), alternating around the start.
    const position = start + (i % 2 ? 1 : -1) * (10 + 7 * i);
    if (pauseMs > 0) await page.waitForTimeout(pauseMs);
    const countBefore = await viewer.votCount.textContent();
    // Timed inside the page, from the slider's change event to the first moment the new count, the idle
    // state and the loaded full-quality image are all there (DOM mutations and the image's load event).
    // Node only looks every 200 ms: polling the page every few ms from here would take a share of the
    // cores the fit needs and slow what it measures.
    await page.evaluate((before) => {
      window.__epsDone = null;
      const ready = () => {
        const s = document.querySelector('[data-testid="status"]');
        const img = document.querySelector('[data-testid="image"]');
        const count = document.querySelector('[data-testid="vot-count"]').textContent;
        return count !== before && s?.dataset.state === 'idle' && img?.dataset.quality === 'full' && img.complete;
      };
      const check = () => {
        if (window.__epsDone === null && ready()) window.__epsDone = performance.now() - window.__epsT0;
      };
      const observer = new MutationObserver(check);
      observer.observe(document.body, { subtree: true, childList: true, attributes: true, characterData: true });
      document.querySelector('[data-testid="image"]').addEventListener('load', check);
      // Capture phase on window: before the viewer's own change handler runs.
      window.addEventListener('change', () => { window.__epsT0 = performance.now(); }, { once: true, capture: true });
    }, countBefore);
    await viewer.setEpsSlider(position);
    await page.waitForFunction(() => window.__epsDone !== null, null, { timeout: 600000, polling: 200 });
    const ms = await page.evaluate(() => window.__epsDone);
    times.push(ms);
    console.log(`eps position ${position}: ${(await viewer.epsValue.textContent()).trim()}, ` +
      `${(await viewer.votCount.textContent()).trim()} Vots, new image after ${ms.toFixed(0)} ms`);
  }
  times.sort((a, b) => a - b);
  console.log(`median eps change -> new image: ${times[Math.floor(times.length / 2)].toFixed(0)} ms over ${runs} runs`);
});
