// Token roles in the viewer (web/js/role.js): from one token file of both roles, a viewer's token greys
// the operator controls (the eps slider that starts fits, the PACS send) and an operator's does not. The
// page shows a dataset named as one retrieved from a PACS (the small brain MRI under the name
// orthanc-<series>, with a PACS configured that is never asked), so that its Send section is live.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import crypto from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';
import { withPage } from './support/browser.mjs';
import { CAN_START_OWN_SERVER, OWN_SERVER_NEEDS, ownServerFolder, startOwnServer } from './support/own-server.mjs';
import { ViewerPage } from './pages/ViewerPage.mjs';

const OPERATOR_CONTROLS = ['eps-slider', 'pacs-send-button'];
const ROLE_TITLE = "Needs an operator's token";
const PACS_DATASET = 'orthanc-1_2_826_0_1_3680043_10_1234_207';
const DATA = process.env.VOTS_DATA;

let server = null;
const tokens = { viewer: crypto.randomBytes(16).toString('hex'), operator: crypto.randomBytes(16).toString('hex') };

before(async () => {
  if (!CAN_START_OWN_SERVER) return;
  const dir = ownServerFolder();
  fs.writeFileSync(path.join(dir, 'tokens'), `reader viewer ${tokens.viewer}\nradiographer operator ${tokens.operator}\n`);
  const brain = path.join(DATA, 'mri-brain_33x41x25_int16.nrrd');
  fs.mkdirSync(path.join(dir, 'pacs'));
  fs.symlinkSync(fs.realpathSync(brain), path.join(dir, 'pacs', `${PACS_DATASET}.nrrd`));
  server = await startOwnServer(dir, ['--token-file', path.join(dir, 'tokens'), '--data', path.join(dir, 'pacs'),
    '--dicomweb', 'orthanc=dicomweb+http://127.0.0.1:9/dicom-web']);
});

after(() => server?.stop());

// The page opened with the role's token, once it shows a frame: its data-role and each control's state.
async function controlsFor(t, role) {
  let seen = null;
  await withPage(t, async (page) => {
    const viewer = new ViewerPage(page);
    await page.goto(`${server.url}/#dataset=${PACS_DATASET}&token=${tokens[role]}`);
    await viewer.waitForIdle();
    await page.getByTestId('pacs-send-button').waitFor({ state: 'visible' });
    const frame = await viewer.framePixels();
    assert.ok(frame.variance > 20, `frame looks blank: luminance variance ${frame.variance.toFixed(2)}`);
    seen = await page.evaluate((ids) => ({
      role: document.body.dataset.role,
      controls: Object.fromEntries(ids.map((id) => {
        const control = document.querySelector(`[data-testid="${id}"]`);
        return [id, { disabled: control.disabled, title: control.title }];
      })),
    }), OPERATOR_CONTROLS);
  });
  return seen;
}

test("a viewer's token greys the operator controls", async (t) => {
  assert.ok(server, OWN_SERVER_NEEDS);
  const seen = await controlsFor(t, 'viewer');
  assert.equal(seen.role, 'viewer');
  for (const id of OPERATOR_CONTROLS) {
    assert.equal(seen.controls[id].disabled, true, `${id} is not greyed: ${JSON.stringify(seen.controls[id])}`);
    assert.equal(seen.controls[id].title, ROLE_TITLE, `${id} does not say why`);
  }
});

test("an operator's token leaves them usable", async (t) => {
  assert.ok(server, OWN_SERVER_NEEDS);
  const seen = await controlsFor(t, 'operator');
  assert.equal(seen.role, 'operator');
  for (const id of OPERATOR_CONTROLS) {
    assert.equal(seen.controls[id].disabled, false, `${id} is greyed: ${JSON.stringify(seen.controls[id])}`);
    assert.notEqual(seen.controls[id].title, ROLE_TITLE);
  }
});
