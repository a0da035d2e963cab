// The colour bar beside the image: the colour map as a gradient and the window's ends in data units; no fetches.

import { COLORMAP_TABLES, DEFAULT_COLORMAP } from './contract.js';

// Every 17th of a map's 256 colours (the server's tables, generated into contract.js), as evenly spaced
// CSS gradient stops: grey, hot and bone are linear between corners at entries 85 and 170, which are
// among them, so those bars are exact; viridis is drawn straight between 16 points of its spline.
const STOP_EVERY = 17;
function gradientStops(map) {
  const table = COLORMAP_TABLES[map] || COLORMAP_TABLES[DEFAULT_COLORMAP];
  return table.filter((_, i) => i % STOP_EVERY === 0);
}

// The unit of the values a mode shows: Hounsfield units for CT (or what /api/datasets names), none for
// the density view, whose values are Vot sizes.
export function valueUnit(ds, mode) {
  if (mode === 'density') return '';
  if (typeof ds?.units === 'string') return ds.units;
  return ds?.modality === 'CT' ? 'HU' : '';
}

// {low, high, unit, gradient} for the view: what the darkest and the brightest colour stand for.
export function colorbarOf(view, ds) {
  const { level, width } = view.window;
  return {
    low: level - width / 2,
    high: level + width / 2,
    unit: valueUnit(ds, view.mode),
    gradient: `linear-gradient(to top, ${gradientStops(view.colormap).join(', ')})`,
  };
}
