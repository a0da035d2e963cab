// The benchmarks' drag: from the image's centre, `reach` pixels to the right with a sine wave up and down,
// as a 60 Hz mouse moves, then released.

const MOVE_EVERY_MS = 16; // a 60 Hz mouse

export async function dragAcrossImage(page, viewer, dragMs, reach) {
  const box = await viewer.image.boundingBox();
  const x = box.x + box.width / 2;
  const y = box.y + box.height / 2;
  await page.mouse.move(x, y);
  await page.mouse.down();
  const steps = Math.round(dragMs / MOVE_EVERY_MS);
  const start = Date.now();
  for (let i = 1; i <= steps; i++) {
    await page.mouse.move(x + reach * (i / steps), y + 40 * Math.sin((2 * Math.PI * i) / steps));
    const wait = start + i * MOVE_EVERY_MS - Date.now();
    if (wait > 0) await page.waitForTimeout(wait);
  }
  await page.mouse.up();
}
