// The colour bar beside the image: the colour map as a gradient and the window's ends in data units; no fetches.

// CSS gradient stops that reproduce the server's maps (render/src/Colormap.cpp): grey, hot and bone are
// piecewise linear with corners at thirds, so these stops are exact; viridis is a spline through its
// five key colours, drawn here straight between them (the bar is a legend, not a measurement).
const GRADIENTS = {
  grey: ['#000', '#fff'],
  hot: ['#000', '#f00 33.333%', '#ff0 66.667%', '#fff'],
  bone: ['#000', 'rgb(74 74 106) 33.333%', 'rgb(149 181 181) 66.667%', '#fff'],
  viridis: ['#440154', '#3b528b', '#21918c', '#5ec962', '#fde725'],
};

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
    gradient: `linear-gradient(to top, ${(GRADIENTS[view.colormap] || GRADIENTS.grey).join(', ')})`,
  };
}
