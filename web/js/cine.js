// Cine: turns the camera about the vertical axis, one server frame after another, until stopped.
import { normalize } from './camera.js';
import { TURN_FRAMES } from './downloads.js';
import { createStepper } from './stepper.js';

const STEP_DEG = 360 / TURN_FRAMES;
const MIN_STEP_MS = 80; // at most about 12 frames a second, even when every frame is a cache hit

// view: the view object the wiring owns (this sets view.cam). frames: createFrames's object.
// onStep() runs after each turn of the camera; onChange(running) when cine starts or stops.
export function createCine({ view, frames, onStep, onChange }) {
  let startAz = 0;
  let step = 0;

  // Every turn asks for the same azimuths (the start plus whole steps), so from the second turn on each
  // frame is the server's cached answer to the same request.
  const stepper = createStepper({
    busy: () => frames.busy(),
    step() {
      step = (step + 1) % TURN_FRAMES;
      view.cam = normalize({ ...view.cam, az: startAz + step * STEP_DEG });
      onStep();
    },
    minStepMs: MIN_STEP_MS,
    onChange,
  });

  function start() {
    if (stepper.running()) return;
    startAz = view.cam.az;
    step = 0;
    stepper.start();
  }

  return {
    start,
    stop: stepper.stop,
    toggle: () => (stepper.running() ? stepper.stop() : start()),
    running: stepper.running,
  };
}
