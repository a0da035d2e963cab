// Number formatting for the panel, the status line and the URL hash; no DOM.

// For display: three significant digits, or two decimals for large and whole values.
export function fmtValue(v) {
  if (!Number.isFinite(v)) return '–';
  const a = Math.abs(v);
  if (a >= 1000 || Number.isInteger(v)) return String(Math.round(v * 100) / 100);
  return String(Number(v.toPrecision(3)));
}

// For values the user typed or that go into URLs: enough digits to round-trip, none of float noise.
export function fmtExact(v) {
  return String(Number(Number(v).toPrecision(7)));
}

export function fmtCount(n) {
  return Number.isFinite(n) ? Math.round(n).toLocaleString('en-US') : '–';
}

export function fmtSeconds(s) {
  if (!Number.isFinite(s)) return '–';
  return s < 10 ? `${s.toFixed(2)} s` : `${s.toFixed(1)} s`;
}
