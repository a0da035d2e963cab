// Loads the viewer's DOM-free modules (web/js) under node for unit specs.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const WEB_JS = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..', '..', 'web', 'js');

// web/ is served as it is and has no package.json, so node would read its .js files as CommonJS:
// load a copy that sits next to one saying they are ES modules. Returns {name: module} for the names.
export async function loadWebModules(names) {
  const copy = fs.mkdtempSync(path.join(os.tmpdir(), 'vots-web-js-'));
  try {
    fs.cpSync(WEB_JS, copy, { recursive: true });
    fs.writeFileSync(path.join(copy, 'package.json'), '{"type": "module"}\n');
    const out = {};
    for (const name of names) out[name] = await import(pathToFileURL(path.join(copy, name)).href);
    return out;
  } finally {
    fs.rmSync(copy, { recursive: true, force: true });
  }
}
