// Writes to the page's elements that skip a value already there: Chromium lays out and repaints after any
// write, even of the same text, and the status line and view buttons are written at every pointer move.
export function setText(node, text) {
  if (node.textContent !== text) node.textContent = text;
}

export function setData(node, key, value) {
  if (node.dataset[key] !== value) node.dataset[key] = value;
}

export function setAttr(node, name, value) {
  if (node.getAttribute(name) !== value) node.setAttribute(name, value);
}
