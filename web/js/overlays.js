// What is drawn over the image: the edge labels, the colour bar and the scale bar, from the view and its dataset.
import { colorbarOf } from './colorbar.js';
import { fmtValue } from './format.js';
import { edgeLabels } from './orientation.js';
import { scaleBarOf } from './scalebar.js';

// el: {view, edgeLabels, colorbar, colorbarRamp, colorbarHigh, colorbarLow, scalebar, scalebarLine,
// scalebarLabel}; cheap enough for every pointer move.
export function showOverlays(el, view, ds) {
  const labels = ds ? edgeLabels(view.cam, ds.orientation ?? null) : null;
  for (const label of el.edgeLabels) {
    label.hidden = !labels;
    label.textContent = labels ? labels[label.dataset.edge] : '';
    label.dataset.kind = labels ? labels.kind : '';
  }

  el.colorbar.hidden = !ds;
  if (ds) {
    const bar = colorbarOf(view, ds);
    const unit = bar.unit ? ` ${bar.unit}` : '';
    el.colorbarRamp.style.backgroundImage = bar.gradient;
    el.colorbarHigh.textContent = `${fmtValue(bar.high)}${unit}`;
    el.colorbarLow.textContent = `${fmtValue(bar.low)}${unit}`;
    el.colorbar.dataset.colormap = view.colormap;
  }

  const scale = scaleBarOf(ds, view.cam, el.view.clientHeight);
  el.scalebar.hidden = !scale;
  if (scale) {
    el.scalebarLine.style.width = `${scale.px.toFixed(1)}px`;
    el.scalebarLabel.textContent = scale.label;
    el.scalebar.dataset.mm = String(scale.mm);
    el.scalebar.dataset.px = scale.px.toFixed(3);
  }
}
