// What a dataset's kind allows: a .vots dataset ("kind": "vots") is drawn from its file alone. No DOM lookups.
import { OPERATOR_REASON, isViewerRole } from './role.js';

export function isVotsDataset(ds) {
  return ds?.kind === 'vots';
}

export const VOTS_EPS_REASON =
  'This dataset is a Vot-Space file fitted at one error bound; another ε needs a refit of its volume, which the server does not have.';
export const VOTS_REFERENCE_REASON =
  'This dataset is a Vot-Space file: the reference ray caster needs the volume\'s grid, which the server does not have.';

// A view the dataset can draw: a .vots dataset at its own eps, never on the grid renderer (the server answers 409).
export function fitViewToDataset(view, ds) {
  if (!isVotsDataset(ds)) return;
  const eps = Number(ds.eps);
  if (eps > 0) view.eps = eps;
  view.renderer = 'vots';
}

// Disables the eps slider and the grid renderer for a .vots dataset, saying why in their tooltips; the
// slider stays greyed for a viewer's token (role.js), whatever the dataset.
export function syncKindLimits(el, ds) {
  const vots = isVotsDataset(ds);
  el.epsSlider.disabled = vots || isViewerRole();
  el.epsSlider.title = vots ? VOTS_EPS_REASON : isViewerRole() ? OPERATOR_REASON : '';
  const grid = el.renderer.querySelector('option[value="grid"]');
  if (grid) {
    grid.disabled = vots;
    grid.title = vots ? VOTS_REFERENCE_REASON : '';
  }
  el.renderer.title = vots ? VOTS_REFERENCE_REASON : '';
}
