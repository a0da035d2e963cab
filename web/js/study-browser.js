// The PACS panel: a study search form, the studies found, a study's series, and opening one with progress.
import { fetchPacsServices, fetchStudySeries, followSeriesOpen, searchStudies } from './pacs-api.js';

const STATE_LABELS = {
  queued: 'Waiting',
  announcing: 'Asking the PACS',
  retrieving: 'Retrieving',
  loading: 'Loading',
  done: 'Opened',
};

// "Doe^John" as DICOM writes a person's name: "Doe, John".
export function personName(pn) {
  const [family = '', given = ''] = String(pn || '').split('=')[0].split('^');
  return given ? `${family}, ${given}` : family;
}

// What the panel asks for a typed name: a prefix ("doe" finds "Doe^John") unless it holds a wildcard.
export function namePattern(typed) {
  const t = String(typed || '').trim();
  return !t || /[*?]/.test(t) ? t : `${t}*`;
}

// "20240131" -> "2024-01-31"; anything else as it is.
export function studyDate(da) {
  const d = String(da || '');
  return /^\d{8}$/.test(d) ? `${d.slice(0, 4)}-${d.slice(4, 6)}-${d.slice(6)}` : d;
}

// The progress line of an open: "Retrieving 12 / 108 images", "Opened (kept from an earlier retrieve)".
export function openProgressText(open) {
  const label = STATE_LABELS[open.state] || open.state;
  if (open.state === 'done') return open.fromCache ? `${label} (kept from an earlier retrieve)` : label;
  if (open.total > 0 && open.state !== 'announcing') return `${label} ${open.received} / ${open.total} images`;
  return `${label}…`;
}

// An element with text content only: what the PACS says is never read as markup.
function node(tag, text, className) {
  const e = document.createElement(tag);
  if (text !== undefined) e.textContent = text;
  if (className) e.className = className;
  return e;
}

// el: the panel's elements (see index.html, #pacs). onOpened(datasetName) runs once a series is a dataset;
// onServices(names) once the server has named its PACS.
export function createStudyBrowser({ el, onOpened, onServices = () => {} }) {
  let following = null; // the open being followed: {cancel()}
  let searchToken = 0; // answers of a superseded search or series listing are dropped

  const service = () => el.service.value;

  function showError(message) {
    el.error.textContent = message;
    el.error.hidden = !message;
  }

  function selectRow(list, row) {
    for (const r of list.children) r.setAttribute('aria-selected', String(r === row));
  }

  function showStudies(studies) {
    el.studies.replaceChildren(...studies.map((s) => {
      const row = node('li', undefined, 'pacs-row');
      row.dataset.studyUid = s.studyUid;
      row.tabIndex = 0;
      row.setAttribute('role', 'option');
      row.append(
        node('span', personName(s.patientName) || '(no name)', 'pacs-title'),
        node('span', [s.patientId, studyDate(s.studyDate), (s.modalities || []).join('/')].filter(Boolean).join(' · '),
          'pacs-detail'),
        node('span', [s.description, s.accessionNumber && `acc. ${s.accessionNumber}`,
          `${s.seriesCount} series, ${s.instanceCount} images`].filter(Boolean).join(' · '), 'pacs-detail'),
      );
      const pick = () => {
        selectRow(el.studies, row);
        listSeries(s.studyUid);
      };
      row.addEventListener('click', pick);
      row.addEventListener('keydown', (e) => { if (e.key === 'Enter') pick(); });
      return row;
    }));
    el.studiesNote.textContent = studies.length ? `${studies.length} studies` : 'No study matches.';
  }

  function showSeries(studyUid, series) {
    el.series.replaceChildren(...series.map((s) => {
      const row = node('li', undefined, 'pacs-row');
      row.dataset.seriesUid = s.seriesUid;
      const open = node('button', 'Open', 'pacs-open');
      open.type = 'button';
      open.title = `Retrieve series ${s.seriesUid} and show it`;
      open.addEventListener('click', () => {
        selectRow(el.series, row);
        openSeries(studyUid, s.seriesUid);
      });
      row.append(
        node('span', `${s.seriesNumber ? `#${s.seriesNumber} ` : ''}${s.description || '(no description)'}`,
          'pacs-title'),
        node('span', `${s.modality || '?'} · ${s.instanceCount} images`, 'pacs-detail'),
        open,
      );
      return row;
    }));
    el.seriesBox.hidden = false;
  }

  async function search(event) {
    event.preventDefault();
    const mine = ++searchToken;
    showError('');
    el.seriesBox.hidden = true;
    el.studiesNote.textContent = 'Searching…';
    try {
      const studies = await searchStudies(service(), {
        patientName: namePattern(el.patientName.value),
        patientId: el.patientId.value.trim(),
        dateFrom: el.dateFrom.value,
        dateTo: el.dateTo.value,
        modality: el.modality.value.trim().toUpperCase(),
        accessionNumber: el.accession.value.trim(),
      });
      if (mine === searchToken) showStudies(studies);
    } catch (e) {
      if (mine !== searchToken) return;
      el.studiesNote.textContent = '';
      el.studies.replaceChildren();
      showError(e.message);
    }
  }

  async function listSeries(studyUid) {
    const mine = ++searchToken;
    showError('');
    try {
      const series = await fetchStudySeries(service(), studyUid);
      if (mine === searchToken) showSeries(studyUid, series);
    } catch (e) {
      if (mine === searchToken) showError(e.message);
    }
  }

  function showProgress(open) {
    el.progressBox.hidden = false;
    el.progress.max = Math.max(1, open.total);
    el.progress.value = open.state === 'done' ? el.progress.max : open.received;
    el.progressLabel.textContent = openProgressText(open);
  }

  async function openSeries(studyUid, seriesUid) {
    if (following) following.cancel();
    showError('');
    el.cancel.hidden = false;
    showProgress({ state: 'queued', received: 0, total: 0 });
    const mine = followSeriesOpen(service(), studyUid, seriesUid, (open) => {
      if (following === mine) showProgress(open);
    });
    following = mine;
    try {
      const open = await mine.done;
      if (following !== mine) return;
      onOpened(open.dataset);
    } catch (e) {
      if (following !== mine) return;
      el.progressBox.hidden = true;
      if (!e.isIgnorable) showError(e.message);
    } finally {
      if (following === mine) {
        following = null;
        el.cancel.hidden = true;
      }
    }
  }

  el.form.addEventListener('submit', search);
  el.cancel.addEventListener('click', () => {
    if (!following) return;
    following.cancel();
    following = null;
    el.cancel.hidden = true;
    el.progressLabel.textContent = 'Cancelled';
  });

  return {
    // Shows the panel when the server names a PACS; a server without one leaves it hidden.
    async start() {
      let services;
      try {
        services = await fetchPacsServices();
      } catch (e) {
        el.root.hidden = false;
        showError(e.message);
        return;
      }
      onServices(services.map((s) => s.name));
      if (!services.length) return;
      el.service.replaceChildren(...services.map((s) => {
        const option = new Option(s.name, s.name);
        option.title = s.url;
        return option;
      }));
      el.serviceRow.hidden = services.length < 2;
      el.root.hidden = false;
    },
  };
}
