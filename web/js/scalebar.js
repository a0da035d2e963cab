// The scale bar: a round length in mm and its width on screen for the view's camera; no DOM.
import { imageHeightMm } from './geometry.js';
import { PROJECTIONS } from './contract.js';

const TARGET_PX = 120; // the bar is the largest 1-2-5 length in mm that is at most about this wide

// The largest of 1, 2, 5 times a power of ten that is <= x (x > 0).
export function roundDown125(x) {
  const p = 10 ** Math.floor(Math.log10(x));
  const m = x / p;
  // A hair of slack, so 5 computed as 4.9999999 still reads as 5.
  const step = m >= 5 - 1e-9 ? 5 : m >= 2 - 1e-9 ? 2 : 1;
  return step * p;
}

// {mm, px, label} for an image shown viewHeightPx CSS pixels tall; null when nothing sensible fits.
export function scaleBarOf(ds, cam, viewHeightPx) {
  if (!ds || !(viewHeightPx > 0)) return null;
  const mmPerPx = imageHeightMm(ds, cam) / viewHeightPx;
  if (!(mmPerPx > 0) || !Number.isFinite(mmPerPx)) return null;
  const mm = roundDown125(TARGET_PX * mmPerPx);
  const length = mm >= 10 && mm % 10 === 0 ? `${mm / 10} cm` : `${Number(mm.toPrecision(3))} mm`;
  // In perspective a length on screen depends on its depth: the bar holds at the volume's centre only,
  // and says so, since nearer parts look larger and farther ones smaller.
  const label = cam.proj === PROJECTIONS.persp ? `${length} at centre` : length;
  return { mm, px: mm / mmPerPx, label };
}
