// Journey: the Lab mode (issue 45). A ColorChecker rendered by the engine from measured spectra
// (a camera of the 52, D50) shows its truth; one click hands the DNG to the Images step, which
// decodes, detects and samples it back to the truth (noise off: exact); the reference follows
// the chart and illuminant. Camera quality: the ranking of the 52 and the curves against the
// best-fit CMF combination. Bad options show a coded error next to the input. No console errors.
import test from 'node:test';
import assert from 'node:assert/strict';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { screenshot, repoRoot } from './harness.mjs';
import { openPage, step, errorNear, markCounts, CLI } from './journey.mjs';

const S = '#step-lab';

test('lab: render a chart, open it in the journey (sampled = truth), rank the cameras, plot one against the CMFs', async () => {
  const b = await openPage();
  try {
    const { page } = b;
    await step(page, 'lab');
    await page.selectOption(`${S} select >> nth=0`, 'Nikon_D850');
    await page.selectOption(`${S} select >> nth=1`, 'cc24');
    await page.selectOption(`${S} select >> nth=2`, 'D50');
    await page.fill(`${S} input[data-lab="exposure"]`, '0.6');
    await page.click(`${S} [data-action="lab-render"]`);
    await page.waitForSelector(`${S} table[data-lab="truth"]`, { timeout: 60000 });
    assert.equal(await page.$$eval(`${S} table[data-lab="truth"] tbody tr`, (r) => r.length), 24);
    assert.match(await page.textContent(`${S} [data-lab="render-cli"]`), /^tristim lab render --camera Nikon_D850 --chart cc24 --illuminant D50 --exposure 0\.6 --out chart\.dng$/);
    await screenshot(page, 'lab-render');

    // One click: the Images step decodes, detects and samples the rendered DNG.
    await page.click(`${S} [data-action="lab-open"]`);
    await page.waitForSelector('#step-images:not([hidden])');
    // The sample of the rendered image (not the example's): the image's size, corners near the truth's.
    await page.waitForFunction(() => {
      const t = window.tristim.derived.labTruth, s = window.tristim.derived.sample;
      return s?.patches?.length === 24 && window.tristim.derived.image?.width === t.width
        && s.corners.every((v, i) => Math.abs(v - t.corners[i]) < 1);
    }, null, { timeout: 60000 });
    const { sample, rows } = await page.evaluate(() => ({
      sample: window.tristim.derived.sample.patches.map((p) => ({ id: p.id, mean: Array.from(p.mean) })),
      rows: [...document.querySelectorAll('#step-lab table[data-lab="truth"] tbody tr')].map((tr) => [...tr.children].map((c) => c.textContent)),
    }));
    let worst = { e: 0 };
    sample.forEach((p, k) => {
      assert.equal(p.id, rows[k][0]);
      [0, 1, 2].forEach((c) => {
        const e = Math.abs(p.mean[c] - Number(rows[k][1 + c]));
        if (e > worst.e) worst = { e, at: `${p.id} ${'RGB'[c]}: sampled ${p.mean[c]}, truth ${rows[k][1 + c]}` };
      });
    });
    assert.ok(worst.e <= 1e-6, worst.at);
    const ref = await page.evaluate(() => ({ ...window.tristim.session.settings }));
    assert.equal(ref.chart, 'cc24');
    assert.equal(ref.illuminant, 'D50');

    // Camera quality: the 52 ranked, best SMI first; one camera against the CMFs.
    await step(page, 'lab');
    await page.click(`${S} [data-tab="quality"]`);
    await page.click(`${S} [data-action="lab-rank"]`);
    await page.waitForSelector(`${S} table[data-lab="ranking"]`, { timeout: 60000 });
    const ranking = await page.$$eval(`${S} table[data-lab="ranking"] tbody tr`, (trs) => trs.map((tr) => Number(tr.children[2].textContent)));
    assert.equal(ranking.length, 52);
    assert.ok(ranking.every((v, i) => i === 0 || v <= ranking[i - 1]), 'sorted by SMI');
    await page.click(`${S} table[data-lab="ranking"] tbody tr:nth-child(3) button`);
    await page.waitForSelector(`${S} figure[data-plot^="luther-"]`);
    const counts = await markCounts(page, await page.$eval(`${S} figure[data-plot^="luther-"]`, (f) => f.dataset.plot));
    assert.ok(counts.line >= 6, `camera and fitted curves: ${JSON.stringify(counts)}`);
    await screenshot(page, 'lab-quality');

    // Exercise 1: a patch under three lights and two observers, with its stimulus plot.
    await page.click(`${S} [data-tab="ex1"]`);
    await page.click(`${S} [data-action="lab-ex1"]`);
    await page.waitForSelector(`${S} table[data-lab="ex1-table"]`);
    assert.equal(await page.$$eval(`${S} table[data-lab="ex1-table"] tbody tr`, (r) => r.length), 6);
    assert.match(await page.textContent(`${S} section[aria-labelledby="h-lab-ex1"] pre.cli`), /tristim reference --chart cc24 --illuminant D65/);
    assert.ok((await markCounts(page, 'lab-ex1-C3')).line >= 4);
    // Exercise 2: the 35-term polynomial refused on 24 patches, over-fitting in leave-one-out.
    await page.click(`${S} [data-tab="ex2"]`);
    await page.click(`${S} [data-action="lab-ex2"]`);
    await page.waitForSelector(`${S} table[data-lab="ex2-table"]`, { timeout: 60000 });
    const ex2 = await page.$$eval(`${S} table[data-lab="ex2-table"] tbody tr`, (trs) => trs.map((tr) => [...tr.children].map((c) => c.textContent)));
    assert.equal(ex2.length, 10);
    const r22 = ex2.find((r) => r[0] === 'Cheung2004-22' && r[1] === 'cc24'), r3 = ex2.find((r) => r[0] === 'matrix-3x3' && r[1] === 'cc24');
    assert.ok(Number(r22[5]) > 2 * Number(r3[5]), `leave-one-out: 22 terms ${r22[5]}, 3x3 ${r3[5]}`);
    assert.match(ex2.find((r) => r[0] === 'Cheung2004-35' && r[1] === 'cc24')[4], /TOO_FEW_PATCHES/);
    await screenshot(page, 'lab-exercise2');

    // A bad option: a coded error next to the input, the page usable.
    await page.click(`${S} [data-tab="render"]`);
    await page.fill(`${S} input[data-lab="exposure"]`, '9');
    await page.click(`${S} [data-action="lab-render"]`);
    const err = await errorNear(page, `${S} [data-action="lab-render"]`);
    assert.equal(err.code, 'INVALID_ARGUMENT');
    assert.deepEqual(b.problems, []);
  } finally { await b.close(); }
});

test('lab: a JPEG through the sRGB OECF under an uploaded SPD, opened in the journey: sampled = stored within 1.5 DN, as the CLI renders it', async () => {
  const b = await openPage();
  try {
    const { page } = b;
    const spdFile = 'tests/data/colour-science/illuminant_ampas_iso7589_studio_tungsten_380-780_5nm.csv';
    await step(page, 'lab');
    await page.selectOption(`${S} select >> nth=0`, 'Nikon_D850');
    await page.setInputFiles(`${S} input[data-lab="spd"]`, path.join(repoRoot, spdFile));
    await page.selectOption(`${S} select[data-lab="format"]`, 'jpeg');
    await page.waitForFunction((s) => [...document.querySelector(s).options].some((o) => o.value === 'sRGB'), `${S} select[data-lab="oecf"]`);
    await page.selectOption(`${S} select[data-lab="oecf"]`, 'sRGB');
    await page.click(`${S} [data-action="lab-render"]`);
    await page.waitForFunction(() => window.tristim.derived.labTruth?.jpeg_quality === 95, null, { timeout: 60000 });
    const truth = await page.evaluate(() => window.tristim.derived.labTruth);
    assert.equal(truth.illuminant, path.basename(spdFile));
    assert.match(await page.textContent(`${S} [data-lab="render-cli"]`), /--oecf sRGB --out chart\.jpg$/);
    const cli = JSON.parse(execFileSync(CLI, ['lab', 'render', '--camera', 'Nikon_D850', '--chart', 'cc24', '--illuminant', path.join(repoRoot, spdFile),
      '--oecf', 'sRGB', '--out', path.join(os.tmpdir(), `lab-web-${process.pid}.jpg`)]).toString());
    assert.deepEqual(truth.patches.map((p) => p.stored), cli.patches.map((p) => p.stored));
    await screenshot(page, 'lab-render-jpeg');
    await page.click(`${S} [data-action="lab-open"]`);
    // The JPEG's sample (8-bit values), not the one of the image shown before it.
    await page.waitForFunction(() => { const s = window.tristim.derived.sample; return s?.patches?.length === 24
      && window.tristim.derived.image?.width === 900 && s.patches.every((p) => Math.max(...p.mean) <= 255); }, null, { timeout: 60000 });
    const sample = await page.evaluate(() => window.tristim.derived.sample.patches.map((p) => Array.from(p.mean)));
    let worst = { e: 0 };
    sample.forEach((m, k) => m.forEach((v, c) => {
      const e = Math.abs(v - truth.patches[k].stored[c]);
      if (e > worst.e) worst = { e, at: `${truth.patches[k].id} ${'RGB'[c]}: sampled ${v}, stored ${truth.patches[k].stored[c]}` };
    }));
    assert.ok(worst.e <= 1.5, `tolerance 1.5 DN (JPEG quality 95): ${worst.at}`);
    assert.deepEqual(b.problems, []);
  } finally { await b.close(); }
});
