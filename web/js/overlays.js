// What is drawn over the image: the edge labels, the colour bar and the scale bar, from the view and its dataset.
import { colorbarOf } from './colorbar.js';
import { setData, setText } from './dom.js';
import { fmtValue } from './format.js';
import { edgeLabels } from './orientation.js';
import { scaleBarOf } from './scalebar.js';

// el: {view, edgeLabels, colorbar, colorbarRamp, colorbarHigh, colorbarLow, scalebar, scalebarLine,
// scalebarLabel}; cheap enough for every pointer move.
export function showOverlays(el, view, ds) {
  const labels = ds ? edgeLabels(view.cam, ds.orientation ?? null) : null;
  for (const label of el.edgeLabels) {
    label.hidden = !labels;
    setText(label, labels ? labels[label.dataset.edge] : '');
    setData(label, 'kind', labels ? labels.kind : '');
  }

  el.colorbar.hidden = !ds;
  if (ds) {
    const bar = colorbarOf(view, ds);
    const unit = bar.unit ? ` ${bar.unit}` : '';
    el.colorbarRamp.style.backgroundImage = bar.gradient;
    setText(el.colorbarHigh, `${fmtValue(bar.high)}${unit}`);
    setText(el.colorbarLow, `${fmtValue(bar.low)}${unit}`);
    setData(el.colorbar, 'colormap', view.colormap);
  }

  const scale = scaleBarOf(ds, view.cam, el.view.clientHeight);
  el.scalebar.hidden = !scale;
  if (scale) {
    el.scalebarLine.style.width = `${scale.px.toFixed(1)}px`;
    setText(el.scalebarLabel, scale.label);
    setData(el.scalebar, 'mm', String(scale.mm));
    setData(el.scalebar, 'px', scale.px.toFixed(3));
  }
}
