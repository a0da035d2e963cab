// A `vots serve` of a spec's own (a token file, HTTPS, ...) on a free loopback port over run.sh's data,
// with a folder for its files; stop() ends it and removes the folder.
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const WEB = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..', '..', 'web');
const BIN = process.env.VOTS_BIN; // set by run.sh when it started the server itself
const DATA = process.env.VOTS_DATA;
// Whether a spec can start a server of its own: run.sh starts its server from a binary and data it names.
export const CAN_START_OWN_SERVER = Boolean(BIN && DATA);
export const OWN_SERVER_NEEDS = 'needs VOTS_BIN and VOTS_DATA: run.sh sets them when it starts the server, not with VOTS_URL';

// A fresh folder for the server's files (tokens, certificates), made before the server starts.
export function ownServerFolder() {
  return fs.mkdtempSync(path.join(os.tmpdir(), 'vots-web-own-'));
}

// Starts the server with `args` beyond the data, web and cache ones; resolves once it listens.
export async function startOwnServer(dir, args) {
  const child = spawn(BIN, ['serve', '--port', '0', '--data', DATA, '--web', WEB, '--cache-dir', path.join(dir, 'cache'),
    '--prepare', '', '--no-warm-up', ...args], { stdio: ['ignore', 'pipe', 'pipe'] });
  let output = '';
  const url = await new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`no listening line within 60 s:\n${output}`)), 60000);
    const read = (chunk) => {
      output += chunk;
      const m = output.match(/listening on (https?:\/\/\S+?)\/\n/);
      if (m && output.includes('renderer')) {
        clearTimeout(timer);
        resolve(m[1]);
      }
    };
    child.stdout.on('data', read);
    child.stderr.on('data', read);
    child.on('exit', (code) => reject(new Error(`vots serve exited (${code}):\n${output}`)));
  });
  return {
    url,
    output: () => output,
    stop() {
      child.kill('SIGTERM');
      fs.rmSync(dir, { recursive: true, force: true });
    },
  };
}
