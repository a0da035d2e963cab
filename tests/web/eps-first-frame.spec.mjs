// A refit's first image: a draft of the new Vot-Space as soon as it exists, then the still, which is
// /render's PNG for that camera and eps; no frame at the old eps once the slider has moved.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset, BASE_URL } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

// Every frame shown from now on ("vots:frame": its eps, quality, size, Vot count), in order.
async function recordShownFrames(page) {
  await page.evaluate(() => {
    window.__shownFrames = [];
    document.querySelector('[data-testid="image"]').addEventListener('vots:frame', (e) => {
      const { eps, still, width, height, votCount, transport } = e.detail;
      window.__shownFrames.push({ eps, still, width, height, votCount, transport });
    });
  });
}

// The fit jobs the page starts: their ids, from the answers to POST /api/fit.
function recordFitJobs(page) {
  const jobs = [];
  page.on('response', async (r) => {
    if (r.url().endsWith('/api/fit') && r.request().method() === 'POST') jobs.push((await r.json()).job);
  });
  return jobs;
}

// The bytes of the image on screen (the page's own copy, fetched from its object URL).
async function shownImageBytes(page) {
  const bytes = await page.evaluate(async () => {
    const img = document.querySelector('[data-testid="image"]');
    return [...new Uint8Array(await (await fetch(img.src)).arrayBuffer())];
  });
  return Buffer.from(bytes);
}

for (const [transport, step] of [['socket', 11], ['render', 12]]) {
  test(`over ${transport}: a refit shows a draft of the new Vot-Space first, then /render's PNG`, async (t) => {
    const ds = await pickDataset();
    await withPage(t, async (page) => {
      const viewer = new ViewerPage(page);
      await viewer.open({ dataset: ds.name, cam: 'az=25,el=10,zoom=1,pan=0:0,proj=ortho,fov=30' }, { transport });
      await viewer.waitForIdle();
      const countBefore = (await viewer.votCount.textContent()).trim();
      const oldEps = Number((await viewer.hashParams()).eps);
      const jobs = recordFitJobs(page);
      await recordShownFrames(page);

      // An eps no other spec fits: the server has to fit it and upload a new Vot-Space.
      await viewer.setEpsSlider(await viewer.epsSliderPositionAfter(step));
      await viewer.waitForIdle();

      const newEps = Number((await viewer.hashParams()).eps);
      assert.notEqual(newEps, oldEps);
      assert.equal(jobs.length, 1, `expected one fit job, saw ${jobs.length}`);
      const job = await (await fetch(`${BASE_URL}/api/jobs/${jobs[0]}`)).json();
      assert.equal(job.state, 'done');
      const frames = await page.evaluate(() => window.__shownFrames);
      assert.ok(frames.length >= 2, `expected a draft and the still, saw ${JSON.stringify(frames)}`);
      for (const f of frames) assert.equal(f.eps, newEps, `a frame at another eps was shown: ${JSON.stringify(frames)}`);

      const [first] = frames;
      const still = frames.at(-1);
      assert.equal(first.still, false, `the first frame at the new eps is not a draft: ${JSON.stringify(first)}`);
      assert.equal(first.transport, transport);
      assert.equal(first.votCount, job.votCount, 'the draft is not of the new Vot-Space');
      assert.notEqual(String(first.votCount), countBefore.replace(/\D/g, ''), 'the draft shows the old Vot count');
      assert.ok(first.width * first.height < still.width * still.height, 'the draft is not smaller than the still');
      assert.equal(still.still, true);
      assert.equal(still.votCount, job.votCount);
      assert.equal((await viewer.votCount.textContent()).replace(/\D/g, ''), String(job.votCount));

      // The still on screen is /render's PNG for the page's camera and the new eps.
      const url = await viewer.image.getAttribute('data-frame-url');
      const params = new URL(url, BASE_URL + '/').searchParams;
      assert.equal(Number(params.get('eps')), newEps);
      assert.equal(params.get('size'), `${still.width}x${still.height}`);
      const res = await page.request.get(`${BASE_URL}/${url}`);
      assert.equal(res.status(), 200);
      const png = await res.body();
      const shown = await shownImageBytes(page);
      assert.ok(png.equals(shown), `the still (${shown.length} bytes) differs from /render's PNG (${png.length})`);
    });
  });
}
