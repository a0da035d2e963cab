// Benchmark: time from an eps slider release to the refitted full-quality image in headless Chromium.
//
//   VOTS_URL=http://127.0.0.1:8080 node bench/eps_change.mjs [dataset] [runs]
// needs a running `vots serve` and tests/web/node_modules (tests/web/run.sh installs it).
import { withPage } from '../tests/web/support/browser.mjs';
import { ViewerPage } from '../tests/web/pages/ViewerPage.mjs';

const dataset = process.argv[2] || 'cranium';
const runs = Number(process.argv[3] || 5);
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
    const countBefore = await viewer.votCount.textContent();
    const t0 = performance.now();
    await viewer.setEpsSlider(position);
    await page.waitForFunction((before) => {
      const s = document.querySelector('[data-testid="status"]');
      const img = document.querySelector('[data-testid="image"]');
      const count = document.querySelector('[data-testid="vot-count"]').textContent;
      return count !== before && s?.dataset.state === 'idle' && img?.dataset.quality === 'full' && img.complete;
    }, countBefore, { timeout: 600000, polling: 10 });
    const ms = performance.now() - t0;
    times.push(ms);
    console.log(`eps position ${position}: ${(await viewer.epsValue.textContent()).trim()}, ` +
      `${(await viewer.votCount.textContent()).trim()} Vots, new image after ${ms.toFixed(0)} ms`);
  }
  times.sort((a, b) => a - b);
  console.log(`median eps change -> new image: ${times[Math.floor(times.length / 2)].toFixed(0)} ms over ${runs} runs`);
});
