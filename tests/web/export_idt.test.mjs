// The Export step's ACES Input Transform (issue 46): a built-in camera under D55 (and Bradford),
// downloaded as CLF and as the plain 3×3, byte-identical to `tristim idt --camera … --illuminant …
// --out … --matrix …`, read back by the engine's CLF reader and summarised; from an uploaded
// sensitivities CSV (= `--sensitivities`) and from the chart's patches too; a broken CLF loaded back shows a coded error and the page stays usable.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { screenshot, repoRoot } from './harness.mjs';
import { step, pageTest, CLI, artifact } from './journey.mjs';

pageTest('export step: ACES IDT as CLF and 3×3, byte-identical to `tristim idt`, read back and summarised', { problems: false }, async ({ page }) => {
  await step(page, 'export');
  const camera = 'Canon_EOS_5D_Mark_II';
  for (const adaptation of ['CAT02', 'Bradford']) {
    await page.selectOption('#idt-source', 'camera');
    await page.selectOption('#idt-camera', camera);
    await page.selectOption('#idt-illuminant', 'D55');
    await page.selectOption('#idt-adaptation', adaptation);
    assert.match(await page.textContent('#step-export .idt-command'), new RegExp(`tristim idt --camera "${camera}" --illuminant D55 --adaptation ${adaptation}`));
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#step-export button[data-export="IDT (CLF)"]')]);
    assert.equal(dl.suggestedFilename(), `tristim-idt-${camera}-D55-${adaptation}.clf`);
    const clf = fs.readFileSync(await dl.path());
    const [dlm] = await Promise.all([page.waitForEvent('download'), page.click('#step-export button[data-export="IDT 3×3 matrix"]')]);
    const matrix = fs.readFileSync(await dlm.path());
    // The CLI writes the same bytes.
    const cliClf = artifact(`export-idt-${adaptation}.clf`), cliMatrix = artifact(`export-idt-${adaptation}.txt`);
    execFileSync(CLI, ['idt', '--camera', camera, '--illuminant', 'D55', '--adaptation', adaptation, '--out', cliClf, '--matrix', cliMatrix]);
    assert.ok(clf.equals(fs.readFileSync(cliClf)), `page CLF = CLI CLF (${adaptation}), byte for byte`);
    assert.ok(matrix.equals(fs.readFileSync(cliMatrix)), `page 3×3 = CLI 3×3 (${adaptation}), byte for byte`);
    // The engine's reader on the download: recipe, matrix, the camera white -> ACES.
    await page.waitForFunction((a) => new RegExp(`Adaptation ${a}`).test(document.querySelector('#step-export .idt-summary')?.textContent ?? ''), adaptation, { timeout: 30000 });
    const summary = await page.textContent('#step-export .idt-summary');
    assert.ok(summary.includes(`Camera ${camera}`), summary);
    assert.match(summary, /Illuminant D55/);
    assert.match(summary, /ACES2065-1/);
    assert.match(summary, /Matrix (-?\d+\.\d{4} ?){3}( \/ (-?\d+\.\d{4} ?){3}){2}/);
    assert.match(summary, /fit on 190 samples: ΔE\*ab mean \d+\.\d\d/);
    assert.match(summary, new RegExp(`${clf.length} bytes`));
  }
  await screenshot(page, 'export-idt');

  // Uploaded sensitivities (colour-science's Canon 5D Mk II): the CLI's --sensitivities file.
  const ssf = path.join(repoRoot, 'tests/data/colour-science/camera_canon_eos_5d_mark_ii_rawtoaces_v1_scitech_380-780_5nm.csv');
  await page.selectOption('#idt-source', 'sensitivities');
  await page.selectOption('#idt-adaptation', 'CAT02');
  const [chooser] = await Promise.all([page.waitForEvent('filechooser'), page.click('#idt-ssf')]);
  await chooser.setFiles(ssf);
  await page.waitForFunction(() => /--sensitivities camera_canon/.test(document.querySelector('#step-export .idt-command')?.textContent ?? ''), null, { timeout: 30000 });
  const [dls] = await Promise.all([page.waitForEvent('download'), page.click('#step-export button[data-export="IDT (CLF)"]')]);
  assert.equal(dls.suggestedFilename(), 'tristim-idt-camera_canon_eos_5d_mark_ii_rawtoaces_v1_scitech_380-780_5nm-D55-CAT02.clf');
  const cliSsf = artifact('export-idt-ssf.clf');
  execFileSync(CLI, ['idt', '--sensitivities', ssf, '--illuminant', 'D55', '--out', cliSsf]);
  assert.ok(fs.readFileSync(await dls.path()).equals(fs.readFileSync(cliSsf)), 'page CLF = CLI CLF (--sensitivities), byte for byte');
  await page.waitForFunction(() => /Sensitivities camera_canon/.test(document.querySelector('#step-export .idt-summary')?.textContent ?? ''), null, { timeout: 30000 });

  // From the chart's patches (the example's fit): a CLF the engine reads back.
  await page.selectOption('#idt-source', 'chart');
  assert.equal(await page.isDisabled('#idt-camera'), true);
  const [dlc] = await Promise.all([page.waitForEvent('download'), page.click('#step-export button[data-export="IDT (CLF)"]')]);
  assert.equal(dlc.suggestedFilename(), 'tristim-idt-chart-CAT02.clf');
  const chartClf = fs.readFileSync(await dlc.path(), 'utf8');
  assert.match(chartClf, /<CameraRGB>[^<]+<\/CameraRGB>/);
  await page.waitForFunction(() => /CameraRGB/.test(document.querySelector('#step-export .idt-summary')?.textContent ?? ''), null, { timeout: 30000 });

  // A broken CLF loaded back: a coded error beside the input, and the page keeps working.
  const broken = artifact('export-idt-broken.clf');
  fs.writeFileSync(broken, chartClf.replace('</Matrix>', '</Matrx>'));
  await page.setInputFiles('#step-export input[type=file]', broken);
  await page.waitForFunction(() => /PARSE_ERROR|Matrix/.test(document.querySelector('#step-export .field-error:not([hidden])')?.textContent ?? ''), null, { timeout: 30000 });
  const good = artifact('export-idt-CAT02.clf');
  await page.setInputFiles('#step-export input[type=file]', good);
  await page.waitForFunction(() => /CLF “tristim IDT/.test(document.querySelector('#step-export .import-result')?.textContent ?? ''), null, { timeout: 30000 });
});
