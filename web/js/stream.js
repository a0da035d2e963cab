// The viewer socket (GET /api/stream, docs/API.md "Viewer socket"): views out, frames in, each frame
// acknowledged once it is shown, so the server never draws ahead of what the page can show.
import { withTokenQuery } from './access.js';

// onFrame(header, blob) shows a frame and resolves once it is on screen (then it is acknowledged);
// onError(message) gets the server's {"type":"error"} answers; onDown() runs once the socket is gone.
// Returns {ready: Promise<boolean>, isOpen(), sendView(params, still) -> seq}.
export function openViewerSocket({ onFrame, onError, onDown }) {
  const url = new URL(withTokenQuery('api/stream'), window.location.href);
  url.protocol = url.protocol === 'https:' ? 'wss:' : 'ws:';
  let ws;
  try {
    ws = new WebSocket(url);
  } catch {
    return { ready: Promise.resolve(false), isOpen: () => false, sendView: () => 0 };
  }
  ws.binaryType = 'blob';
  let open = false;
  let seq = 0;
  let header = null; // the text header of the image that comes next
  let shown = Promise.resolve(); // frames are shown (and acknowledged) in the order they came

  const ready = new Promise((resolve) => {
    ws.addEventListener('open', () => {
      open = true;
      resolve(true);
    });
    ws.addEventListener('close', () => {
      const wasOpen = open;
      open = false;
      resolve(false);
      if (wasOpen) onDown();
    });
  });

  ws.addEventListener('message', (e) => {
    if (typeof e.data === 'string') {
      let message;
      try {
        message = JSON.parse(e.data);
      } catch {
        return;
      }
      if (message.type === 'frame') header = message;
      else if (message.type === 'error') onError(message);
      return;
    }
    const frameHeader = header;
    header = null;
    if (!frameHeader) return;
    shown = shown
      .then(() => onFrame(frameHeader, e.data))
      .catch(() => {})
      .then(() => {
        if (open) ws.send(JSON.stringify({ type: 'ack', frame: frameHeader.frame }));
      });
  });

  return {
    ready,
    isOpen: () => open,
    sendView(params, still) {
      seq += 1;
      ws.send(JSON.stringify({ type: 'view', seq, still, params }));
      return seq;
    },
  };
}
