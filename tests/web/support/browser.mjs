// Launches Debian chromium via playwright-core with a fresh profile and a pinned 1024x768 DPR-1 page; keeps artefacts on failure.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const HERE = path.dirname(fileURLToPath(import.meta.url));
export const ARTIFACTS = path.resolve(HERE, '..', 'artifacts');
export const VIEWPORT = { width: 1024, height: 768 };

// Set by run.sh, which started the server; a developer may point it at a running one.
export const BASE_URL = (process.env.VOTS_URL || '').replace(/\/$/, '');

const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
const CHROMIUM_ARGS = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
];

export function artifactPath(name) {
  fs.mkdirSync(ARTIFACTS, { recursive: true });
  return path.join(ARTIFACTS, name.replace(/[^\w.-]+/g, '_'));
}

// Opens a fresh browser profile and page; artefacts of a failed test are kept under artifacts/.
// Usage: await withPage(t, async (page) => { ... }); args: more chromium switches.
export async function withPage(t, fn, { args = [] } = {}) {
  if (!BASE_URL) throw new Error('VOTS_URL is not set: run the specs through tests/web/run.sh');
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'vots-web-profile-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    headless: true,
    args: [...CHROMIUM_ARGS, ...args],
    viewport: VIEWPORT,
    deviceScaleFactor: 1,
  });
  const page = context.pages()[0] || (await context.newPage());
  const log = [];
  page.on('console', (m) => log.push(`[console.${m.type()}] ${m.text()}`));
  page.on('pageerror', (e) => log.push(`[pageerror] ${e.stack || e.message}`));
  page.on('requestfailed', (r) => log.push(`[requestfailed] ${r.url()} ${r.failure()?.errorText}`));
  page.on('response', (r) => {
    if (r.status() >= 400) log.push(`[http ${r.status()}] ${r.url()}`);
  });
  const base = t.name.replace(/[^\w.-]+/g, '_');
  try {
    await fn(page, { log });
    // Page errors are bugs even when every assertion held.
    const pageErrors = log.filter((l) => l.startsWith('[pageerror]'));
    if (pageErrors.length) throw new Error(`uncaught errors in the page:\n${pageErrors.join('\n')}`);
  } catch (e) {
    try {
      await page.screenshot({ path: artifactPath(`${base}-FAILED.png`) });
      fs.writeFileSync(artifactPath(`${base}-FAILED.html`), await page.content());
    } catch {
      // The page may be gone; the log below still helps.
    }
    fs.writeFileSync(artifactPath(`${base}-FAILED.log`), `${page.url()}\n${log.join('\n')}\n${e.stack || e}\n`);
    throw e;
  } finally {
    await context.close();
    fs.rmSync(profile, { recursive: true, force: true });
  }
}

// Opens one browser with n pages, each in a context (a window) of its own: tabs of one window would share
// its compositor, which draws only the front tab at full rate. For benchmarks of several viewers at once;
// no artefacts are kept. Usage: await withPages(8, async (pages) => { ... }).
export async function withPages(n, fn, { args = [] } = {}) {
  if (!BASE_URL) throw new Error('VOTS_URL is not set: run the specs through tests/web/run.sh');
  const browser = await chromium.launch({ executablePath: CHROMIUM, headless: true, args: [...CHROMIUM_ARGS, ...args] });
  try {
    const pages = [];
    for (let i = 0; i < n; i++) {
      const context = await browser.newContext({ viewport: VIEWPORT, deviceScaleFactor: 1 });
      pages.push(await context.newPage());
    }
    return await fn(pages);
  } finally {
    await browser.close();
  }
}

// The dataset the specs use: VOTS_TEST_DATASET, else the small brain MRI (run.sh serves it in index
// space), else the fewest voxels.
export async function pickDataset() {
  const res = await fetch(`${BASE_URL}/api/datasets`);
  // Datasets over the server's memory budget ("fits": false) cannot be opened.
  const datasets = (await res.json()).datasets?.filter((d) => d.fits !== false);
  if (!datasets?.length) throw new Error('the server lists no datasets');
  const wanted = process.env.VOTS_TEST_DATASET;
  if (wanted) {
    const d = datasets.find((x) => x.name === wanted);
    if (!d) throw new Error(`VOTS_TEST_DATASET '${wanted}' is not served`);
    return d;
  }
  const brain = datasets.find((x) => x.name === 'mri-brain_33x41x25_int16');
  if (brain) return brain;
  const voxels = (d) => d.dims[0] * d.dims[1] * d.dims[2];
  return [...datasets].sort((a, b) => voxels(a) - voxels(b))[0];
}

// Compares two RGBA buffers: the largest channel difference and the fraction of pixels that differ.
export function comparePixels(a, b) {
  if (a.width !== b.width || a.height !== b.height) {
    return { sameSize: false, maxDiff: 255, diffFraction: 1 };
  }
  let maxDiff = 0;
  let differing = 0;
  for (let i = 0; i < a.data.length; i += 4) {
    let px = 0;
    for (let c = 0; c < 3; c++) px = Math.max(px, Math.abs(a.data[i + c] - b.data[i + c]));
    if (px > 0) differing++;
    maxDiff = Math.max(maxDiff, px);
  }
  return { sameSize: true, maxDiff, diffFraction: differing / (a.data.length / 4) };
}
