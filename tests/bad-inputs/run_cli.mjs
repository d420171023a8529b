// The bad-input catalogue through the native CLI (ctest native:bad-inputs): each case's bytes are
// written to a temporary folder under the case's file name and given to the command a user would
// run with such a file; the code in "tristim <command>: error <CODE>: ..." must be the expected one.
//   node tests/bad-inputs/run_cli.mjs <path to tristim> [case id substring]
//   raw       tristim detect <file>        (decodes the whole image; a decodable image without a
//                                           chart answers CHART_NOT_FOUND)
//   reference tristim fit --rgb <good camera RGB> --xyz <file> --model matrix-3x3 --no-loo
//   patches   tristim fit --rgb <file> --xyz <good reference> --model matrix-3x3 --no-loo
//   profile   tristim evaluate --profile <file> --rgb <good> --xyz <good>
//   recipe    tristim fit --recipe <file> --rgb <good> --xyz <good>
//   corners   tristim sample <Passport DNG> --chart passport --corners <corners>
//   dcp       tristim inspect <file>       (a DNG camera profile, read strictly)
//   link      tristim reproduce <file>     (a file holding a share link; docs/link-format.md)
//   project   tristim reproduce <file>     (a .tristim project file)
//   clf       tristim inspect <file.clf>   (a Common LUT Format file, read strictly)
//   cube, icc tristim inspect <file.cube|.icc>  (a 3D LUT's or an ICC profile's header, by its name)
//   share     tristim share --profile <file> --payload   (a profile whose training block is fitted again)
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { spawnSync } from 'node:child_process';
import { materialise, expected, readBase } from './inputs.mjs';

const [cli, only = ''] = process.argv.slice(2);
if (!cli || !fs.existsSync(cli)) {
  console.error('usage: node tests/bad-inputs/run_cli.mjs <path to tristim> [case id substring]');
  process.exit(2);
}
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-bad-inputs-'));
// A good pair for the commands that need one: the Lab reference of the page's fixtures and
// camera RGB made from it (any positive numbers pair by id; the fit is not what is tested).
const labCsv = new TextDecoder().decode(readBase('tests/web/fixtures/cc24_Lab_D50.csv'));
const rows = labCsv.trim().split('\n').slice(1).map((l) => l.split(','));
const goodRef = path.join(dir, 'good-ref.csv');
fs.writeFileSync(goodRef, labCsv);
const goodRgb = path.join(dir, 'good-rgb.csv');
fs.writeFileSync(goodRgb, 'patch,R,G,B\n' + rows.map(([id, L, a, b]) => {
  const l = Number(L);
  return `${id},${(l * 9 + Number(a) * 3 + 40).toFixed(3)},${(l * 10 + 30).toFixed(3)},${(l * 8 - Number(b) * 3 + 60).toFixed(3)}`;
}).join('\n') + '\n');

function command(c, file) {
  switch (c.kind) {
    case 'raw': return ['detect', file];
    case 'reference': return ['fit', '--rgb', goodRgb, '--xyz', file, '--model', 'matrix-3x3', '--no-loo'];
    case 'patches': return ['fit', '--rgb', file, '--xyz', goodRef, '--model', 'matrix-3x3', '--no-loo'];
    case 'profile': return ['evaluate', '--profile', file, '--rgb', goodRgb, '--xyz', goodRef];
    case 'recipe': return ['fit', '--recipe', file, '--rgb', goodRgb, '--xyz', goodRef];
    case 'corners': return ['sample', file, '--chart', 'passport', '--corners', c.corners.join(',')];
    case 'dcp': return ['inspect', file];
    case 'link': return ['reproduce', file];      // a file holding the link (exit 2 with the code)
    case 'project': return ['reproduce', file];
    case 'clf': return ['inspect', file];
    case 'cube': case 'icc': return ['inspect', file];
    case 'share': return ['share', '--profile', file, '--payload'];
    default: throw new Error(`${c.id}: unknown kind ${c.kind}`);
  }
}

let failed = 0, n = 0;
const t0 = Date.now();
for (const c of materialise((c) => c.id.includes(only), 'cli')) {
  const file = path.join(dir, `${c.id}-${c.name}`);
  fs.writeFileSync(file, c.bytes);
  const t = Date.now();
  const r = spawnSync(cli, command(c, file), { encoding: 'utf8', timeout: 60000, maxBuffer: 64 << 20 });
  const m = /error ([A-Z_]+):/.exec(r.stderr ?? '');
  const got = r.status === 0 ? 'OK' : m ? m[1] : `exit ${r.status ?? r.signal} without a code: ${(r.stderr ?? '').slice(0, 200)}`;
  const want = expected(c, 'cli');
  const ms = Date.now() - t;
  n++;
  if (got !== want) {
    failed++;
    console.log(`FAIL ${c.id}: expected ${want}, got ${got} (${ms} ms) ${(r.stderr ?? '').trim().slice(0, 300)}`);
  } else console.log(`ok   ${c.id}: ${got} (${ms} ms)`);
  fs.rmSync(file);
}
fs.rmSync(dir, { recursive: true, force: true });
console.log(`${n} cases, ${failed} failed, ${((Date.now() - t0) / 1000).toFixed(1)} s`);
process.exit(failed ? 1 : 0);
