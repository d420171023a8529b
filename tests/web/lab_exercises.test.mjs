// Journey: the Lab's exercises 3-5 (issue 45) — Shen 2008's J and L sweeps, Abed 2013 Table IV and
// Guarnera 2018's exposure invariance and Table 4 — each run in the page with its plots, its
// results table beside the paper's figures and a CSV download (the engine's CSV: header with
// units); an exercise's set-up as a #lab= link, opened in a fresh browser, sets and runs it; a bad
// link is a coded error shown as text (never as HTML). No console errors.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { openBrowser, screenshot } from './harness.mjs';
import { openPage, step, waitReady } from './journey.mjs';

const S = '#step-lab';

async function csvOf(page, action) {
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click(`${S} [data-action="${action}"]`)]);
  return { name: dl.suggestedFilename(), text: fs.readFileSync(await dl.path(), 'utf8') };
}
/// Opens the tab of exercise `ex`, runs it, and waits for its table `table` (data-lab="<table>-table").
async function runExercise(page, ex, table, timeout = 60000) {
  await page.click(`${S} [data-tab="${ex}"]`);
  await page.click(`${S} [data-action="lab-${ex}"]`);
  await page.waitForSelector(`${S} table[data-lab="${table}-table"]`, { timeout });
}
const rowsOf = (page, key) => page.$$eval(`${S} table[data-lab="${key}-table"] tbody tr`, (trs) => trs.map((tr) => [...tr.children].map((c) => c.textContent)));

test('lab exercises 3-5: tables beside the papers, CSV downloads, a set-up link opened in a fresh browser', async () => {
  const b = await openPage();
  let link;
  try {
    const { page } = b;
    await step(page, 'lab');
    // Exercise 3: Tables I-II (grey-based + L = 0..3) and the J sweep.
    await runExercise(page, 'ex3', 'ex3-L');
    const L = await rowsOf(page, 'ex3-L');
    assert.equal(L.length, 5);
    assert.deepEqual(L.map((r) => r[1]), ['grey-based', 'Shen2008', 'Shen2008', 'Shen2008', 'Shen2008']);
    for (const r of L.slice(1)) assert.ok(Number(r[5]) > 0.995, `R2 red ${r[5]}`);
    assert.equal((await rowsOf(page, 'ex3-J')).length, 44);
    assert.ok(await page.$(`${S} figure[data-plot="lab-ex3-J-colorimetric-cc24"] svg`));
    assert.match(await page.textContent(`${S} section[aria-labelledby="h-lab-ex3"] pre.cli`), /tristim lab shen --camera Canon_EOS_5D_Mark_II --chart cc24 --table L/);
    const csv3 = await csvOf(page, 'lab-csv-ex3-L');
    assert.equal(csv3.name, 'lab-shen-L.csv');
    assert.match(csv3.text, /^chart,method,J \(basis functions\),L \(iterations\),"noise sigma \(rho, 0-255\)",R2 red/);
    assert.equal(csv3.text.trim().split('\n').length, 6);
    await screenshot(page, 'lab-exercise3');

    // Exercise 4: Table IV, 6 training rows × 5 methods; the Classic disagreement is in the text.
    await runExercise(page, 'ex4', 'ex4');
    const t4 = await rowsOf(page, 'ex4');
    assert.equal(t4.length, 30);
    assert.deepEqual([...new Set(t4.map((r) => r[0]))], ['Classic', 'SG', 'Custom All', 'Custom-Matte', 'Custom-Glossy', 'Total']);
    const classic = Object.fromEntries(t4.filter((r) => r[0] === 'Classic').map((r) => [r[1], Number(r[5])]));
    assert.ok(classic['matrix-3x3'] < classic.saunderson && classic['matrix-3x3'] < classic['corrected-3x3'], JSON.stringify(classic));
    assert.match(await page.textContent(`${S} [data-lab="ex4"]`), /plain 3×3 is AHEAD of every corrected method/);
    const csv4 = await csvOf(page, 'lab-csv-ex4');
    assert.equal(csv4.text.trim().split('\n').length, 31);
    await screenshot(page, 'lab-exercise4');

    // Exercise 5 under A: exposure invariance (T2R flat in k, the polynomial not) and Table 4.
    await page.click(`${S} [data-tab="ex5"]`);
    await page.selectOption(`${S} section[aria-labelledby="h-lab-ex5"] select >> nth=1`, 'A');
    await page.click(`${S} [data-action="lab-ex5"]`);
    await page.waitForSelector(`${S} table[data-lab="ex5-table4-table"]`, { timeout: 90000 });
    const ex = await rowsOf(page, 'ex5-exposure');
    assert.equal(ex.length, 28);
    const t2r = ex.filter((r) => r[0] === 'Guarnera2018-T2R').map((r) => r[2]);
    assert.equal(new Set(t2r).size, 1, `T2R the same at every k: ${t2r}`);
    const g4 = await rowsOf(page, 'ex5-table4');
    assert.equal(g4.length, 6);
    assert.deepEqual(g4.map((r) => r[3]), ['single', 'weighted', 'recursive', 'single', 'weighted', 'recursive']);
    const csv5 = await csvOf(page, 'lab-csv-ex5-table4');
    assert.match(csv5.text, /^light,colour training,transform,shots,NRMSE X \(fraction of the range\)/);
    await screenshot(page, 'lab-exercise5');

    // The set-up as a link: exercise 3 on the SG with another camera.
    await page.click(`${S} [data-tab="ex3"]`);
    const ex3 = `${S} section[aria-labelledby="h-lab-ex3"]`;
    await page.selectOption(`${ex3} select >> nth=0`, 'Nikon_D850');
    await page.selectOption(`${ex3} select >> nth=1`, 'sg140');
    await page.click(`${S} [data-action="lab-link-ex3"]`);
    link = await page.inputValue(`${S} input[data-lab-link="ex3"]`);
    assert.match(link, /#lab=ex3&camera=Nikon_D850&chart=sg140$/);
    assert.deepEqual(b.problems, []);
  } finally { await b.close(); }

  // A fresh browser (no session) opens the link: the Lab, exercise 3, set and run.
  const c = await openBrowser();
  try {
    const { page } = c;
    await page.goto(c.origin + '/' + link.slice(link.indexOf('#')));
    await waitReady(page);
    await page.waitForSelector(`${S}:not([hidden]) table[data-lab="ex3-L-table"]`, { timeout: 60000 });
    const ex3 = `${S} section[aria-labelledby="h-lab-ex3"]`;
    assert.equal(await page.$$eval(`${ex3} select`, (s) => s[0].value), 'Nikon_D850');
    assert.equal(await page.$$eval(`${ex3} select`, (s) => s[1].value), 'sg140');
    assert.match(await page.textContent(`${ex3} pre.cli`), /--camera Nikon_D850 --chart sg140/);
    await screenshot(page, 'lab-exercise-link');
    // A bad link: a coded error as text, nothing inserted as HTML, the set-up untouched.
    await page.evaluate(() => { location.hash = '#lab=ex3&camera=%3Cimg%20src%3Dx%20onerror%3Dalert(1)%3E'; });
    await page.waitForSelector(`${S} [data-lab="link-error"]:not([hidden])`);
    const msg = await page.textContent(`${S} [data-lab="link-error"]`);
    assert.match(msg, /INVALID_ARGUMENT/);
    assert.match(msg, /'<img src=x onerror=alert\(1\)>' is not a choice of camera/);
    assert.equal(await page.$$eval(`${S} img`, (i) => i.length), 0);
    assert.equal(await page.$$eval(`${ex3} select`, (s) => s[0].value), 'Nikon_D850');
    await page.evaluate(() => { location.hash = '#lab=ex9'; });
    await page.waitForFunction(() => /no exercise 'ex9'/.test(document.querySelector('#step-lab [data-lab="link-error"]').textContent));
    assert.deepEqual(c.problems, []);
  } finally { await c.close(); }
});
