// Page object for the Vots viewer: finds controls by data-testid only and reads state the way a user sees it.
import { BASE_URL, artifactPath } from '../support/browser.mjs';

const FRAME_TIMEOUT_MS = Number(process.env.VOTS_FRAME_TIMEOUT_MS || 60000); // first frames may wait for a fit

export class ViewerPage {
  constructor(page) {
    this.page = page;
    this.byId = (id) => page.getByTestId(id);
    this.image = this.byId('image');
    this.status = this.byId('status');
    this.error = this.byId('error');
    this.dataset = this.byId('dataset');
    this.mode = this.byId('mode');
    this.colormap = this.byId('colormap');
    this.windowPreset = this.byId('window-preset');
    this.level = this.byId('level');
    this.width = this.byId('width');
    this.epsSlider = this.byId('eps-slider');
    this.epsValue = this.byId('eps-value');
    this.progress = this.byId('progress');
    this.votCount = this.byId('vot-count');
    this.fitTime = this.byId('fit-time');
    this.projection = this.byId('projection');
  }

  // hash: an object of URL-hash parameters or a ready string starting with '#'. transport: 'render' keeps
  // the page on GET /render (what most specs observe, request by request); 'socket', the default viewer,
  // frames over GET /api/stream (stream.spec.mjs). VOTS_TEST_TRANSPORT=socket runs every spec's page on it.
  async open(hash = '', { transport = process.env.VOTS_TEST_TRANSPORT || 'render' } = {}) {
    const text = typeof hash === 'string'
      ? hash
      : '#' + Object.entries(hash).map(([k, v]) => `${k}=${encodeURIComponent(v)}`).join('&');
    await this.page.goto(`${BASE_URL}/${transport === 'render' ? '?transport=render' : ''}${text}`);
  }

  viewButton(name) {
    return this.byId(`view-${name}`);
  }

  // Idle = no fit, no frame in flight or scheduled, and the shown frame is full quality.
  async waitForIdle(timeout = FRAME_TIMEOUT_MS) {
    await this.page.waitForFunction(() => {
      const s = document.querySelector('[data-testid="status"]');
      const img = document.querySelector('[data-testid="image"]');
      return s?.dataset.state === 'idle' && img?.dataset.quality === 'full' && img.complete && img.naturalWidth > 0;
    }, null, { timeout, polling: 50 });
  }

  async waitForError(timeout = FRAME_TIMEOUT_MS) {
    await this.error.waitFor({ state: 'visible', timeout });
    return (await this.error.textContent()).trim();
  }

  async hashParams() {
    const hash = await this.page.evaluate(() => location.hash);
    return Object.fromEntries(new URLSearchParams(hash.replace(/^#/, '')));
  }

  async cam() {
    return (await this.hashParams()).cam;
  }

  // The hash camera as numbers, parsed here rather than with the page's own code, so the test checks the text.
  async camValues() {
    const out = {};
    for (const part of (await this.cam()).split(',')) {
      const [k, v] = part.split('=');
      if (k === 'pan') [out.panX, out.panY] = v.split(':').map(Number);
      else out[k] = k === 'proj' ? v : Number(v);
    }
    return out;
  }

  // The frame exactly as the server sent it, decoded to RGBA, plus its luminance mean and variance.
  async framePixels() {
    const r = await this.page.evaluate(() => {
      const img = document.querySelector('[data-testid="image"]');
      const c = document.createElement('canvas');
      c.width = img.naturalWidth;
      c.height = img.naturalHeight;
      const ctx = c.getContext('2d', { willReadFrequently: true });
      ctx.drawImage(img, 0, 0);
      const d = ctx.getImageData(0, 0, c.width, c.height).data;
      let sum = 0;
      let sum2 = 0;
      const n = d.length / 4;
      for (let i = 0; i < d.length; i += 4) {
        const y = 0.299 * d[i] + 0.587 * d[i + 1] + 0.114 * d[i + 2];
        sum += y;
        sum2 += y * y;
      }
      let bin = '';
      for (let i = 0; i < d.length; i += 0x8000) bin += String.fromCharCode(...d.subarray(i, i + 0x8000));
      return { width: c.width, height: c.height, mean: sum / n, variance: sum2 / n - (sum / n) ** 2, b64: btoa(bin) };
    });
    return { width: r.width, height: r.height, mean: r.mean, variance: r.variance, data: Buffer.from(r.b64, 'base64') };
  }

  // The on-screen size of the image element and of the frame it shows (device pixels).
  async imageGeometry() {
    return this.page.evaluate(() => {
      const img = document.querySelector('[data-testid="image"]');
      const r = img.getBoundingClientRect();
      return { cssWidth: r.width, cssHeight: r.height, naturalWidth: img.naturalWidth, naturalHeight: img.naturalHeight };
    });
  }

  async screenshotView(name) {
    const file = artifactPath(`${name}.png`);
    await this.image.screenshot({ path: file });
    return file;
  }

  async screenshotPage(name) {
    const file = artifactPath(`${name}.png`);
    await this.page.screenshot({ path: file });
    return file;
  }

  // A left-drag (orbit), shift-drag (pan) or middle-drag (pan) across the view, in small steps like a hand.
  async drag(dx, dy, { shift = false, button = 'left', steps = 20 } = {}) {
    const box = await this.image.boundingBox();
    const x = box.x + box.width / 2;
    const y = box.y + box.height / 2;
    await this.page.mouse.move(x, y);
    if (shift) await this.page.keyboard.down('Shift');
    await this.page.mouse.down({ button });
    for (let i = 1; i <= steps; i++) {
      await this.page.mouse.move(x + (dx * i) / steps, y + (dy * i) / steps);
      await this.page.waitForTimeout(15);
    }
    await this.page.mouse.up({ button });
    if (shift) await this.page.keyboard.up('Shift');
  }

  async wheel(deltaY) {
    const box = await this.image.boundingBox();
    await this.page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
    await this.page.mouse.wheel(0, deltaY);
  }

  // Moves the eps slider as a user's release would: `input` while moving, `change` on release.
  async setEpsSlider(position) {
    await this.epsSlider.evaluate((s, pos) => {
      s.value = String(pos);
      s.dispatchEvent(new Event('input', { bubbles: true }));
      s.dispatchEvent(new Event('change', { bubbles: true }));
    }, position);
  }

  // The eps slider's position `steps` steps from where it is now, clamped to its ends.
  async epsSliderPositionAfter(steps) {
    const max = Number(await this.epsSlider.getAttribute('max'));
    return Math.max(0, Math.min(max, Number(await this.epsSlider.inputValue()) + steps));
  }

  // Steps the eps slider with the keyboard as a user holding or tapping a key would: focus, then `presses`
  // key presses `gapMs` apart (the browser itself fires `input` and `change` for each step).
  async stepEpsSlider(presses, { key = 'ArrowRight', gapMs = 20 } = {}) {
    await this.epsSlider.focus();
    for (let i = 0; i < presses; i++) {
      await this.page.keyboard.press(key);
      if (gapMs > 0) await this.page.waitForTimeout(gapMs);
    }
  }

  // Drags the eps slider's thumb with the mouse by dx CSS pixels, in small steps like a hand, then releases.
  async dragEpsSlider(dx, { steps = 10 } = {}) {
    await this.holdEpsSlider(dx, { steps });
    await this.page.mouse.up();
  }

  // Presses the eps slider's thumb and moves it by dx CSS pixels in steps 15 ms apart, like a hand; the
  // button stays down (moveHeldEpsSlider moves on, page.mouse.up() lets go).
  async holdEpsSlider(dx, { steps = 10 } = {}) {
    const box = await this.epsSlider.boundingBox();
    const value = Number(await this.epsSlider.inputValue());
    const max = Number(await this.epsSlider.getAttribute('max'));
    this.heldAt = { x: box.x + (box.width * value) / max, y: box.y + box.height / 2 };
    await this.page.mouse.move(this.heldAt.x, this.heldAt.y);
    await this.page.mouse.down();
    await this.moveHeldEpsSlider(dx, { steps });
  }

  async moveHeldEpsSlider(dx, { steps = 10 } = {}) {
    const { x, y } = this.heldAt;
    for (let i = 1; i <= steps; i++) {
      await this.page.mouse.move(x + (dx * i) / steps, y);
      await this.page.waitForTimeout(15);
    }
    this.heldAt = { x: x + dx, y };
  }

  // The CSS pixels the thumb moves for `positions` steps of the slider.
  async epsSliderPixels(positions) {
    const box = await this.epsSlider.boundingBox();
    return (box.width * positions) / Number(await this.epsSlider.getAttribute('max'));
  }

  // Waits (10 s at most) until recordFitRequests' array holds `count` requests; `what` names the wait in
  // the failure.
  async waitForFitRequests(fits, count, what) {
    for (const start = Date.now(); fits.length < count; await this.page.waitForTimeout(50)) {
      if (Date.now() - start > 10000) throw new Error(`${what}: ${fits.length} fit requests after 10 s, expected ${count}`);
    }
  }

  // Collects the bodies of the page's POST /api/fit requests from now on, into the returned array.
  recordFitRequests() {
    const fits = [];
    this.page.on('request', (r) => {
      if (r.url().endsWith('/api/fit') && r.method() === 'POST') fits.push(r.postDataJSON());
    });
    return fits;
  }

  // Records in the page whether the progress bar ever becomes visible (fits on tiny data can be quick).
  async watchProgress() {
    await this.page.evaluate(() => {
      const bar = document.querySelector('[data-testid="progress"]');
      window.__votsProgressSeen = { visible: false, maxValue: 0 };
      const check = () => {
        if (bar.checkVisibility()) window.__votsProgressSeen.visible = true;
        window.__votsProgressSeen.maxValue = Math.max(window.__votsProgressSeen.maxValue, bar.value);
      };
      new MutationObserver(check).observe(document.body, { subtree: true, attributes: true, childList: true, characterData: true });
    });
  }

  async progressSeen() {
    return this.page.evaluate(() => window.__votsProgressSeen);
  }
}
