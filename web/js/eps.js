// The error bound eps on the client: the server's default per dataset, the log-scale slider, its label; no DOM.
import { fmtValue } from './format.js';

export const SLIDER_STEPS = 1000; // eps-slider integer range, mapped log-linearly onto [min, max] of epsBounds

// The span of a dataset's value range; eps percentages are of this span.
export function rangeSpan(ds) {
  const span = Number(ds.range[1]) - Number(ds.range[0]);
  return span > 0 ? span : 1;
}

// The server's default eps for the dataset (it owns the rule), or null when it sent none.
export function defaultEpsOf(ds) {
  const eps = Number(ds?.defaultEps);
  return eps > 0 ? eps : null;
}

// The slider spans 0.1 % .. 50 % of the range, widened to include the server's default.
export function epsBounds(ds) {
  const span = rangeSpan(ds);
  const def = defaultEpsOf(ds);
  if (def === null) return { min: span * 1e-3, max: span * 0.5 };
  return { min: Math.min(span * 1e-3, def), max: Math.max(span * 0.5, def) };
}

export function epsToSlider(ds, eps) {
  const { min, max } = epsBounds(ds);
  const t = Math.log(Math.min(max, Math.max(min, eps)) / min) / Math.log(max / min);
  return Math.round(t * SLIDER_STEPS);
}

// Three significant digits keep URLs short and make equal slider positions hit the server's fit cache.
export function sliderToEps(ds, pos) {
  const { min, max } = epsBounds(ds);
  return Number((min * Math.pow(max / min, pos / SLIDER_STEPS)).toPrecision(3));
}

export function epsLabel(ds, eps) {
  if (!(eps > 0)) return '– (no default from the server)';
  const pct = (100 * eps) / rangeSpan(ds);
  const pctText = pct >= 10 ? pct.toFixed(0) : pct >= 1 ? pct.toFixed(1) : pct.toPrecision(2);
  return `${fmtValue(eps)} (${pctText} % of range)`;
}
