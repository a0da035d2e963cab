// Thin client for the vots HTTP contract (datasets, render, fit jobs); knows no DOM and no UI state. request() is
// shared with pacs-api.js.
import { withToken, withTokenQuery } from './access.js';
import { DEFAULT_RENDERER } from './contract.js';

// Thrown for every failure the user should see; `superseded`/`aborted` ones are expected and ignored.
export class ApiError extends Error {
  constructor(message, { status = 0, superseded = false, aborted = false } = {}) {
    super(message);
    this.name = 'ApiError';
    this.status = status;
    this.superseded = superseded;
    this.aborted = aborted;
  }

  get isIgnorable() {
    return this.superseded || this.aborted;
  }
}

// Reads the server's {"error": "..."} body; falls back to the status line when the body is not JSON.
async function errorFromResponse(res, what) {
  let message = `${res.status} ${res.statusText}`.trim();
  try {
    const body = await res.json();
    if (body && typeof body.error === 'string') message = body.error;
  } catch {
    // Not JSON (a proxy page or an empty body): the status line is the best we have.
  }
  const superseded = res.status === 409 && message === 'superseded';
  return new ApiError(`${what}: ${message} (HTTP ${res.status})`, { status: res.status, superseded });
}

export async function request(url, init, what) {
  let res;
  try {
    res = await fetch(url, withToken(init));
  } catch (e) {
    if (e.name === 'AbortError') throw new ApiError(`${what}: aborted`, { aborted: true });
    throw new ApiError(`${what}: cannot reach the server (${e.message})`);
  }
  if (!res.ok) throw await errorFromResponse(res, what);
  return res;
}

export async function fetchDatasets() {
  const res = await request('api/datasets', { cache: 'no-store' }, 'Loading datasets');
  const body = await res.json();
  if (!body || !Array.isArray(body.datasets)) throw new ApiError('Loading datasets: the server sent no dataset list');
  return body.datasets;
}

function viewQuery(p) {
  const q = new URLSearchParams();
  q.set('dataset', p.dataset);
  if (p.frame) q.set('frame', String(p.frame)); // frame 0 unsaid: a 3D dataset's query stays as it was
  q.set('cam', p.cam);
  q.set('size', `${p.size.w}x${p.size.h}`);
  q.set('eps', String(p.eps));
  if (p.degree !== undefined) q.set('degree', String(p.degree));
  q.set('mode', p.mode);
  // Only when not the default, so a view without them asks for exactly what it asked before.
  if (p.renderer && p.renderer !== DEFAULT_RENDERER) q.set('renderer', p.renderer);
  if (p.slab) q.set('slab', p.slab);
  q.set('window', `${p.window.level},${p.window.width}`);
  q.set('colormap', p.colormap);
  if (p.client) q.set('client', p.client);
  return q;
}

// The /render parameters as the viewer socket's view message carries them ({name: string}).
export function viewParamsRecord(p) {
  return Object.fromEntries(viewQuery(p));
}

// Builds the /render URL; parameter order is fixed so equal states give byte-equal URLs.
export function renderUrl(p) {
  return `render?${viewQuery(p)}`;
}

// GET /turntable: the /render parameters of the view plus the number of frames of one turn (WebM).
export function turntableUrl(p, frames) {
  const q = viewQuery(p);
  q.set('frames', String(frames));
  return `turntable?${q}`;
}

// Fetches one frame. Resolves to {blob, votCount, frameMs, fitSeconds}; rejects with ApiError.
export async function fetchFrame(url, signal) {
  const res = await request(url, { signal, cache: 'no-store' }, 'Rendering');
  const header = (name) => {
    const v = res.headers.get(name);
    return v === null || v === '' ? null : Number(v);
  };
  let blob;
  try {
    blob = await res.blob();
  } catch (e) {
    if (e.name === 'AbortError') throw new ApiError('Rendering: aborted', { aborted: true });
    throw new ApiError(`Rendering: the image download failed (${e.message})`);
  }
  return {
    blob,
    votCount: header('X-Vots-Vot-Count'),
    frameMs: header('X-Vots-Frame-Ms'),
    fitSeconds: header('X-Vots-Fit-Seconds'),
  };
}

// client: a viewer's id; the server cancels its older fit when it asks for another (unless others want it).
export async function startFit({ dataset, frame, eps, degree, client }) {
  const body = { dataset, eps };
  if (frame) body.frame = frame;
  if (degree !== undefined) body.degree = degree;
  if (client) body.client = client;
  const res = await request('api/fit', {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify(body),
  }, 'Starting the fit');
  const job = await res.json();
  if (job == null || job.job === undefined) throw new ApiError('Starting the fit: the server sent no job id');
  return job;
}

export async function fetchJob(id) {
  const res = await request(`api/jobs/${encodeURIComponent(id)}`, { cache: 'no-store' }, 'Fit status');
  return res.json();
}

// Follows a fit job: SSE first, and if the stream breaks, polling GET /api/jobs/{id}.
// Calls onProgress({progress, stage}); resolves with {votCount, fitSeconds}; rejects with ApiError.
// Returns {done: Promise, cancel()}; a cancelled follow never settles its promise again.
export function followJob(id, onProgress) {
  let cancelled = false;
  let source = null;
  let pollTimer = 0;
  let settle;
  const done = new Promise((resolve, reject) => {
    settle = { resolve, reject };
  });
  const finish = (fn, value) => {
    if (cancelled) return;
    cancelled = true;
    if (source) source.close();
    clearTimeout(pollTimer);
    fn(value);
  };
  const parse = (data) => {
    try {
      return JSON.parse(data);
    } catch {
      return {};
    }
  };

  const poll = async () => {
    if (cancelled) return;
    try {
      const job = await fetchJob(id);
      if (job.state === 'done') return finish(settle.resolve, job);
      if (job.state === 'failed') return finish(settle.reject, new ApiError(`Fit failed: ${job.error || 'unknown error'}`));
      onProgress({ progress: Number(job.progress) || 0, stage: job.stage || job.state });
    } catch (e) {
      return finish(settle.reject, e);
    }
    pollTimer = setTimeout(poll, 300);
  };

  source = new EventSource(withTokenQuery(`api/jobs/${encodeURIComponent(id)}/events`));
  source.addEventListener('progress', (e) => {
    if (!cancelled) onProgress(parse(e.data));
  });
  source.addEventListener('done', (e) => finish(settle.resolve, parse(e.data)));
  source.addEventListener('error', (e) => {
    if (cancelled) return;
    if (typeof e.data === 'string') {
      // A server-sent `event: error` carries data; the browser's own connection error does not.
      const body = parse(e.data);
      finish(settle.reject, new ApiError(`Fit failed: ${body.error || e.data || 'unknown error'}`));
    } else {
      // The stream broke or ended without `done`: stop the auto-reconnect and ask the job itself.
      source.close();
      source = null;
      poll();
    }
  });

  return {
    done,
    cancel() {
      cancelled = true;
      if (source) source.close();
      clearTimeout(pollTimer);
    },
  };
}
