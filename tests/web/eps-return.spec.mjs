// Going back to a fitted eps while another eps still fits: the late fit's reply must not swap the frames to it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { BASE_URL, withPage, pickDataset } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

const REACT_MS = 1500; // after the late fit is done: time for a viewer that wrongly adopts it to ask for a frame

async function waitForJobDone(id) {
  for (const start = Date.now(); ; await new Promise((r) => setTimeout(r, 200))) {
    const job = await (await fetch(`${BASE_URL}/api/jobs/${encodeURIComponent(id)}`)).json();
    if (job.state === 'done') return;
    assert.notEqual(job.state, 'failed', `the fit job failed: ${JSON.stringify(job)}`);
    assert.ok(Date.now() - start < 60000, 'the fit job did not finish within 60 s');
  }
}

test('a fit reply that arrives after going back to the default eps leaves the frames at the default', async (t) => {
  const ds = await pickDataset();
  const defaultEps = Number(ds.defaultEps);
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: 'az=30,el=15,zoom=1,pan=0:0,proj=ortho,fov=30' });
    await viewer.waitForIdle();

    // Hold the answer to POST /api/fit until the test lets it through.
    let release;
    const released = new Promise((r) => {
      release = r;
    });
    const held = [];
    await page.route('**/api/fit', async (route) => {
      const response = await route.fetch();
      // The eps as the viewer asked for it (the reply echoes it as the server stores it).
      held.push({ eps: route.request().postDataJSON().eps, job: (await response.json()).job });
      await released;
      await route.fulfill({ response });
    });
    const renderEps = [];
    page.on('request', (r) => {
      if (r.url().includes('/render?')) renderEps.push(Number(new URL(r.url()).searchParams.get('eps')));
    });

    await viewer.setEpsSlider(await viewer.epsSliderPositionAfter(16));
    for (const start = Date.now(); held.length === 0; await page.waitForTimeout(50)) {
      assert.ok(Date.now() - start < 10000, 'the slider change sent no fit request');
    }
    const late = held[0];
    assert.ok(late.eps > defaultEps, `the held fit should be for a larger eps: ${JSON.stringify(late)}`);

    // Back to the default eps through the link: it counts as fitted, so no new fit; frames stay at it.
    await page.evaluate((eps) => {
      const q = new URLSearchParams(location.hash.slice(1));
      q.set('eps', String(eps));
      location.hash = q.toString();
    }, defaultEps);
    await page.waitForFunction((eps) => new URLSearchParams(location.hash.slice(1)).get('eps') === String(eps),
      defaultEps);

    const rendersBefore = renderEps.length;
    release();
    await waitForJobDone(late.job);
    await page.waitForTimeout(REACT_MS);
    await viewer.waitForIdle();

    const afterRelease = renderEps.slice(rendersBefore);
    assert.ok(!afterRelease.includes(late.eps), `frames were asked for the abandoned eps ${late.eps}: ${afterRelease}`);
    const shown = new URL(await viewer.image.getAttribute('data-frame-url'), BASE_URL + '/');
    assert.equal(Number(shown.searchParams.get('eps')), defaultEps, 'the shown frame is for the default eps');
    assert.equal(Number((await viewer.hashParams()).eps), defaultEps, 'the link still holds the default eps');
    assert.ok(!(await viewer.error.isVisible()), `an error is shown: ${await viewer.error.textContent()}`);
  });
});
