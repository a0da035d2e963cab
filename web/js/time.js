// The frame slider and the time cine of a 4D dataset (fMRI, perfusion, cardiac phases): which 3D volume is shown.
import { createStepper } from './stepper.js';

const MIN_STEP_MS = 120; // at most about 8 volumes a second, even when every frame is a cache hit

// 0-based, as /render's frame= and `vots render --frame` count them.
const frameLabel = (frame, frames) => `${frame} (of 0–${frames - 1})`;

// el: {box, slider, value, cine}. view: the view object the wiring owns (this sets view.frame). dataset():
// the current dataset. busy(): true while a fit or a frame is on its way. showFrame() draws view.frame (and
// fits it first when needed); stopTurn() ends the turntable cine, which the time cine does not run beside.
export function attachTimeControl({ el, view, dataset, busy, showFrame, stopTurn }) {
  const frameCount = () => Math.max(1, Number(dataset()?.frames) || 1);

  function choose(frame) {
    view.frame = frame;
    sync();
    showFrame();
  }

  // The next volume only once the last one has been fitted and drawn.
  const stepper = createStepper({
    busy,
    step: () => choose((view.frame + 1) % frameCount()),
    minStepMs: MIN_STEP_MS,
    onChange(running) {
      el.cine.setAttribute('aria-pressed', String(running));
      el.cine.textContent = running ? 'Stop time cine' : 'Time cine';
    },
  });

  function sync() {
    const frames = frameCount();
    el.box.hidden = frames < 2; // a 3D dataset has no time to choose
    if (view.frame >= frames) view.frame = 0;
    el.slider.max = String(frames - 1);
    el.slider.value = String(view.frame);
    el.value.textContent = frameLabel(view.frame, frames);
    if (frames < 2) stepper.stop();
  }

  function start() {
    if (stepper.running() || frameCount() < 2) return;
    stopTurn();
    stepper.start({ firstStepNow: true });
  }

  el.slider.addEventListener('input', () => {
    stepper.stop();
    el.value.textContent = frameLabel(Number(el.slider.value), frameCount());
  });
  el.slider.addEventListener('change', () => {
    stepper.stop();
    choose(Number(el.slider.value));
  });
  el.cine.addEventListener('click', () => (stepper.running() ? stepper.stop() : start()));

  return { sync, stop: stepper.stop, running: stepper.running };
}
