// The page's camera module, run inside the browser: cam= text round-trips, named views, clamps and drag directions.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage } from './support/browser.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

test('camera text, views, limits and trackball directions', async (t) => {
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await viewer.open();
    const r = await page.evaluate(async () => {
      const c = await import('./js/camera.js');
      const cam = c.parseCamera('az=30,el=20,zoom=1.5,pan=0.25:-0.5,proj=persp,fov=40');
      const errors = [];
      for (const bad of ['az=abc', 'proj=fisheye', 'pan=1', 'tilt=3', 'az']) {
        try {
          c.parseCamera(bad);
          errors.push(null);
        } catch (e) {
          errors.push(e.message);
        }
      }
      const base = c.parseCamera('az=0,el=0');
      return {
        roundTrip: c.formatCamera(cam),
        views: Object.keys(c.VIEWS).map((v) => c.formatCamera(c.parseCamera(v))),
        posteriorName: c.viewName(c.parseCamera('az=-180,el=0')),
        errors,
        clamped: c.formatCamera(c.parseCamera('az=400,el=120,zoom=5000,pan=300:-300,fov=500')),
        right: c.orbit(base, 10, 0, 800, 600).az,
        up: c.orbit(base, 0, -10, 800, 600).el,
        elClamp: c.orbit(base, 0, -10000, 800, 600).el,
        wrap: c.orbit(c.parseCamera('az=179,el=0'), 100, 0, 600, 600).az,
        panRight: c.pan(base, 30, 0, 600).panX,
        zoomIn: c.zoomBy(base, -100).zoom,
        toLeft: c.formatCamera(c.toView(cam, 'left')),
      };
    });
    assert.equal(r.roundTrip, 'az=30,el=20,zoom=1.5,pan=0.25:-0.5,proj=persp,fov=40');
    assert.deepEqual(r.views.map((v) => v.split(',').slice(0, 2).join(',')),
      ['az=0,el=0', 'az=180,el=0', 'az=90,el=0', 'az=-90,el=0', 'az=0,el=90', 'az=0,el=-90']);
    assert.equal(r.posteriorName, 'posterior');
    assert.ok(r.errors.every((e) => typeof e === 'string' && e.startsWith('camera:')), JSON.stringify(r.errors));
    assert.equal(r.clamped, 'az=40,el=90,zoom=1000,pan=100:-100,proj=ortho,fov=150');
    assert.ok(r.right > 0, 'dragging right increases az');
    assert.ok(r.up > 0, 'dragging up increases el');
    assert.equal(r.elClamp, 90);
    assert.ok(r.wrap > -180 && r.wrap < 0, `az wraps into (-180, 180]: ${r.wrap}`);
    assert.ok(r.panRight < 0, 'content follows the pointer, so the look-at point moves left');
    assert.ok(Math.abs(r.zoomIn - 1.1) < 1e-9);
    assert.equal(r.toLeft, 'az=90,el=0,zoom=1.5,pan=0:0,proj=persp,fov=40');
  });
});
