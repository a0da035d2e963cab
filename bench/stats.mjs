// The benchmarks' summaries: medians and quantiles over the finite values, and a figure in whole ms.

// Values a run could not measure (NaN, undefined) are left out rather than sorted among the rest.
const finiteSorted = (xs) => xs.filter((x) => Number.isFinite(x)).sort((a, b) => a - b);

export const median = (xs) => {
  const s = finiteSorted(xs);
  return s.length ? s[Math.floor(s.length / 2)] : NaN;
};

export const quantile = (xs, q) => {
  const s = finiteSorted(xs);
  return s.length ? s[Math.min(s.length - 1, Math.floor(q * s.length))] : NaN;
};

// A server that sends fewer times (an older build, a baseline) leaves parts unknown: '?'.
export const ms = (v) => (Number.isFinite(v) ? v.toFixed(0) : '?');
