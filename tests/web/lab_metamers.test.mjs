// Journey: the Lab's metamerism explorer (issue 45). A metamer of a Munsell chip constructed for
// the observer under D65 (ΔE00 0 there, large under F11), with a camera's figures beside; the
// search over the Munsell set; both as the native CLI prints them; the plot of both spectra; a bad
// option gives a coded error next to the button. No console errors.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { screenshot } from './harness.mjs';
import { pageTest, step, errorNear, markCounts, CLI } from './journey.mjs';

const S = '#step-lab';
const cli = (...a) => JSON.parse(execFileSync(CLI, ['lab', 'metamers', ...a, '--json']).toString());
const cells = (page) => page.$$eval(`${S} table[data-lab="met-pairs"] tbody tr`, (trs) => trs.map((tr) => [...tr.children].map((c) => c.textContent)));

pageTest('lab metamers: construct a metamer, search the Munsell pairs, plot both spectra', { timeout: 120000 }, async ({ page }) => {
  await step(page, 'lab');
  await page.click(`${S} [data-tab="metamers"]`);
  const panel = `${S} section[aria-labelledby="h-lab-metamers"]`;
  const sel = (name) => `${panel} select[data-lab="met-${name}"]`;
  await page.waitForFunction((s) => document.querySelector(s)?.options.length === 1269, sel('chip'), { timeout: 60000 });
  await page.selectOption(sel('ill2'), 'F11');
  await page.selectOption(sel('camera'), 'Nikon_D850');
  await page.selectOption(sel('chip'), '5PB4/10');
  await page.click(`${panel} [data-action="lab-met-construct"]`);
  await page.waitForSelector(`${panel} table[data-lab="met-pairs"] tbody tr`, { timeout: 60000 });
  assert.equal(await page.textContent(`${panel} [data-lab="met-cli"]`),
    'tristim lab metamers --illuminant D65 --second F11 --observer 1931 --camera Nikon_D850 --construct 5PB4/10 --json');
  const want = cli('--illuminant', 'D65', '--second', 'F11', '--camera', 'Nikon_D850', '--construct', '5PB4/10');
  const row = (await cells(page))[0];
  assert.deepEqual(row.slice(0, 2), ['5PB4/10', '5PB4/10 + black']);
  const figures = want.pairs[0].views.flatMap((v) => [v.dE00_1, v.dE00_2]).map((x) => x.toFixed(2));
  assert.deepEqual(row.slice(2), figures);
  assert.equal(row[2], '0.00');
  assert.ok(Number(row[3]) > 1, `under F11 ${row[3]}`);
  assert.equal(await page.$$eval(`${panel} [data-lab="met-dE"] li`, (li) => li.length), 2);
  assert.ok((await markCounts(page, 'lab-metamers')).line >= 2);
  await screenshot(page, 'lab-metamers-construct');

  // The search: the pairs within ΔE00 0.5 under D65, ranked under A, as the CLI lists them.
  await page.selectOption(sel('ill2'), 'A');
  await page.selectOption(sel('camera'), '');
  await page.click(`${panel} [data-action="lab-met-search"]`);
  await page.waitForFunction((p) => document.querySelector(`${p} [data-lab="met-cli"]`)?.textContent.includes('--max-match'), panel);
  await page.waitForFunction((p) => document.querySelectorAll(`${p} table[data-lab="met-pairs"] thead th`).length === 4, panel);
  const found = cli('--illuminant', 'D65', '--second', 'A', '--max-match', '0.5', '--top', '10');
  const rows = await cells(page);
  assert.deepEqual(rows.map((r) => r.slice(0, 2)), found.pairs.map((p) => [p.a, p.b]));
  assert.match(await page.textContent(`${panel} [data-lab="met-summary"]`), new RegExp(`^${found.matching} pairs`));
  await page.click(`${panel} table[data-lab="met-pairs"] tbody tr:nth-child(2) button`);
  await page.waitForFunction((p) => document.querySelector(`${p} figure[data-plot="lab-metamers"] figcaption`)?.textContent.includes(
    document.querySelector(`${p} table[data-lab="met-pairs"] tbody tr:nth-child(2) td`).textContent), panel);
  await screenshot(page, 'lab-metamers-search');

  // A bad option: a coded error next to the button, the page usable.
  await page.fill(`${panel} input[data-lab="met-max"]`, '0');
  await page.click(`${panel} [data-action="lab-met-search"]`);
  assert.equal((await errorNear(page, `${panel} [data-action="lab-met-search"]`)).code, 'INVALID_ARGUMENT');
});
