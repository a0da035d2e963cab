// The PACS panel's words for what the PACS answers: person names, dates and an open's progress line.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadWebModules } from './support/web-modules.mjs';

const { 'study-browser.js': browser } = await loadWebModules(['study-browser.js']);

test('a DICOM person name reads family, given; other groups and a missing name are dropped', () => {
  assert.equal(browser.personName('Doe^John'), 'Doe, John');
  assert.equal(browser.personName('Doe^John^^Dr=ドウ^ジョン'), 'Doe, John');
  assert.equal(browser.personName('Phantom'), 'Phantom');
  assert.equal(browser.personName(''), '');
  assert.equal(browser.personName(undefined), '');
});

test('a typed patient name is searched as a prefix unless it holds a wildcard', () => {
  assert.equal(browser.namePattern('doe'), 'doe*');
  assert.equal(browser.namePattern(' Doe^J '), 'Doe^J*');
  assert.equal(browser.namePattern('D?e'), 'D?e');
  assert.equal(browser.namePattern('*oe'), '*oe');
  assert.equal(browser.namePattern(''), '');
});

test('a DICOM date reads YYYY-MM-DD; anything else is shown as it came', () => {
  assert.equal(browser.studyDate('20240131'), '2024-01-31');
  assert.equal(browser.studyDate('2024'), '2024');
  assert.equal(browser.studyDate(''), '');
});

test('an open\'s progress line counts images while retrieving and says when the kept copy was used', () => {
  assert.equal(browser.openProgressText({ state: 'announcing', received: 0, total: 0 }), 'Asking the PACS…');
  assert.equal(browser.openProgressText({ state: 'retrieving', received: 12, total: 108 }),
    'Retrieving 12 / 108 images');
  assert.equal(browser.openProgressText({ state: 'loading', received: 108, total: 108 }), 'Loading 108 / 108 images');
  assert.equal(browser.openProgressText({ state: 'done', received: 108, total: 108, fromCache: false }), 'Opened');
  assert.equal(browser.openProgressText({ state: 'done', received: 108, total: 108, fromCache: true }),
    'Opened (kept from an earlier retrieve)');
});
