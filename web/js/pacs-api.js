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

// Starts a server job (start() gives its 202 answer) and polls `${jobsPath}/{id}` until it ends.
// onProgress(job) sees every answer. Returns {done, cancel()}: done resolves with the finished job and
// rejects with an ApiError carrying the failure's status and message, or `aborted` once cancel() has
// asked the server to stop it (POST `${jobsPath}/{id}/cancel`).
function followJob(start, jobsPath, what, onProgress) {
  let id = null;
  let stopped = false;
  let timer = 0;
  let wake = () => {};
  const cancelled = () => new ApiError(`${what}: cancelled`, { aborted: true });
  const cancelOnServer = () => {
    // It ends as cancelled either way.
    json(`${jobsPath}/${encodeURIComponent(id)}/cancel`, postJson, `${what}: cancelling`).catch(() => {});
  };
  const done = (async () => {
    let job = await start();
    id = job.id;
    if (stopped) cancelOnServer();
    for (;;) {
      if (stopped) throw cancelled();
      onProgress(job);
      if (job.state === 'done') return job;
      if (job.state === 'failed' || job.state === 'cancelled') {
        throw new ApiError(`${what}: ${job.error || job.state} (HTTP ${job.status})`,
          { status: job.status || 0, aborted: job.state === 'cancelled' });
      }
      await new Promise((resolve) => {
        wake = resolve;
        timer = setTimeout(resolve, POLL_MS);
      });
      if (stopped) throw cancelled();
      job = await json(`${jobsPath}/${encodeURIComponent(id)}`, {}, what);
    }
  })();
  return {
    done,
    cancel() {
      stopped = true;
      clearTimeout(timer);
      wake(); // done settles (aborted) now, not at the next poll
      if (id !== null) cancelOnServer();
    },
  };
}

// Starts (or joins) the open of a series and follows it (followJob). done resolves with the finished open
// ({dataset, fromCache, ...}); its failures carry 401, 404, 502, 504 or 507.
export function followSeriesOpen(service, studyUid, seriesUid, onProgress) {
  return followJob(() => json(
    `${servicePath(service)}/studies/${encodeURIComponent(studyUid)}/series/${encodeURIComponent(seriesUid)}/open`,
    postJson, 'Opening the series'), 'api/pacs/opens', 'Opening the series', onProgress);
}

// Sends a slab sweep of the view to the PACS (POST /api/pacs/{service}/store) and follows it (followJob).
// body: {dataset, cam, mode, thickness, step, size, renderer, eps, window}. done resolves with the finished
// store ({stored, description}); its failures carry 400, 401, 404, 409, 502 or 504. A cancelled send
// stores nothing.
export function sendSweep(service, body, onProgress) {
  return followJob(() => json(`${servicePath(service)}/store`,
    { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) },
    'Sending to the PACS'), 'api/pacs/stores', 'Sending to the PACS', onProgress);
}
