// A timed loop of steps that waits for the page: the turntable cine and the time cine both run on one.
// busy(): true while the last step's frame is on its way (the next step waits for it, so a slow server
// plays slowly and never skips). step() makes one step. minStepMs: the least time between two steps.
// onChange(running) when the loop starts or stops.
export function createStepper({ busy, step, minStepMs, onChange }) {
  let running = false;
  let timer = 0;
  let lastStep = 0;

  function next() {
    timer = 0;
    if (!running) return;
    const wait = minStepMs - (performance.now() - lastStep);
    if (busy() || wait > 0) {
      timer = setTimeout(next, Math.max(16, wait));
      return;
    }
    lastStep = performance.now();
    step();
    timer = setTimeout(next, minStepMs);
  }

  // firstStepNow: the first step comes at once rather than after minStepMs.
  function start({ firstStepNow = false } = {}) {
    if (running) return;
    running = true;
    lastStep = firstStepNow ? 0 : performance.now();
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

  return { start, stop, running: () => running };
}
