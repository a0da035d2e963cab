// Mouse, wheel and keys on the view, with VTK trackball habits: they move view.cam and ask for drafts and commits.
import { orbit, pan, zoomBy } from './camera.js';
import { homeCamera } from './view.js';

const WHEEL_SETTLE_MS = 200; // after the last wheel event, send the full-quality frame

// view: the view object the wiring owns; this sets view.cam. viewSize(): the view's {width, height}
// (watchSize). onDraft() runs after each move while the
// pointer or wheel is busy, onCommit() once a gesture ends. Returns {isMoving()}.
export function attachInput({ viewEl, viewSize, keyTarget, view, onDraft, onCommit }) {
  let dragging = null; // {kind: 'orbit'|'pan'|'zoom', x, y, pointerId}
  let wheelTimer = 0;

  viewEl.addEventListener('contextmenu', (e) => e.preventDefault());

  viewEl.addEventListener('pointerdown', (e) => {
    if (e.target.closest('#error')) return;
    let kind = null;
    if (e.button === 0) kind = e.shiftKey ? 'pan' : 'orbit';
    else if (e.button === 1) kind = 'pan';
    else if (e.button === 2) kind = 'zoom';
    if (!kind) return;
    e.preventDefault(); // no middle-click autoscroll, no text selection
    viewEl.setPointerCapture(e.pointerId);
    viewEl.classList.add('dragging');
    dragging = { kind, x: e.clientX, y: e.clientY, pointerId: e.pointerId };
  });

  viewEl.addEventListener('pointermove', (e) => {
    if (!dragging || e.pointerId !== dragging.pointerId) return;
    const dx = e.clientX - dragging.x;
    const dy = e.clientY - dragging.y;
    if (dx === 0 && dy === 0) return;
    dragging.x = e.clientX;
    dragging.y = e.clientY;
    const r = viewSize();
    if (dragging.kind === 'orbit') view.cam = orbit(view.cam, dx, dy, r.width, r.height);
    else if (dragging.kind === 'pan') view.cam = pan(view.cam, dx, dy, r.height);
    else view.cam = zoomBy(view.cam, dy * 2);
    onDraft();
  });

  function endDrag(e) {
    if (!dragging || e.pointerId !== dragging.pointerId) return;
    dragging = null;
    viewEl.classList.remove('dragging');
    onCommit();
  }
  viewEl.addEventListener('pointerup', endDrag);
  viewEl.addEventListener('pointercancel', endDrag);

  viewEl.addEventListener('wheel', (e) => {
    e.preventDefault();
    const lines = e.deltaMode === 1 ? 33 : e.deltaMode === 2 ? 400 : 1;
    view.cam = zoomBy(view.cam, e.deltaY * lines);
    onDraft();
    clearTimeout(wheelTimer);
    wheelTimer = setTimeout(() => {
      wheelTimer = 0;
      onCommit();
    }, WHEEL_SETTLE_MS);
  }, { passive: false });

  keyTarget.addEventListener('keydown', (e) => {
    if (e.target.closest('input, select, textarea') || e.ctrlKey || e.metaKey || e.altKey) return;
    if (e.key === 'r' || e.key === 'R') {
      view.cam = homeCamera(view.cam);
      onCommit();
    }
  });

  return { isMoving: () => dragging !== null || wheelTimer !== 0 };
}
