// Client of the server's PACS routes (/api/pacs): services, study and series searches, opening a series.
import { ApiError, request } from './api.js';

const POLL_MS = 250; // an open's progress is asked this often while it retrieves

const servicePath = (service) => `api/pacs/${encodeURIComponent(service)}`;

async function json(url, init, what) {
  const res = await request(url, { cache: 'no-store', ...init }, what);
  return res.json();
}

// [{name, url}]: the PACS `vots serve --dicomweb` named; empty when none.
export async function fetchPacsServices() {
  const body = await json('api/pacs', {}, 'Listing the PACS');
  return Array.isArray(body?.services) ? body.services : [];
}

// query: {patientName, patientId, dateFrom, dateTo, modality, accessionNumber}; empty fields are left out.
export async function searchStudies(service, query) {
  const q = new URLSearchParams();
  for (const [key, value] of Object.entries(query)) if (value) q.set(key, value);
  const body = await json(`${servicePath(service)}/studies?${q}`, {}, 'Searching the PACS');
  return Array.isArray(body?.studies) ? body.studies : [];
}

export async function fetchStudySeries(service, studyUid) {
  const body = await json(`${servicePath(service)}/studies/${encodeURIComponent(studyUid)}/series`, {},
    'Listing the series');
  return Array.isArray(body?.series) ? body.series : [];
}

const postJson = { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: '{}' };

export function cancelSeriesOpen(id) {
  return json(`api/pacs/opens/${encodeURIComponent(id)}/cancel`, postJson, 'Cancelling the retrieve');
}

// Starts (or joins) the open of a series and polls it. onProgress(open) sees every answer; returns
// {done, cancel()}: done resolves with the finished open ({dataset, fromCache, ...}) and rejects with an
// ApiError carrying the failure's status (401, 404, 502, 504, 507) and message; cancel() asks the server
// to stop, and done then never settles.
export function followSeriesOpen(service, studyUid, seriesUid, onProgress) {
  let id = null;
  let stopped = false;
  let timer = 0;
  const done = (async () => {
    let open = await json(
      `${servicePath(service)}/studies/${encodeURIComponent(studyUid)}/series/${encodeURIComponent(seriesUid)}/open`,
      postJson, 'Opening the series');
    id = open.id;
    for (;;) {
      if (stopped) throw new ApiError('Opening the series: cancelled', { aborted: true });
      onProgress(open);
      if (open.state === 'done') return open;
      if (open.state === 'failed' || open.state === 'cancelled') {
        throw new ApiError(`Opening the series: ${open.error || open.state} (HTTP ${open.status})`,
          { status: open.status || 0, aborted: open.state === 'cancelled' });
      }
      await new Promise((resolve) => { timer = setTimeout(resolve, POLL_MS); });
      open = await json(`api/pacs/opens/${encodeURIComponent(id)}`, {}, 'Opening the series');
    }
  })();
  return {
    done,
    cancel() {
      stopped = true;
      clearTimeout(timer);
      if (id !== null) cancelSeriesOpen(id).catch(() => {}); // it ends as cancelled either way
    },
  };
}

export function cancelSweepSend(id) {
  return json(`api/pacs/stores/${encodeURIComponent(id)}/cancel`, postJson, 'Cancelling the send');
}

// Sends a slab sweep of the view to the PACS (POST /api/pacs/{service}/store) and polls it until it ends.
// body: {dataset, cam, mode, thickness, step, size, renderer, eps, window}. onProgress(store) sees every
// answer. Returns {done, cancel()}: done resolves with the finished store ({stored, description}) and
// rejects with an ApiError carrying the status (400, 401, 404, 409, 502, 504) and message, or `aborted`
// once cancel() has asked the server to stop (nothing is stored then).
export function sendSweep(service, body, onProgress) {
  let id = null;
  let stopped = false;
  let timer = 0;
  const cancelled = () => new ApiError('Sending to the PACS: cancelled', { aborted: true });
  const done = (async () => {
    let store = await json(`${servicePath(service)}/store`,
      { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) },
      'Sending to the PACS');
    id = store.id;
    if (stopped) cancelSweepSend(id).catch(() => {});
    for (;;) {
      if (stopped) throw cancelled();
      onProgress(store);
      if (store.state === 'done') return store;
      if (store.state === 'cancelled') throw cancelled();
      if (store.state === 'failed') {
        throw new ApiError(`Sending to the PACS: ${store.error || 'failed'} (HTTP ${store.status})`,
          { status: store.status || 0 });
      }
      await new Promise((resolve) => { timer = setTimeout(resolve, POLL_MS); });
      if (stopped) throw cancelled();
      store = await json(`api/pacs/stores/${encodeURIComponent(store.id)}`, {}, 'Sending to the PACS');
    }
  })();
  return {
    done,
    cancel() {
      stopped = true;
      clearTimeout(timer);
      if (id !== null) cancelSweepSend(id).catch(() => {}); // it ends as cancelled either way
    },
  };
}
