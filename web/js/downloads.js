// The "Download" links: the current frame as the PNG the server renders, and a turn as WebM (GET /turntable).
import { withTokenQuery } from './access.js';
import { renderUrl, turntableUrl } from './api.js';

export const TURN_FRAMES = 36; // one frame every 10 degrees, as the cine button turns

// links: {png, turn} anchors; params: frames.viewParams() (null before the first fit: links disabled).
export function syncDownloads(links, params) {
  for (const a of [links.png, links.turn]) a.setAttribute('aria-disabled', String(!params));
  if (!params) {
    links.png.removeAttribute('href');
    links.turn.removeAttribute('href');
    return;
  }
  // A link cannot send the Authorization header, so a server that asks for a token gets it as token=.
  links.png.href = withTokenQuery(renderUrl(params));
  links.turn.href = withTokenQuery(turntableUrl(params, TURN_FRAMES));
  links.png.download = `${params.dataset}-${params.mode}.png`;
  links.turn.download = `${params.dataset}-${params.mode}-turn.webm`;
}
