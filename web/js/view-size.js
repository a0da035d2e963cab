// The view's size in CSS pixels, kept up to date by a ResizeObserver instead of read from the layout.

// Returns a function giving {width, height} of `el`'s border box. Reading getBoundingClientRect at every
// pointer move forced a layout each time, since each frame shown changes the overlays' text (a CPU
// profile of a drag: bench/RESULTS.md, "Eight viewers: where the two cores go").
export function watchSize(el) {
  const first = el.getBoundingClientRect();
  let size = { width: first.width, height: first.height };
  new ResizeObserver(([entry]) => {
    const box = entry.borderBoxSize?.[0];
    size = box ? { width: box.inlineSize, height: box.blockSize } : { width: entry.contentRect.width, height: entry.contentRect.height };
  }).observe(el);
  return () => size;
}
