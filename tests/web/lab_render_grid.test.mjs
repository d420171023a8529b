// Journey: the Lab's chart of one's own (issue 45). An uploaded SPD shows as the illuminant
// picker's choice ("uploaded: <file>") and leaves it when a listed light is picked again; Munsell
// chips picked from the engine's list, and uploaded reflectances, become the chart picker's choice
// and are rendered as a generated grid whose truth lists them in order, as the CLI renders them.
import assert from 'node:assert/strict';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { screenshot, repoRoot } from './harness.mjs';
import { pageTest, step, upload, CLI } from './journey.mjs';

const S = '#step-lab';
const shown = (page, sel) => page.locator(`${S} ${sel}`).evaluate((s) => s.selectedOptions[0]?.textContent);

pageTest('lab render: an uploaded SPD is the illuminant picker\'s choice; Munsell chips and uploaded reflectances are the chart\'s', async ({ page }) => {
  const spdFile = 'tests/data/colour-science/illuminant_ampas_iso7589_studio_tungsten_380-780_5nm.csv';
  await step(page, 'lab');
  const illum = 'select >> nth=2', chart = 'select >> nth=1';
  await page.selectOption(`${S} select >> nth=0`, 'Nikon_D850');
  await page.setInputFiles(`${S} input[data-lab="spd"]`, path.join(repoRoot, spdFile));
  await page.waitForFunction(() => [...document.querySelectorAll('#step-lab select')][2].selectedOptions[0]?.textContent.startsWith('uploaded:'));
  assert.equal(await shown(page, illum), `uploaded: ${path.basename(spdFile)}`);
  // A listed light again: the upload is dropped from the picker and from the render.
  await page.selectOption(`${S} ${illum}`, 'D50');
  assert.equal(await page.$$eval(`${S} option[data-lab="extra"]`, (o) => o.length), 0);
  assert.equal(await page.$eval(`${S} input[data-lab="spd"]`, (i) => i.files.length), 0);

  // Munsell chips from the engine's list.
  await page.focus(`${S} select[data-lab="munsell-chips"]`);
  await page.waitForFunction((s) => document.querySelector(s).options.length === 1269, `${S} select[data-lab="munsell-chips"]`);
  const chips = ['5R4/14', '10YR6/10', '5G5/8', '5PB4/10'];  // in the engine's order, as the picker lists them
  await page.selectOption(`${S} select[data-lab="munsell-chips"]`, chips);
  assert.equal(await shown(page, chart), 'Munsell: 4 chips');
  await page.click(`${S} [data-action="lab-render"]`);
  await page.waitForFunction(() => window.tristim.derived.labTruth?.layout, null, { timeout: 60000 });
  let truth = await page.evaluate(() => window.tristim.derived.labTruth);
  assert.deepEqual(truth.patches.filter((p) => !p.board).map((p) => p.id), chips);  // then the grid's empty cells: the board
  assert.deepEqual([truth.layout.rows, truth.layout.columns], [2, 3]);  // columns ⌈√(1.5·4)⌉
  const line = await page.textContent(`${S} [data-lab="render-cli"]`);
  assert.match(line, /--chart "munsell:5R4\/14,10YR6\/10,5G5\/8,5PB4\/10" --illuminant D50/);
  const native = JSON.parse(execFileSync(CLI, ['lab', 'render', '--camera', 'Nikon_D850', '--chart', `munsell:${chips.join(',')}`, '--illuminant', 'D50',
    '--out', path.join(os.tmpdir(), `lab-grid-web-${process.pid}.dng`)]).toString());
  assert.deepEqual(truth.patches.map((p) => p.rgb), native.patches.map((p) => p.rgb));
  assert.match(await page.textContent(`${S} [data-lab="summary"]`), /--chart custom --rows 2 --columns 3 --corners/);
  await screenshot(page, 'lab-render-munsell');

  // Reflectances of one's own: the chart picker names the file; the chips are deselected.
  const wl = Array.from({ length: 41 }, (_, i) => 380 + 10 * i);
  const csv = [['id', ...wl].join(','), ...[1, 2, 3, 4, 5].map((i) => [`M${i}`, ...wl.map((w) => (0.2 + 0.3 * (1 + Math.cos(w / 30 + i))).toFixed(4))].join(','))].join('\n');
  await upload(page, `${S} input[data-lab="reflectances"]`, 'mine.csv', Buffer.from(csv));
  await page.waitForFunction(() => [...document.querySelectorAll('#step-lab select')][1].selectedOptions[0]?.textContent === 'uploaded: mine.csv');
  assert.equal(await page.$eval(`${S} select[data-lab="munsell-chips"]`, (s) => s.selectedOptions.length), 0);
  await page.click(`${S} [data-action="lab-render"]`);
  await page.waitForFunction(() => window.tristim.derived.labTruth?.chart === 'mine.csv', null, { timeout: 60000 });
  truth = await page.evaluate(() => window.tristim.derived.labTruth);
  assert.deepEqual(truth.patches.filter((p) => !p.board).map((p) => p.id), ['M1', 'M2', 'M3', 'M4', 'M5']);
  assert.match(await page.textContent(`${S} [data-lab="render-cli"]`), /--reflectances mine\.csv --illuminant D50/);
  // A listed chart again: the upload leaves the picker.
  await page.selectOption(`${S} ${chart}`, 'cc24');
  assert.equal(await page.$$eval(`${S} option[data-lab="extra"]`, (o) => o.length), 0);
});
