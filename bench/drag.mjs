// The benchmarks' drag: from the image's centre, `reach` pixels to the right with a sine wave up and down,
// as a 60 Hz mouse moves, then released; VOTS_DRAG_HOLD_MS after the last move (default 0: at once, a
// flick), as a hand that stops on what it wants to see and then lets go; VOTS_DRAG_PAUSE_MS: the hand stops
// that long halfway and goes on (default 0).

const MOVE_EVERY_MS = 16; // a 60 Hz mouse

export async function dragAcrossImage(page, viewer, dragMs, reach) {
  const box = await viewer.image.boundingBox();
  const x = box.x + box.width / 2;
  const y = box.y + box.height / 2;
  await page.mouse.move(x, y);
  await page.mouse.down();
  const steps = Math.round(dragMs / MOVE_EVERY_MS);
  const pauseMs = Number(process.env.VOTS_DRAG_PAUSE_MS || 0);
  let start = Date.now();
  for (let i = 1; i <= steps; i++) {
    await page.mouse.move(x + reach * (i / steps), y + 40 * Math.sin((2 * Math.PI * i) / steps));
    if (pauseMs > 0 && i === Math.round(steps / 2)) {
      // The whole pause, however far behind the moves' schedule a busy browser has left the loop.
      await page.waitForTimeout(pauseMs);
      start = Date.now() - i * MOVE_EVERY_MS;
    }
    const wait = start + i * MOVE_EVERY_MS - Date.now();
    if (wait > 0) await page.waitForTimeout(wait);
  }
  const holdMs = Number(process.env.VOTS_DRAG_HOLD_MS || 0);
  if (holdMs > 0) await page.waitForTimeout(holdMs);
  await page.mouse.up();
}
