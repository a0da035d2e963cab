// A frame the server refuses for being busy (503, 429) is asked for again: the view does not stay stale
// until the hand moves, over /render and over the viewer socket alike.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, pickDataset } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

const CAM = 'az=20,el=10,zoom=1,pan=0:0,proj=ortho,fov=30';
const BUSY = { error: 'render queue is full; try again' };
// Both the draft at the dataset's eps and the still after it are refused: without a retry nothing asks
// again, since a refused draft is still followed by its still.
const REFUSALS = 2;

test('frames refused over /render while the server is busy are asked for again', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    let refused = 0;
    let drawn = 0;
    await page.route('**/render?**', async (route) => {
      if (route.request().url().includes('renderer=grid')) return route.fallback();
      if (refused < REFUSALS) {
        refused += 1;
        return route.fulfill({ status: 503, contentType: 'application/json', body: JSON.stringify(BUSY) });
      }
      drawn += 1;
      return route.fallback();
    });
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: CAM, eps: Number(ds.defaultEps) }, { transport: 'render' });
    await viewer.waitForIdle();
    assert.equal(refused, REFUSALS);
    assert.ok(drawn >= 1, 'a frame was asked for again after the refusals');
    await viewer.error.waitFor({ state: 'hidden', timeout: 5000 }); // the banner goes with the frame
  });
});

test('views refused over the viewer socket while the server is busy are sent again', async (t) => {
  const ds = await pickDataset();
  await withPage(t, async (page) => {
    let refused = 0;
    let passed = 0;
    await page.routeWebSocket(/\/api\/stream/, (ws) => {
      const server = ws.connectToServer();
      ws.onMessage((message) => {
        const parsed = typeof message === 'string' ? JSON.parse(message) : null;
        if (parsed?.type === 'view' && refused < REFUSALS) {
          refused += 1;
          ws.send(JSON.stringify({ type: 'error', seq: parsed.seq, status: 503, ...BUSY }));
          return;
        }
        if (parsed?.type === 'view') passed += 1;
        server.send(message);
      });
    });
    const viewer = new ViewerPage(page);
    await viewer.open({ dataset: ds.name, cam: CAM, eps: Number(ds.defaultEps) }, { transport: 'socket' });
    await viewer.waitForIdle();
    // The socket opens with the first frame, drawn over /render; the next view goes over the socket.
    await viewer.viewButton('left').click();
    await page.waitForFunction(() => document.querySelector('[data-testid="image"]')?.dataset.transport === 'socket',
      null, { timeout: 60000, polling: 50 });
    await viewer.waitForIdle();
    assert.equal(refused, REFUSALS);
    assert.ok(passed >= 1, 'a view was sent again after the refusals');
    await viewer.error.waitFor({ state: 'hidden', timeout: 5000 });
  });
});
