// Cine: turns the camera about the vertical axis, one server frame after another, until stopped.
import { normalize } from './camera.js';
import { TURN_FRAMES } from './downloads.js';

const STEP_DEG = 360 / TURN_FRAMES;
const MIN_STEP_MS = 80; // at most about 12 frames a second, even when every frame is a cache hit

// view: the view object the wiring owns (this sets view.cam). frames: createFrames's object.
// onStep() runs after each turn of the camera; onChange(running) when cine starts or stops.
export function createCine({ view, frames, onStep, onChange }) {
  let running = false;
  let startAz = 0;
  let step = 0;
  let timer = 0;
  let lastStep = 0;

  // Every turn asks for the same azimuths (the start plus whole steps), so from the second turn on each
  // frame is the server's cached answer to the same request.
  function next() {
    timer = 0;
    if (!running) return;
    const wait = MIN_STEP_MS - (performance.now() - lastStep);
    // The next angle only once the last frame has landed: a slow renderer turns slowly, never skips.
    if (frames.busy() || wait > 0) {
      timer = setTimeout(next, Math.max(16, wait));
      return;
    }
    step = (step + 1) % TURN_FRAMES;
    view.cam = normalize({ ...view.cam, az: startAz + step * STEP_DEG });
    lastStep = performance.now();
    onStep();
    timer = setTimeout(next, MIN_STEP_MS);
  }

  function start() {
    if (running) return;
    running = true;
    startAz = view.cam.az;
    step = 0;
    lastStep = performance.now();
    onChange(true);
    next();
  }

  function stop() {
    if (!running) return;
    running = false;
    clearTimeout(timer);
    timer = 0;
    onChange(false);
  }

  return {
    start,
    stop,
    toggle: () => (running ? stop() : start()),
    running: () => running,
  };
}
