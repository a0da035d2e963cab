// The Send to PACS section's rules without a browser: which datasets came from a PACS, the progress words,
// and which views a sweep can be drawn from.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadWebModules } from './support/web-modules.mjs';

const { 'pacs-send.js': send } = await loadWebModules(['pacs-send.js']);

test('a dataset came from the PACS whose name, a dash and a series UID with _ for . it carries', () => {
  const services = ['orthanc', 'pacs-b'];
  assert.equal(send.pacsServiceOf('orthanc-1_2_826_0_1_3680043_10_1234_207', services), 'orthanc');
  assert.equal(send.pacsServiceOf('pacs-b-1_2_3', services), 'pacs-b');
  assert.equal(send.pacsServiceOf('orthanc-head', services), null);
  assert.equal(send.pacsServiceOf('cranium', services), null);
  assert.equal(send.pacsServiceOf('other-1_2_3', services), null);
  assert.equal(send.pacsServiceOf(undefined, services), null);
});

test('a send\'s progress reads slabs drawn, then storing, then what was stored', () => {
  assert.equal(send.sendProgressText({ state: 'queued', drawn: 0, total: 12 }), 'Waiting…');
  assert.equal(send.sendProgressText({ state: 'drawing', drawn: 3, total: 12 }), 'Drawing 3 / 12 slabs');
  assert.equal(send.sendProgressText({ state: 'storing', drawn: 12, total: 12 }), 'Storing 12 images');
  assert.equal(send.sendProgressText({ state: 'done', stored: 12, total: 12, description: 'MIP 10 mm / 5 mm axial' }),
    'Stored 12 images: MIP 10 mm / 5 mm axial');
});

test('a sweep is drawn from MIP, MinIP or AIP with the orthographic projection only', () => {
  const ortho = 'az=0,el=0,zoom=1,pan=0:0,proj=ortho,fov=30';
  assert.equal(send.sweepRefusal({ mode: 'mip', cam: ortho }), '');
  assert.equal(send.sweepRefusal({ mode: 'aip', cam: ortho }), '');
  assert.match(send.sweepRefusal({ mode: 'density', cam: ortho }), /MIP, MinIP or AIP/);
  assert.match(send.sweepRefusal({ mode: 'mip', cam: ortho.replace('ortho', 'persp') }), /orthographic/);
});
