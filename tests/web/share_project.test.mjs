// Project files in the page (issue 44): the session exported as one .tristim file is read by the
// CLI (tristim reproduce: reproduced, from its chart RAW sampled again) and, imported into a fresh
// browser, restores the page exactly: the same results, selection, corners and settings.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { spawnSync } from 'node:child_process';
import { repoRoot, screenshot } from './harness.mjs';
import { openPage, step, waitReady } from './journey.mjs';

const state = (page) => page.evaluate(() => {
  const s = window.tristim.session;
  return {
    selected: s.selected,
    results: (s.results ?? []).map((r) => [r.key, r.fit.evaluation.training.dE00.mean]),
    corners: Array.from(s.corners ?? []),
    settings: s.settings,
    chart: s['files.chart'] ? [s['files.chart'].name, s['files.chart'].bytes.byteLength] : null,
  };
});

test('a project file exported by the page reproduces with the CLI and restores the session in a fresh browser', async () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-project-'));
  const file = path.join(dir, 'session.tristim');
  let before;
  const a = await openPage();
  try {
    const { page } = a;
    // Not the fresh session's choice: another result shown instead of the best one.
    await page.evaluate(() => { const s = window.tristim.session; return window.tristim.save('selected', s.results.find((r) => r.key !== s.selected).key); });
    await step(page, 'share');
    const [download] = await Promise.all([page.waitForEvent('download', { timeout: 120000 }), page.click('#share-export')]);
    await download.saveAs(file);
    before = await state(page);
    assert.ok(before.results.length > 0 && before.chart, 'the example session has results and its RAW');
    assert.deepEqual(a.problems, []);
  } finally { await a.close(); }

  const cli = spawnSync(path.join(repoRoot, 'build/native/core/tristim'), ['reproduce', file], { encoding: 'utf8' });
  assert.equal(cli.status, 0, cli.stderr + cli.stdout);
  assert.match(cli.stdout, /^reproduced .*sampled again/);

  const b = await openPage();
  try {
    const { page } = b;
    assert.notEqual((await state(page)).selected, before.selected, 'a fresh session selects another result');
    await step(page, 'share');
    page.on('dialog', (d) => d.accept());   // "Replace this session with the project's?"
    await Promise.all([page.waitForNavigation({ timeout: 120000 }), page.setInputFiles('#share-import', file)]);
    await waitReady(page, 120000);
    const after = await state(page);
    assert.deepEqual(after, before);
    await screenshot(page, 'share-project-imported');
    assert.deepEqual(b.problems, []);
  } finally {
    await b.close();
    fs.rmSync(dir, { recursive: true, force: true });
  }
});
