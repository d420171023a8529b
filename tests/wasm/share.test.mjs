// Share links both ways between the native CLI and the module (issue 44): a table of recipes —
// every model × objective, each linearisation and each surface correction once, and an absolute
// recipe — each fitted on the Passport DNG; the link the CLI makes (tristim share) reproduces in
// the module (reproduceLink), and the link the module makes (shareSample, as the page's Share
// button) reproduces with the CLI (tristim reproduce: exit 0, "reproduced"). Damaged links give
// their codes in the module. Leave-one-out only on the least-squares rows (the iterative
// objectives refit once per patch): the table stays well under a minute.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import zlib from 'node:zlib';
import { createHash } from 'node:crypto';
import { execFileSync, spawnSync } from 'node:child_process';
import { loadTristim, readBytes, testPath, repoRoot, throwsCode } from './load.mjs';

const T = await loadTristim();
const cli = path.join(repoRoot, 'build/native/core/tristim');
const dng = testPath('examples/web/passport.dng');
const base = JSON.parse(fs.readFileSync(path.join(repoRoot, 'examples/recipes/passport-rootpoly2-psm.json'), 'utf8'));
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-share-'));
const run = (args) => spawnSync(cli, args, { encoding: 'utf8', maxBuffer: 16 << 20 });

/// The chart sample of the recipe's corners as the page hands it to the engine (the declared
/// ChartSample fields only: sampleChart's reply carries conveniences besides).
function chartSample(raw) {
  const { layout, homography, patches } = T.sampleChart(raw, { chart: base.sampling.layout.chart }, base.sampling.corners, { area: base.sampling.area });
  return { layout, homography, patches };
}

/// The table: [label, recipe].
function table() {
  const rows = [];
  const recipe = (edit) => {
    const r = structuredClone(base);
    r.characterisation.white_patch = 'D1';   // corrected-3x3 needs a white; every row keeps it
    edit(r);
    return r;
  };
  for (const m of T.listModels())
    for (const o of T.listObjectives())
      rows.push([`${m.id} ${o.id}`, recipe((r) => {
        r.characterisation.model = m.id;
        r.characterisation.objective = { method: o.id, parameters: {}, settings: {} };
        r.evaluation.leave_one_out = o.id === 'ls';
      })]);
  const ls = (r) => { r.characterisation.model = 'Finlayson2015-2'; r.characterisation.objective = { method: 'ls', parameters: {}, settings: {} }; };
  for (const l of T.listLinearisations()) if (l.id !== 'identity')
    rows.push([`linearisation ${l.id}`, recipe((r) => { ls(r); r.linearisation = { method: l.id, parameters: {}, settings: {} }; })]);
  for (const s of T.listSurfaceCorrections()) if (s.id !== 'none')
    rows.push([`surface ${s.id}`, recipe((r) => { ls(r); r.surface = { method: s.id, parameters: {}, settings: {} }; })]);
  return rows;
}

test('links made natively reproduce in the module, and links made by the module with the CLI', () => {
  if (!fs.existsSync(cli)) throw new Error(`${cli} not found: build the native tree first (bash scripts/build.sh)`);
  const raw = T.decodeRaw(readBytes('examples/web/passport.dng'));
  const sample = chartSample(raw);
  raw.delete();
  const sources = [{ name: 'passport.dng', sha256: T.sha256(readBytes('examples/web/passport.dng')) }];
  const refused = [];
  let n = 0;
  for (const [label, recipe] of table()) {
    const file = path.join(dir, 'recipe.json'), profile = path.join(dir, 'profile.json');
    fs.writeFileSync(file, JSON.stringify(recipe));
    const fit = run(['fit', '--recipe', file, '--raw', dng, '--out', profile]);
    if (fit.status !== 0) {
      // A row the engine refuses (e.g. a linearisation that needs stored values) must be refused
      // by the module too, with the same code.
      const code = /error ([A-Z_]+):/.exec(fit.stderr)?.[1];
      assert.ok(code, `${label}: the CLI failed without a code: ${fit.stderr}`);
      throwsCode(assert, () => T.shareSample(JSON.stringify(recipe), sample, T.recipeReference(JSON.stringify(recipe)), sources), code);
      refused.push(`${label} (${code})`);
      continue;
    }
    // native -> module
    const payload = execFileSync(cli, ['share', '--profile', profile, '--raw', dng, '--payload']).toString().trim();
    const r = T.reproduceLink(payload);
    assert.equal(r.verdict, 'reproduced', `${label}: ${JSON.stringify(r.differences)}`);
    assert.equal(r.actual.digest, r.expected.digest);
    // module -> native
    const made = T.shareSample(JSON.stringify(recipe), sample, T.recipeReference(JSON.stringify(recipe)), sources);
    assert.equal(made, payload, `${label}: the module and the CLI make the same payload`);
    const back = run(['reproduce', made, '--json']);
    assert.equal(back.status, 0, `${label}: ${back.stdout} ${back.stderr}`);
    assert.equal(JSON.parse(back.stdout).verdict, 'reproduced');
    n++;
  }
  assert.ok(n >= 75, `${n} rows reproduced both ways (refused: ${refused.join(', ')})`);
  console.log(`# ${n} links reproduced both ways; refused by both builds alike: ${refused.join(', ') || 'none'}`);
});

test('an absolute recipe of per-patch stimuli: its link reproduces both ways', () => {
  const ex = T.absoluteExample({});
  for (const f of [...ex.frames, ...ex.lens_cap, ex.flat]) f.delete();
  const stimuli = path.join(dir, 'stimuli.csv'), profile = path.join(dir, 'absolute.json');
  fs.writeFileSync(stimuli, ex.stimuli_csv);
  execFileSync(cli, ['absolute', 'fit', '--stimuli', stimuli, '--saturation', '15000', '--noise-floor', '8', '--out', profile], { stdio: 'pipe' });
  const payload = execFileSync(cli, ['share', '--profile', profile, '--payload']).toString().trim();
  const r = T.reproduceLink(payload);
  assert.equal(r.kind, 'absolute');
  assert.equal(r.verdict, 'reproduced', JSON.stringify(r.differences));
  const recipe = JSON.parse(fs.readFileSync(profile, 'utf8')).recipe;
  const made = T.shareAbsolute(JSON.stringify(recipe));
  assert.equal(made, payload);
  const back = run(['reproduce', made]);
  assert.equal(back.status, 0, back.stderr);
  assert.match(back.stdout, /^reproduced/);
});

test('damaged links: each its code in the module; the CLI exits 2 with the same code', () => {
  const raw = T.decodeRaw(readBytes('examples/web/passport.dng'));
  const sample = chartSample(raw);
  raw.delete();
  const payload = T.shareSample(JSON.stringify(base), sample, T.recipeReference(JSON.stringify(base)), []);
  const link = T.shareLink('http://127.0.0.1:8080/', payload);
  const mid = payload.indexOf('.') + 40;
  const tampered = payload.slice(0, mid) + (payload[mid] === 'A' ? 'B' : 'A') + payload.slice(mid + 1);
  // 64 MiB of '[' deflated (~64 KB): refused while inflating, at 1 MiB, before any check.
  const bomb = `1.${zlib.deflateRawSync(Buffer.alloc(64 << 20, '[')).toString('base64url')}.AAAAAAAAAAAAAAAA`;
  const cases = [
    ['tampered', tampered, 'PARSE_ERROR'],
    ['truncated', link.slice(0, link.length - 30), 'PARSE_ERROR'],
    ['future version', '3' + payload.slice(1), 'PROFILE_VERSION'],
    ['not a link', 'https://example.org/#tristim=hello', 'PARSE_ERROR'],
    ['bomb', bomb, 'LIMIT_EXCEEDED'],
  ];
  for (const [what, text, code] of cases) {
    throwsCode(assert, () => T.reproduceLink(text), code);
    const r = run(['reproduce', text]);
    assert.equal(r.status, 2, `${what}: exit ${r.status}`);
    assert.match(r.stderr, new RegExp(`error ${code}:`), what);
  }
  // A RAW that is not the link's source is refused before anything is sampled.
  throwsCode(assert, () => T.reproduceLinkImage(T.shareSample(JSON.stringify(base), sample, T.recipeReference(JSON.stringify(base)), [{ name: 'x.dng', sha256: '0'.repeat(64) }]),
    readBytes('examples/web/passport.dng')), 'PATCH_MISMATCH');
});

test('version 2 is written; a version 1 link (made before it) is still read, in the module and with the CLI', () => {
  const v1 = fs.readFileSync(path.join(repoRoot, 'tests/fuzz/corpus/share_payload/passport-link.txt'), 'utf8').slice(1);
  assert.match(v1, /#tristim=1\./);
  const r = T.reproduceLink(v1);
  assert.equal(r.verdict, 'reproduced', JSON.stringify(r.differences));
  // Its payload written again is version 2, shorter, and reads to the same document.
  const v2 = execFileSync(cli, ['share', '--profile', writeProfile(r.profile), '--raw', dng, '--payload']).toString().trim();
  assert.match(v2, /^2\./);
  assert.ok(v2.length + 400 < v1.length, `${v2.length} against ${v1.length}`);
  assert.equal(T.reproduceLink(v2).verdict, 'reproduced');
  assert.equal(run(['reproduce', v1]).status, 0);
  // The data are checked by their SHA-256 and inflate with the documented dictionary (docs/link-format.md).
  const [, text, check] = v2.split('.');
  const data = Buffer.from(text, 'base64url');
  assert.equal(createHash('sha256').update(data).digest().subarray(0, 12).toString('base64url'), check);
  const content = zlib.inflateRawSync(data, { dictionary: Buffer.from(T.shareLinkDictionary(), 'latin1') });
  assert.ok(JSON.parse(content.subarray(0, content.indexOf(0)).toString()).results.length > 10);
});

/// A profile JSON text in a file of the test's directory: its path.
function writeProfile(text) {
  const file = path.join(dir, 'v1-profile.json');
  fs.writeFileSync(file, text);
  return file;
}

test.after(() => fs.rmSync(dir, { recursive: true, force: true }));
