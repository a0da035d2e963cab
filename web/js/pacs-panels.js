// The PACS panels' wiring: the study browser and the send form, found by their element ids and tied together.
import { createPacsSend } from './pacs-send.js';
import { createStudyBrowser } from './study-browser.js';

const $ = (id) => document.getElementById(id);

// The send form draws with the viewer's parameters and slab; a series the browser opened goes to onOpened; the
// services the browser learns are the form's targets.
export function attachPacsPanels({ viewParams, slab, onOpened }) {
  const pacsSend = createPacsSend({
    el: {
      root: $('pacs-send'),
      what: $('pacs-send-what'),
      thickness: $('pacs-send-thickness'),
      step: $('pacs-send-step'),
      note: $('pacs-send-note'),
      send: $('pacs-send-button'),
      cancel: $('pacs-send-cancel'),
      progressBox: $('pacs-send-progress-box'),
      progress: $('pacs-send-progress'),
      label: $('pacs-send-progress-label'),
      result: $('pacs-send-result'),
      error: $('pacs-send-error'),
    },
    viewParams,
    slab,
  });

  const studyBrowser = createStudyBrowser({
    el: {
      root: $('pacs'),
      form: $('pacs-form'),
      serviceRow: $('pacs-service-row'),
      service: $('pacs-service'),
      patientName: $('pacs-patient-name'),
      patientId: $('pacs-patient-id'),
      dateFrom: $('pacs-date-from'),
      dateTo: $('pacs-date-to'),
      modality: $('pacs-modality'),
      accession: $('pacs-accession'),
      studies: $('pacs-studies'),
      studiesNote: $('pacs-studies-note'),
      seriesBox: $('pacs-series-box'),
      series: $('pacs-series'),
      progressBox: $('pacs-progress-box'),
      progress: $('pacs-progress'),
      progressLabel: $('pacs-progress-label'),
      cancel: $('pacs-cancel'),
      error: $('pacs-error'),
    },
    onOpened,
    onServices: (names) => pacsSend.setServices(names),
  });
  return { pacsSend, studyBrowser };
}
