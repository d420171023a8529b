// One pairing for the CLI and the page (pair_by_id, chart/reference.hpp): on patch files whose
// order differs from the reference file's (the held-out one spelling its ids "A05" against the
// reference's "A5"), the page's fit (web/fit/handlers.js, its sample built from the file's rows)
// and held-out set (web/lib/pairs.js heldOutSet) list the patches in the order of
// `tristim fit --rgb --xyz` and `tristim evaluate --rgb --xyz` on the same files — the RGB file's
// order — with the same per-patch CSV, training digest and held-out errors; reference patches the
// held-out file lacks are named on both sides, an id the reference lacks is PATCH_MISMATCH on both.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { spawnSync } from 'node:child_process';
import { loadTristim, repoRoot } from './load.mjs';
import { handlers as fitHandlers } from '../../web/fit/handlers.js';
import { handlers as referenceHandlers } from '../../web/reference/handlers.js';
import { handlers as exportHandlers } from '../../web/export/handlers.js';
import { heldOutSet } from '../../web/lib/pairs.js';

const CLI = path.join(repoRoot, 'build/native/core/tristim');
const handlers = { ...fitHandlers, ...referenceHandlers, ...exportHandlers };

/// `head` then one row per index of `order`: the id (as `spell` writes it) and three values of `m`.
const table = (head, ids, m, order, spell = (id) => id) =>
  [head, ...order.map((i) => [spell(ids[i]), m[3 * i], m[3 * i + 1], m[3 * i + 2]].join(','))].join('\n') + '\n';
const twoDigits = (id) => id.replace(/^([A-Z])(\d)$/, '$10$2');
const close = (a, b, what) => Array.from(a).forEach((v, i) => assert.ok(Math.abs(v - b[i]) <= 1e-9 * Math.max(1, Math.abs(b[i])), `${what}[${i}]: ${v} vs ${b[i]} (tolerance 1e-9)`));

function tristim(args) {
  const r = spawnSync(CLI, args, { encoding: 'utf8' });
  return { code: r.status, out: r.stdout, err: r.stderr };
}

test('the page pairs patch files in the order tristim fit/evaluate --rgb --xyz do: the RGB file\'s', async () => {
  const T = await loadTristim();
  const engine = { call: async (name, payload) => handlers[name](T, payload, { progress: () => {}, state: {} }).result };
  const ref = T.referenceChart('cc24', 'D50', '1931');
  const train = T.simulateCamera('Canon_EOS_5D_Mark_II', 'cc24', 'D50', {});
  const held = T.simulateCamera('Nikon_D850', 'cc24', 'D50', { noise_sigma: 0.002, seed: 3 });
  const n = ref.ids.length;
  const trainOrder = Array.from({ length: n }, (_, i) => (7 * i + 5) % n);    // a permutation of 24
  const cut = ['A1', 'B3', 'D6'];   // the held-out chart cut by the frame: no RGB for these
  const heldOrder = Array.from({ length: n }, (_, i) => (11 * i + 2) % n).filter((i) => !cut.includes(ref.ids[i]));
  assert.notDeepEqual(trainOrder, [...trainOrder].sort((a, b) => a - b));
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-pairing-'));
  try {
    const file = (name, text) => { fs.writeFileSync(path.join(dir, name), text); return { name, text, path: path.join(dir, name) }; };
    const refFile = file('ref.csv', table('patch,X,Y,Z', ref.ids, ref.XYZ, ref.ids.map((_, i) => i)));
    const trainFile = file('train.csv', table('patch,R,G,B', train.ids, train.RGB, trainOrder));
    const heldFile = file('held.csv', table('patch,R,G,B', held.ids, held.RGB, heldOrder, twoDigits));
    const expectTrain = trainOrder.map((i) => ref.ids[i]), expectHeld = heldOrder.map((i) => ref.ids[i]);

    // The CLI: fit on train.csv, evaluate on held.csv, both against ref.csv.
    const fit = tristim(['fit', '--rgb', trainFile.path, '--xyz', refFile.path, '--model', 'matrix-3x3', '--out', path.join(dir, 'p.json'),
      '--csv', path.join(dir, 'patches.csv')]);
    assert.equal(fit.code, 0, fit.err);
    const profile = JSON.parse(fs.readFileSync(path.join(dir, 'p.json'), 'utf8'));
    assert.deepEqual(profile.training.labels, expectTrain);   // the RGB file's order
    const ev = tristim(['evaluate', '--profile', path.join(dir, 'p.json'), '--rgb', heldFile.path, '--xyz', refFile.path]);
    assert.equal(ev.code, 0, ev.err);
    assert.equal(ev.err, 'tristim evaluate: 3 reference patches have no RGB (A1, B3, D6): evaluated on the 21 others\n');
    const cliHeld = JSON.parse(ev.out).metrics.patches;
    assert.deepEqual(cliHeld.ids, heldOrder.map((i) => twoDigits(held.ids[i])));

    // The page: step 1's reference file, a sample of train.csv's rows, the fit step's held-out file.
    const reference = await engine.call('parseReference', { text: refFile.text, fileName: refFile.name, illuminant: 'D50', observer: '1931' });
    const parsed = await engine.call('parsePatchFile', { text: trainFile.text, fileName: trainFile.name });
    const patches = parsed.ids.map((id, i) => ({ id, mean: Array.from(parsed.RGB.subarray(3 * i, 3 * i + 3)) }));
    const heldOut = await heldOutSet(engine, heldFile, reference);
    assert.deepEqual(heldOut.ids, expectHeld);
    assert.deepEqual(heldOut.withoutRGB, cut);   // what the CLI names on stderr
    const { source, settings, data_digest, ...chart } = reference;
    const { format, version, ...recipe } = profile.recipe;   // the CLI's recipe, as the page holds one
    const page = await engine.call('fit', { recipe, sample: { patches }, reference: chart, heldOut });
    assert.deepEqual(Array.from(page.ids), expectTrain);
    assert.deepEqual(Array.from(page.ids), profile.training.labels.map((l) => T.normalisePatchId(l)));
    assert.equal(JSON.parse(page.profile).training.digest, profile.training.digest);     // the same rows in the same order
    // The page's per-patch CSV (web/export/view.js) is the one `tristim fit --csv` writes.
    const e = page.evaluation;
    const { text } = await engine.call('patchCsv', { ids: page.labels, rgb: page.linear_RGB, xyz: page.reference_XYZ, estimated: e.fit.fitted,
      white: page.recipe.characterisation.lab_white, loo: e.loo_XYZ ?? [] });
    assert.equal(text, fs.readFileSync(path.join(dir, 'patches.csv'), 'utf8'));
    close(page.held_out.patches.dE00, cliHeld.dE00, 'held-out dE00');
    close(page.held_out.patches.rel_Y, cliHeld.rel_Y, 'held-out rel_Y');

    // An id the reference lacks: PATCH_MISMATCH on both sides.
    const stray = file('stray.csv', `${heldFile.text}Z9,0.1,0.2,0.3\n`);
    await assert.rejects(heldOutSet(engine, stray, reference), { code: 'PATCH_MISMATCH' });
    const bad = tristim(['evaluate', '--profile', path.join(dir, 'p.json'), '--rgb', stray.path, '--xyz', refFile.path]);
    assert.notEqual(bad.code, 0);
    assert.match(bad.err, /PATCH_MISMATCH/);
  } finally {
    fs.rmSync(dir, { recursive: true, force: true });
  }
});
