// The slab controls: on/off, thickness in mm, and the slab's position along the view over the volume's depth.
import { fmtValue } from './format.js';
import { halfDepthAlongView } from './geometry.js';
import { clampSlabToView, DEFAULT_THICKNESS_MM } from './slab.js';

// el: {slabOn, slabThickness, slabOffset, slabOffsetValue}; view: the wiring's view object (this sets
// view.slab); dataset(): the view's dataset. onDraft() while the position slider moves, onCommit() after.
export function attachSlabControl({ el, view, dataset, banner, onDraft, onCommit }) {
  const thickness = () => {
    const t = Number(el.slabThickness.value);
    return el.slabThickness.value !== '' && t > 0 ? t : null;
  };

  el.slabOn.addEventListener('change', () => {
    view.slab = el.slabOn.checked ? { offset: 0, thickness: thickness() ?? DEFAULT_THICKNESS_MM } : null;
    onCommit();
  });

  el.slabThickness.addEventListener('change', () => {
    const t = thickness();
    if (t === null) {
      banner.show('Slab: the thickness must be a positive number of mm.', 'input');
      return onCommit(); // shows the thickness the view still has
    }
    banner.clear('input');
    // A thickness typed while the slab is off turns it on: that is what typing one asks for.
    view.slab = { offset: view.slab?.offset ?? 0, thickness: t };
    onCommit();
  });

  const readOffset = () => {
    if (!view.slab) return false;
    view.slab = { ...view.slab, offset: Number(el.slabOffset.value) };
    return true;
  };
  el.slabOffset.addEventListener('input', () => {
    if (readOffset()) onDraft();
  });
  el.slabOffset.addEventListener('change', () => {
    if (readOffset()) onCommit();
  });

  // The controls from the view; the slider spans the volume's depth along the current view direction.
  function sync() {
    const ds = dataset();
    if (ds) view.slab = clampSlabToView(view.slab, ds, view.cam);
    const half = ds ? Math.floor(halfDepthAlongView(ds, view.cam) * 10) / 10 : 0;
    el.slabOn.checked = view.slab !== null;
    if (view.slab) el.slabThickness.value = String(view.slab.thickness);
    else if (thickness() === null) el.slabThickness.value = String(DEFAULT_THICKNESS_MM);
    el.slabOffset.min = String(-half);
    el.slabOffset.max = String(half);
    el.slabOffset.value = String(view.slab ? view.slab.offset : 0);
    el.slabOffset.disabled = view.slab === null;
    el.slabOffset.dataset.half = String(half);
    const offset = view.slab ? view.slab.offset : 0;
    el.slabOffsetValue.textContent = view.slab
      ? `${offset > 0 ? '+' : ''}${fmtValue(offset)} mm of ±${fmtValue(half)}`
      : 'whole volume';
  }

  return { sync };
}
