// The eps slider's wiring: its label while it moves, and when a move becomes a refit.
import { epsLabel, sliderToEps } from './eps.js';

// A slider at rest this long fits its value: a pointer holding the thumb still (before the release; a hand
// that stops to read the label rests for hundreds of ms, between the input events of a moving one lie a
// few), or keyboard steps (Chromium fires `change` for every arrow-key step, and a held key steps ~30 times
// a second). The server cancels the fit when this page asks for another (a viewer wants one fit at a
// time), so a rest that the hand ends costs the cores only the rest.
const EPS_SETTLE_MS = 150;

// slider, label: the elements. currentDataset(): the dataset shown, or null. view: the view, whose eps
// this sets. refit(): commits the view with its new eps.
export function attachEpsSlider({ slider, label, currentDataset, view, refit }) {
  let settleTimer = 0; // keyboard steps waiting to settle
  let restTimer = 0; // a held pointer's rest
  let byKey = false;
  let pointerHeld = false;

  function cancelSettle() {
    clearTimeout(settleTimer);
    settleTimer = 0;
  }
  function cancelRest() {
    clearTimeout(restTimer);
    restTimer = 0;
  }
  // The eps the slider shows becomes the view's; false without a dataset.
  function adopt() {
    const ds = currentDataset();
    if (!ds) return false;
    view.eps = sliderToEps(ds, Number(slider.value));
    return true;
  }
  // The same, true only when that changed the view's eps (a rest already fitted what a release lands on).
  function adoptNew() {
    const before = view.eps;
    return adopt() && view.eps !== before;
  }

  slider.addEventListener('input', () => {
    const ds = currentDataset();
    if (ds) label.textContent = epsLabel(ds, sliderToEps(ds, Number(slider.value)));
    if (!pointerHeld) return;
    cancelRest();
    restTimer = setTimeout(() => {
      restTimer = 0;
      if (pointerHeld && adoptNew()) refit();
    }, EPS_SETTLE_MS);
  });
  slider.addEventListener('keydown', () => {
    byKey = true;
  });
  slider.addEventListener('pointerdown', () => {
    byKey = false;
    pointerHeld = true;
  });
  for (const type of ['pointerup', 'pointercancel']) {
    window.addEventListener(type, () => {
      pointerHeld = false;
      cancelRest();
    }, { capture: true });
  }
  slider.addEventListener('change', () => {
    cancelSettle();
    cancelRest();
    if (!byKey) {
      // A pointer's release is one deliberate choice: fit at once (unless its rest already asked).
      if (adoptNew()) refit();
      return;
    }
    settleTimer = setTimeout(() => {
      settleTimer = 0;
      if (adopt()) refit();
    }, EPS_SETTLE_MS);
  });

  return {
    // Adopts a keyboard step still settling, for a commit that takes it along; true when there was one.
    takeSettling() {
      if (!settleTimer) return false;
      cancelSettle();
      return adopt();
    },
    // Forgets what the slider was about to fit (another dataset, or a link, says what the view is now).
    cancel() {
      cancelSettle();
      cancelRest();
    },
  };
}
