// Frames: the view's frames over the viewer socket (stream.js), else one /render request in flight at a
// time; drafts while moving, the exact frame once still, the shown image.
import { ApiError, fetchFrame, renderUrl, viewParamsRecord } from './api.js';
import { formatCamera } from './camera.js';
import { setData } from './dom.js';
import { DEFAULT_RENDERER, GRID_MODES, MAX_SERVED_SIDE } from './contract.js';
import { formatSlab } from './slab.js';
import { fmtExact } from './format.js';
import { openViewerSocket } from './stream.js';
import { VIEWER_ID } from './viewer-id.js';

const MAX_FRAME_PX = Math.min(2048, MAX_SERVED_SIDE); // longest side of a requested frame, in device pixels
const DRAFT_DIVISOR = 3; // frames while dragging are this much smaller, scaled up by CSS
const RESIZE_SETTLE_MS = 100; // a frame for the new view size once resizing pauses this long
// A drag that pauses this long, and for the time of PAUSE_DRAFTS drafts as the server last drew them, asks
// the socket for its exact frame at once, so that on release it is drawn already or drawing; moving on
// drops it on the server, between two bands of its render if that has begun, so a pause that was only a
// hitch of the hand holds the drag's next draft back for the band being drawn (an eighth of the still), not
// the whole still (bench/RESULTS.md measures what it costs). A loaded server draws slowly: the pause it
// takes for one grows with it.
const STILL_AFTER_PAUSE_MS = 100;
const PAUSE_DRAFTS = 2;
// A drag's views go out on the socket at most this often. A view per animation frame on a 240 Hz display,
// with the acknowledgements, passes the server's 240 messages a second, and the server closes a socket
// that does (1008; the page then falls back to /render). The server draws about 32 drafts a second and
// keeps only the newest view waiting, so a view sent more often only replaces one still waiting there.
const MIN_DRAFT_VIEW_GAP_MS = 8;
// A frame the server refused for being busy (429: this page's share of renders is taken; 503: its queue is
// full, or a fit it waited on is not there yet) is asked for again after RETRY_MS, up to RETRIES times in
// a row: a busy moment must not leave the view stale until the hand moves again. The banner says why;
// the status line reads as rendering meanwhile (busy()).
const RETRY_MS = 1000;
const RETRIES = 3;

// ?transport=render in the page's URL keeps to GET /render (the benchmark's baseline).
const SOCKET_WANTED = new URLSearchParams(window.location.search).get('transport') !== 'render';

// view: the view object the wiring owns (read at request time); viewSize(): its element's {width, height}
// (watchSize). banner: createBanner's object.
// showFacts({votCount, fitSeconds}) shows what a frame's headers say; isMoving() tells whether a drag or
// wheel is still going (then the next frame is a draft too); onChange() runs whenever the status may differ.
// draftCanvas: where the socket's JPEG drafts are drawn (over the image, hidden once the still is shown).
export function createFrames({ viewEl, viewSize, image, draftCanvas, view, banner, showFacts, isMoving, onChange }) {
  let renderEps = null; // eps used for frames: the target once its fit is done, else the previous one
  // No eps is ready yet but a fit is on its way: meanwhile frames come from the exact grid renderer,
  // which needs no fit (a study of thousands of slices shows its first image long before its Vots).
  let previewEps = null;
  let rafId = 0;
  let wantDraft = false;
  let inflight = null; // {url, draft, controller}
  let draftPending = false; // a drag moved while a draft was in flight: send another when it lands
  let shownUrl = null;
  let shownObjectUrl = null;
  let lastFrame = null; // {w, h, frameMs, draftEps (a socket draft's, else undefined)}
  let resizeTimer = 0;
  let pauseTimer = 0; // armed by each draft on the socket: the still of a paused drag
  let draftDrawMs = 0; // the server's time for the last draft shown
  let draftViewSentAt = -Infinity; // performance.now() of the last draft view sent on the socket
  let socket = null; // the viewer socket once open; null: frames come from GET /render
  let socketTried = false;
  let streamPending = null; // {seq, preview}: the newest view sent on the socket and not shown yet
  let streamSentKey = null; // what was sent last ("draft URL" or "still URL"): a repeat sends nothing
  let shownSeq = 0; // the socket frame shown last: an older one arriving later is not shown
  // A refit's new Vot-Space is first shown as a draft (drawn in a fraction of the still's time after its
  // upload), then as the still: the new eps is on screen as soon as it exists.
  let draftAtNewEps = false; // the next frame is the first at a new eps: a draft
  let stillAfterDraft = null; // that draft's request ({seq} on the socket, {url} on /render) until it lands
  const sentUrls = new Map(); // seq -> {url: its /render URL, sentAt: performance.now(), view: a copy}
  let retries = 0; // refusals in a row since the last frame shown
  let retryTimer = 0;

  function frameSize(draft) {
    const r = viewSize();
    const dpr = window.devicePixelRatio || 1;
    let w = Math.max(1, Math.round(r.width * dpr));
    let h = Math.max(1, Math.round(r.height * dpr));
    const s = Math.min(1, MAX_FRAME_PX / Math.max(w, h));
    w = Math.max(1, Math.round(w * s));
    h = Math.max(1, Math.round(h * s));
    if (draft) {
      w = Math.max(8, Math.round(w / DRAFT_DIVISOR));
      h = Math.max(8, Math.round(h / DRAFT_DIVISOR));
    }
    return { w, h };
  }

  // The /render parameters of the view at the size a frame of this kind gets (client: the page's id or none).
  function frameParams(draft, client) {
    const preview = previewing();
    return {
      dataset: view.dataset,
      frame: view.frame,
      cam: formatCamera(view.cam),
      size: frameSize(draft),
      eps: preview ? previewEps : renderEps,
      degree: view.degree,
      mode: view.mode,
      renderer: preview ? 'grid' : view.renderer,
      slab: view.slab ? formatSlab(view.slab) : undefined,
      window: { level: fmtExact(view.window.level), width: fmtExact(view.window.width) },
      colormap: view.colormap,
      client,
    };
  }

  // The grid draws GRID_MODES (not the density, Vot sizes, which waits for its Vots).
  function previewing() {
    return renderEps === null && previewEps !== null && GRID_MODES.includes(view.mode);
  }

  function frameUrl(draft) {
    return renderUrl(frameParams(draft, VIEWER_ID)); // the server answers our older ones 409 "superseded"
  }

  // Asks for a frame on the next animation frame; several changes in one frame cost one request.
  function schedule({ draft = false } = {}) {
    wantDraft = draft;
    clearTimeout(pauseTimer);
    const pauseMs = Math.max(STILL_AFTER_PAUSE_MS, PAUSE_DRAFTS * draftDrawMs);
    pauseTimer = draft && socket ? setTimeout(stillOnPause, pauseMs) : 0;
    // A still over the socket goes out at once: it ends a gesture, so there is nothing to gather into
    // one request, and waiting for the next animation frame added up to a frame's time to release -> lossless.
    if (!draft && socket) {
      cancelAnimationFrame(rafId);
      rafId = 0;
      return flush();
    }
    if (!rafId) rafId = requestAnimationFrame(flush);
    onChange();
  }

  function stillOnPause() {
    pauseTimer = 0;
    if (socket && !rafId && isMoving()) streamFlush(false);
  }

  function flush() {
    rafId = 0;
    if (!view.dataset || (renderEps === null && !previewing())) return onChange();
    if (socket && wantDraft && performance.now() - draftViewSentAt < MIN_DRAFT_VIEW_GAP_MS) {
      rafId = requestAnimationFrame(flush); // the newest camera goes with a later frame
      return;
    }
    const newEpsDraft = draftAtNewEps && !wantDraft; // not a drag's: the still follows when it lands
    const draft = wantDraft || newEpsDraft;
    draftAtNewEps = false;
    openSocketOnce();
    if (socket) return streamFlush(draft, newEpsDraft);
    const url = frameUrl(draft);
    if (inflight) {
      if (inflight.url === url) return onChange();
      // While dragging, let the current draft land (so frames keep coming) and then send the newest state.
      if (draft && inflight.draft) {
        draftPending = true;
        return onChange();
      }
      // Anything else makes the in-flight frame stale: drop it; the server drops it too (superseded).
      inflight.controller.abort();
      inflight = null;
    }
    if (url === shownUrl) return onChange();
    if (newEpsDraft) stillAfterDraft = { url };
    send(url, draft);
  }

  // After a refusal for being busy, the view is asked for again later (see RETRY_MS).
  function retryLater(status) {
    if ((status !== 429 && status !== 503) || retries >= RETRIES) return;
    retries += 1;
    clearTimeout(retryTimer);
    retryTimer = setTimeout(() => {
      retryTimer = 0;
      streamSentKey = null; // the socket sends the same view again
      schedule({ draft: isMoving() });
    }, RETRY_MS);
  }

  // A frame is on screen: the next refusal starts a new count.
  function frameShown() {
    retries = 0;
    clearTimeout(retryTimer);
    retryTimer = 0;
    banner.clear('render');
  }

  // The draft at a new eps has landed (shown or not): its still follows.
  function followWithStill() {
    stillAfterDraft = null;
    schedule({ draft: isMoving() });
  }

  async function send(url, draft) {
    const mine = { url, draft, controller: new AbortController(), sentAt: performance.now(), view: structuredClone(view) };
    const preview = previewing(); // a grid frame in place of Vots still being fitted: it says nothing of them
    inflight = mine;
    if (!draft) {
      draftPending = false;
      stillAfterDraft = null;
    }
    onChange();
    try {
      const frame = await fetchFrame(url, mine.controller.signal);
      if (inflight !== mine) return;
      if (!(await showPng(frame.blob, url, draft, () => inflight === mine))) return;
      image.dataset.transport = 'render';
      announceFrame({ sentAt: mine.sentAt, view: mine.view, still: !draft, transport: 'render', url, votCount: frame.votCount });
      lastFrame = { w: Number(image.dataset.width), h: Number(image.dataset.height), frameMs: frame.frameMs };
      if (!preview) {
        showFacts({
          votCount: frame.votCount !== null ? frame.votCount : undefined,
          fitSeconds: frame.fitSeconds !== null ? frame.fitSeconds : undefined,
        });
      }
      frameShown();
    } catch (e) {
      if (inflight !== mine) return;
      if (!(e instanceof ApiError && e.isIgnorable)) {
        banner.show(e.message, 'render');
        retryLater(e.status);
      }
    } finally {
      if (inflight === mine) {
        inflight = null;
        if (draftPending || stillAfterDraft?.url === url) {
          draftPending = false;
          followWithStill();
        }
      }
      onChange();
    }
  }

  // A "vots:frame" event on the image once a frame is on screen: {sentAt (when its view was asked for,
  // performance.now()), view (a copy of the view it shows), width, height, still, transport, eps (the
  // eps it was drawn at: the view's, or a socket draft's draftEps; null for the exact grid), votCount, and
  // socket frames only the server's times (docs/API.md): waitMs, frameMs, uploadMs, encodeMs, drawMs}.
  // The overlays follow it (ui.js); bench/stream_drag.mjs times drags, bench/eps_change.mjs refits.
  // url: the frame's /render URL.
  function announceFrame({ url, ...detail }) {
    const shownSize = draftCanvas.hidden
      ? { width: Number(image.dataset.width), height: Number(image.dataset.height) }
      : { width: draftCanvas.width, height: draftCanvas.height };
    const params = new URLSearchParams(url.split('?')[1]);
    const { draftEps, ...rest } = detail;
    const eps = params.get('renderer') === 'grid' ? null : (draftEps ?? Number(params.get('eps')));
    image.dispatchEvent(new CustomEvent('vots:frame', { detail: { ...rest, ...shownSize, eps } }));
  }

  // Shows a PNG (or any image) blob as the frame of `url`; false when current() says it is stale by then.
  async function showPng(blob, url, draft, current) {
    const objectUrl = URL.createObjectURL(blob);
    const probe = new Image();
    probe.src = objectUrl;
    try {
      await probe.decode();
    } catch {
      URL.revokeObjectURL(objectUrl);
      throw new ApiError('Rendering: the server sent an image the browser cannot decode');
    }
    if (!current()) {
      URL.revokeObjectURL(objectUrl);
      return false;
    }
    image.src = objectUrl;
    image.dataset.quality = draft ? 'draft' : 'full';
    image.dataset.frameUrl = url;
    image.dataset.renderer = new URLSearchParams(url.split('?')[1]).get('renderer') || DEFAULT_RENDERER;
    image.dataset.width = String(probe.naturalWidth);
    image.dataset.height = String(probe.naturalHeight);
    if (shownObjectUrl) URL.revokeObjectURL(shownObjectUrl);
    shownObjectUrl = objectUrl;
    shownUrl = url;
    draftCanvas.hidden = true;
    return true;
  }

  // The socket opens with the first frame; until it is open (and if it never opens, or closes) frames
  // come from GET /render.
  function openSocketOnce() {
    if (socketTried || !SOCKET_WANTED) return;
    socketTried = true;
    const opening = openViewerSocket({
      onFrame: showStreamFrame,
      onError: (message) => {
        const latest = !streamPending || message.seq >= streamPending.seq; // not an older view's refusal
        if (latest) streamPending = null;
        if (stillAfterDraft && message.seq >= stillAfterDraft.seq) followWithStill();
        banner.show(`Rendering: ${message.error} (HTTP ${message.status})`, 'render');
        if (latest) retryLater(message.status);
        onChange();
      },
      onDown: () => {
        socket = null;
        stillAfterDraft = null;
        streamPending = null;
        streamSentKey = null;
        schedule({ draft: isMoving() });
      },
    });
    opening.ready.then((open) => {
      if (!open) return;
      socket = opening;
      if (inflight) {
        inflight.controller.abort(); // its frame would land after the socket's newer ones
        inflight = null;
      }
      schedule({ draft: isMoving() });
    });
  }

  // The view at full size goes out; the server draws drafts at the size its frame budget allows. The
  // draft at a new eps goes out at /render's draft size (the server scales it by its budget again): the
  // still waits for it, so it must be quick.
  function streamFlush(draft, newEpsDraft = false) {
    const params = frameParams(newEpsDraft, undefined);
    const url = renderUrl(params);
    const key = `${draft ? 'draft' : 'still'} ${url}`;
    if (key === streamSentKey || (!draft && url === shownUrl)) return onChange();
    streamSentKey = key;
    const seq = socket.sendView(viewParamsRecord(params), !draft);
    if (draft) draftViewSentAt = performance.now();
    stillAfterDraft = newEpsDraft ? { seq } : null;
    sentUrls.set(seq, { url, sentAt: performance.now(), view: structuredClone(view) });
    streamPending = { seq, preview: previewing() };
    onChange();
  }

  async function showStreamFrame(header, blob) {
    // The still is asked for as soon as the draft at a new eps is here, while the page decodes the draft.
    if (stillAfterDraft && header.seq >= stillAfterDraft.seq) followWithStill();
    const sent = sentUrls.get(header.seq);
    for (const seq of sentUrls.keys()) if (seq < header.seq) sentUrls.delete(seq); // drawn no more
    if (header.seq < shownSeq || sent === undefined) return;
    const { url } = sent;
    const current = () => header.seq >= shownSeq;
    try {
      if (header.still) {
        if (!(await showPng(blob, url, false, current))) return;
      } else {
        const bitmap = await createImageBitmap(blob);
        if (!current()) return bitmap.close();
        draftCanvas.width = bitmap.width;
        draftCanvas.height = bitmap.height;
        draftCanvas.getContext('2d').drawImage(bitmap, 0, 0);
        bitmap.close();
        draftCanvas.hidden = false;
        setData(image, 'quality', 'draft');
        draftDrawMs = header.drawMs || 0;
        shownUrl = `draft ${url}`;
      }
    } catch (e) {
      banner.show(e.message || 'Rendering: the server sent an image the browser cannot decode', 'render');
      return;
    }
    shownSeq = header.seq;
    setData(image, 'transport', 'socket');
    const { waitMs, frameMs, uploadMs, encodeMs, drawMs, votCount, draftEps } = header;
    announceFrame({ url, sentAt: sent.sentAt, view: sent.view, still: header.still, transport: 'socket', waitMs, frameMs, uploadMs, encodeMs, drawMs, votCount, draftEps });
    lastFrame = { w: header.width, h: header.height, frameMs: header.frameMs, draftEps };
    const preview = streamPending ? streamPending.preview : previewing();
    if (streamPending && header.seq >= streamPending.seq) streamPending = null;
    if (!preview && header.still) showFacts({ votCount: header.votCount, fitSeconds: header.fitSeconds });
    frameShown();
    onChange();
  }

  new ResizeObserver(() => {
    clearTimeout(resizeTimer);
    resizeTimer = setTimeout(() => {
      resizeTimer = 0;
      schedule();
    }, RESIZE_SETTLE_MS);
    onChange();
  }).observe(viewEl);

  return {
    schedule,
    // Frames from now on use this eps (null: none until a fit is done). refitted: its Vot-Space has just
    // been fitted, so the server has yet to upload it: the first frame at it is a draft, then the still.
    useEps(eps, { refitted = false } = {}) {
      draftAtNewEps = refitted && eps !== null && renderEps !== null && eps !== renderEps;
      renderEps = eps;
      if (eps === null) previewEps = null;
    },
    // A fit for eps is running while no eps is ready: show the exact grid until it is done.
    previewWhileFitting(eps) {
      previewEps = eps;
      if (renderEps === null) schedule();
    },
    // Whether the frames now come from the grid in place of the Vots that are still being fitted.
    previewing,
    busy: () => Boolean(inflight || rafId || resizeTimer || retryTimer || draftPending || streamPending || stillAfterDraft),
    // The full-quality frame's parameters without the page's id (for download links), null before a fit.
    viewParams: () => (view.dataset && renderEps !== null ? frameParams(false, undefined) : null),
    hasShownFrame: () => shownUrl !== null,
    lastFrame: () => lastFrame,
  };
}
