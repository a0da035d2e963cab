// The error bound eps on the client: the server's default per dataset, the slider's steps, its label; no DOM.
import { fmtValue } from './format.js';

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

// The eps the slider offers, ascending: the server's ladder for the dataset (`epsSteps`: it owns the rule
// and fits the steps near the shown eps ahead, so a move to one is a cache hit), else the default alone.
export function epsSteps(ds) {
  const steps = Array.isArray(ds?.epsSteps) ? ds.epsSteps.map(Number).filter((e) => e > 0) : [];
  if (steps.length) return steps;
  const def = defaultEpsOf(ds);
  return def === null ? [] : [def];
}

// The slider's highest position (its positions are the steps' indices).
export function sliderMax(ds) {
  return Math.max(0, epsSteps(ds).length - 1);
}

// The position of the step nearest eps on a log scale (an eps from a link may lie between steps).
export function epsToSlider(ds, eps) {
  const steps = epsSteps(ds);
  const far = (i) => Math.abs(Math.log(steps[i] / eps));
  let best = 0;
  for (let i = 1; i < steps.length; i++) if (far(i) < far(best)) best = i;
  return best;
}

// The step at a slider position (clamped to the ends), or null when the dataset offers none.
export function sliderToEps(ds, pos) {
  const steps = epsSteps(ds);
  if (!steps.length) return null;
  return steps[Math.min(steps.length - 1, Math.max(0, Math.round(pos)))];
}

export function epsLabel(ds, eps) {
  if (!(eps > 0)) return '– (no default from the server)';
  const pct = (100 * eps) / rangeSpan(ds);
  const pctText = pct >= 10 ? pct.toFixed(0) : pct >= 1 ? pct.toFixed(1) : pct.toPrecision(2);
  return `${fmtValue(eps)} (${pctText} % of range)`;
}
