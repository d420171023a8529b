// The lab's charts of one's own through the wasm module: a Munsell selection (labRender's chart
// "munsell:…") and uploaded reflectances (labRenderReflectances of readReflectanceFile) give the
// native CLI's DNG and truth byte for byte, and the custom layout samples the DNG back to 1e-6.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { loadTristim, throwsCode, repoRoot } from './load.mjs';

const nativeCli = path.join(repoRoot, 'build/native/core/tristim');

/// The native CLI's file and truth for `args` (lab render …, --out added).
function cli(args) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-lab-grid-'));
  try {
    const file = path.join(dir, 'chart.dng');
    const truth = execFileSync(nativeCli, ['lab', 'render', ...args, '--out', file], { cwd: dir }).toString();
    return { truth, dng: fs.readFileSync(file) };
  } finally { fs.rmSync(dir, { recursive: true, force: true }); }
}

function sampledBack(T, dng, truth) {
  const raw = T.decodeRaw(dng);
  try {
    const s = T.sampleChart(raw, { chart: 'custom', rows: truth.layout.rows, columns: truth.layout.columns }, truth.corners);
    let worst = 0;
    truth.patches.forEach((p, k) => {
      assert.equal(s.patches[k].id, p.cell);
      [0, 1, 2].forEach((c) => { worst = Math.max(worst, Math.abs(s.patches[k].mean[c] - p.rgb[c])); });
    });
    return worst;
  } finally { raw.delete(); }
}

test('lab render munsell:…: the page\'s DNG and truth are the CLI\'s, sampled back with the custom layout to 1e-6', async () => {
  assert.ok(fs.existsSync(nativeCli), `${nativeCli} not found: scripts/build.sh builds it`);
  const T = await loadTristim();
  const chart = 'munsell:5R4/14,10YR6/10,2.5G';
  const out = T.labRender({ camera: 'Nikon_D850', chart, illuminant: 'D50', illuminant_spd: T.illuminantSpectrum('D50'), exposure: 0.6 }, 'dng');
  const native = cli(['--camera', 'Nikon_D850', '--chart', chart, '--illuminant', 'D50', '--exposure', '0.6']);
  assert.equal(out.truth + '\n', native.truth);
  assert.ok(Buffer.from(out.dng).equals(native.dng), 'DNG bytes differ from the CLI\'s');
  const truth = JSON.parse(out.truth);
  assert.equal(truth.patches[0].id, '5R4/14');
  assert.ok(sampledBack(T, out.dng, truth) <= 1e-6);
  throwsCode(assert, () => T.labRender({ chart: 'munsell:5R4/99', illuminant_spd: T.illuminantSpectrum('D65') }, 'dng'), 'UNKNOWN_ID');
});

test('lab render with uploaded reflectances: the page\'s truth is the CLI\'s --reflectances, sampled back to 1e-6', async () => {
  const T = await loadTristim();
  const wl = Array.from({ length: 41 }, (_, i) => 380 + 10 * i);
  const rows = Array.from({ length: 7 }, (_, i) => [`S${i + 1}`, ...wl.map((w) => (0.1 + 0.4 * (1 + Math.sin(w / 35 + i))).toFixed(5))]);
  const text = [['id', ...wl].join(','), ...rows.map((r) => r.join(','))].join('\n') + '\n';
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-lab-grid-'));
  try {
    fs.writeFileSync(path.join(dir, 'mine.csv'), text);
    const native = cli(['--camera', 'Canon_EOS_5D_Mark_II', '--reflectances', path.join(dir, 'mine.csv'), '--illuminant', 'A']);
    const out = T.labRenderReflectances({ camera: 'Canon_EOS_5D_Mark_II', chart: path.join(dir, 'mine.csv'), illuminant: 'A',
      illuminant_spd: T.illuminantSpectrum('A') }, T.readReflectanceFile(text, 'mine.csv'), 'dng');
    assert.equal(out.truth + '\n', native.truth);
    const truth = JSON.parse(out.truth);
    assert.deepEqual(truth.patches.map((p) => p.id), [...rows.map((r) => r[0]), 'R2C4']);  // the empty cell: the board
    assert.deepEqual(truth.patches.map((p) => p.board === true), [false, false, false, false, false, false, false, true]);
    assert.deepEqual([truth.layout.rows, truth.layout.columns], [2, 4]);
    assert.ok(sampledBack(T, out.dng, truth) <= 1e-6);
  } finally { fs.rmSync(dir, { recursive: true, force: true }); }
});
