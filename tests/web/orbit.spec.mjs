// Mouse interaction: left-drag orbits (right = +az, up = +el), shift-drag pans, the wheel zooms; drafts while moving.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

const START_CAM = 'az=10,el=5,zoom=1,pan=0:0,proj=ortho,fov=30';

// Runs `body(viewer, page)` on a page showing a dataset at START_CAM, its first frame drawn.
async function atStartCam(t, body) {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: START_CAM });
    await viewer.waitForIdle();
    await body(viewer, page);
  });
}

test('left-drag orbits: hash cam and image change, drafts while dragging, full frame on release', async (t) => {
  await atStartCam(t, async (viewer, page) => {
    const before = await viewer.framePixels();
    await viewer.screenshotView('orbit-before');

    const sizes = [];
    page.on('request', (r) => {
      if (r.url().includes('/render?')) sizes.push(new URL(r.url()).searchParams.get('size'));
    });
    await viewer.drag(150, -80);
    await viewer.waitForIdle();
    await viewer.screenshotView('orbit-after');

    const cam = await viewer.camValues();
    assert.ok(cam.az > 10 + 5, `dragging right should increase az, got ${cam.az}`);
    assert.ok(cam.el > 5 + 5, `dragging up should increase el, got ${cam.el}`);
    const after = await viewer.framePixels();
    assert.notDeepEqual(after.data, before.data, 'the image did not change after orbiting');

    const full = `${before.width}x${before.height}`;
    assert.ok(sizes.length >= 2, `expected several frames during the drag, saw ${sizes.join(' ')}`);
    assert.ok(sizes.some((s) => s !== full), `no reduced-size draft frame while dragging: ${sizes.join(' ')}`);
    assert.equal(sizes.at(-1), full, 'the last request must be the full-quality frame');
  });
});

test('elevation clamps at +90 when dragging far up', async (t) => {
  await atStartCam(t, async (viewer) => {
    await viewer.drag(0, -700);
    await viewer.waitForIdle();
    assert.equal((await viewer.camValues()).el, 90);
  });
});

test('shift-drag pans and the wheel zooms', async (t) => {
  await atStartCam(t, async (viewer) => {
    const before = await viewer.framePixels();

    await viewer.drag(120, 60, { shift: true });
    await viewer.waitForIdle();
    const panned = await viewer.camValues();
    // pan moves the look-at point, so content dragged right/down means pan x < 0 and pan y > 0.
    assert.ok(panned.panX < -0.1 && panned.panY > 0.1, `content should follow the pointer: pan=${panned.panX}:${panned.panY}`);
    assert.equal(panned.az, 10, 'panning must not orbit');
    const afterPan = await viewer.framePixels();
    assert.notDeepEqual(afterPan.data, before.data, 'the image did not change after panning');

    await viewer.wheel(-300);
    await viewer.waitForIdle();
    const zoomed = await viewer.camValues();
    assert.ok(zoomed.zoom > 1.2, `wheel up should zoom in, zoom=${zoomed.zoom}`);
    await viewer.screenshotView('pan-zoom');
  });
});

test('a drag writes the status line and the view buttons only when what they say changes', async (t) => {
  await atStartCam(t, async (viewer, page) => {
    // Every write to the page re-lays it out, a same-text write as much as any: at 60 pointer moves a
    // second that is a layout per move for nothing.
    await page.evaluate(() => {
      window.__writes = { status: [], buttons: [] };
      const status = document.querySelector('#status');
      new MutationObserver((records) => {
        for (const r of records) {
          const before = r.type === 'attributes' ? r.oldValue : r.removedNodes[0]?.textContent ?? null;
          const after = r.type === 'attributes' ? r.target.getAttribute(r.attributeName) : status.textContent;
          window.__writes.status.push({ before, after });
        }
      }).observe(status, { childList: true, characterData: true, subtree: true, attributes: true, attributeOldValue: true });
      const buttons = new MutationObserver((records) => {
        for (const r of records) window.__writes.buttons.push({ before: r.oldValue, after: r.target.getAttribute(r.attributeName) });
      });
      for (const b of document.querySelectorAll('[data-view]')) buttons.observe(b, { attributes: true, attributeOldValue: true });
    });
    await viewer.drag(150, -80, { steps: 40 });
    await viewer.waitForIdle();
    const writes = await page.evaluate(() => window.__writes);
    assert.ok(writes.status.length >= 1, 'the status line never changed over a drag and its still');
    const idle = writes.status.filter((w) => w.before === w.after);
    assert.equal(idle.length, 0, `${idle.length} of ${writes.status.length} writes to the status line left it as it was`);
    const sameButtons = writes.buttons.filter((w) => w.before === w.after);
    assert.equal(sameButtons.length, 0, `${sameButtons.length} writes to the view buttons left them as they were`);
  });
});
