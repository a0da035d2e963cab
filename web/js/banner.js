// The error banner: one message at a time, tagged with its source so a later success of that source clears it.

// source: 'render' | 'fit' | 'link' | 'datasets' | 'input'. onShow runs after a message appears.
export function createBanner({ box, text, closeButton, onShow }) {
  let source = null;
  closeButton.addEventListener('click', () => {
    source = null;
    box.hidden = true;
  });
  return {
    show(message, from) {
      source = from;
      text.textContent = message;
      box.hidden = false;
      onShow();
    },
    clear(from) {
      if (source !== from) return;
      source = null;
      box.hidden = true;
    },
    // The source of the message shown, or null when none is.
    source: () => source,
  };
}
