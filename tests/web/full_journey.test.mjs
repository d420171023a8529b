// The full journey with the real Passport DNG: reference -> RAW -> corners -> fit three models
// -> every plot has marks -> apply -> export and re-import the profile. Screenshots of each step
// go to test-artifacts/.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { screenshot, repoRoot } from './harness.mjs';
import { step, upload, fileBuffer, DNG, marks, markCounts, noErrorNear, setCorners, waitSampled, pageTest } from './journey.mjs';

// Index of the first differing byte of two buffers (or of the shorter length), -1 when identical.
function firstDifference(a, b) {
  const n = Math.min(a.length, b.length);
  for (let i = 0; i < n; i++) if (a[i] !== b[i]) return i;
  return a.length === b.length ? -1 : n;
}

const example = JSON.parse(fs.readFileSync(path.join(repoRoot, 'examples/web/passport.json'), 'utf8'));

pageTest('full journey: Passport DNG to fitted models, plots, applied image and re-imported profile', async (b) => {
  const { page } = b;

  // 1 Reference
  await step(page, 'reference');
  await page.waitForSelector('#step-reference .swatch');
  await screenshot(page, 'journey-1-reference');

  // 2 Images: the real DNG uploaded, corners placed, table with flags.
  await step(page, 'images');
  // (A name of its own: the example is also called passport.dng.)
  await upload(page, '#step-images input[data-slot="chart"]', 'passport-uploaded.dng', fileBuffer(DNG));
  await page.waitForFunction(() => /passport-uploaded\.dng — \d+×\d+/.test(document.querySelector('#step-images .file-state')?.textContent ?? ''), null, { timeout: 60000 });
  await setCorners(page, example.corners);
  assert.equal(await page.locator('#step-images .patch-table tbody tr').count(), 24);
  const table0 = await page.textContent('#step-images .patch-table tbody tr[data-id="A1"]');
  await page.evaluate(() => { window.__warnings = []; const w = console.warn; console.warn = (...a) => { window.__warnings.push(a.join(' ')); w(...a); }; });
  // Keyboard: nudge corner 1 by 10 px right; the table is re-sampled.
  await page.focus('#step-images .handle[data-corner="0"]');
  await page.keyboard.press('Shift+ArrowRight');
  const right = [...example.corners];
  right[0] += 10;
  await waitSampled(page, right).catch(async (e) => {
    console.log('state', await page.evaluate(() => [Array.from(window.tristim.session.corners ?? []), window.tristim.derived.sample?.corners, document.getElementById('corners-error')?.textContent, window.__warnings]));
    throw e;
  });
  assert.notEqual(await page.textContent('#step-images .patch-table tbody tr[data-id="A1"]'), table0);
  await page.keyboard.press('Shift+ArrowLeft');
  await waitSampled(page, example.corners);
  assert.equal(await page.textContent('#step-images .patch-table tbody tr[data-id="A1"]'), table0);
  // Pointer: drag corner 3 a little and back.
  const h = page.locator('#step-images .handle[data-corner="2"] circle.ring');
  await h.scrollIntoViewIfNeeded();
  const box = await h.boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width / 2 + 6, box.y + box.height / 2 + 4, { steps: 3 });
  await page.mouse.up();
  await page.waitForFunction((cs) => window.tristim.session.corners?.some((v, i) => v !== cs[i]), example.corners, { timeout: 5000 });
  const moved = await page.evaluate(() => Array.from(window.tristim.session.corners));
  assert.ok(moved[4] > example.corners[4] && moved[5] > example.corners[5], `corner 3 dragged right and down: ${moved}`);
  await setCorners(page, example.corners);
  assert.equal(await page.textContent('#step-images .patch-table tbody tr[data-id="A1"]'), table0);
  assert.equal(await page.locator('#step-images .overlay .cell').count(), 24);
  await screenshot(page, 'journey-2-images');

  // A held-out set: the same photo sampled over a smaller central area (other pixels), as a CSV.
  const area = page.locator('#step-images').getByLabel('Sampled area per patch');
  await area.fill('0.25');
  await area.dispatchEvent('change');
  await page.waitForFunction((t0) => document.querySelector('#step-images .patch-table tbody tr[data-id="A1"]')?.textContent !== t0, table0);
  const heldCsv = await page.evaluate(() => {
    const s = window.tristim.derived.sample;
    return 'patch,R,G,B\n' + s.ids.map((id, i) => `${id},${s.RGB[3 * i]},${s.RGB[3 * i + 1]},${s.RGB[3 * i + 2]}`).join('\n') + '\n';
  });
  await area.fill('0.5');
  await area.dispatchEvent('change');
  await page.waitForFunction((t0) => document.querySelector('#step-images .patch-table tbody tr[data-id="A1"]')?.textContent === t0, table0);

  // 3 Fit three models with the first objective.
  await step(page, 'fit');
  const boxes = page.locator('#step-fit input[data-model]');
  const nModels = await boxes.count();
  assert.ok(nModels >= 3, `the engine should offer at least three models, got ${nModels}`);
  for (let i = 0; i < nModels; i++) await boxes.nth(i).setChecked(i < 3);
  const objs = page.locator('#step-fit input[data-objective]');
  for (let i = 0; i < await objs.count(); i++) await objs.nth(i).setChecked(i === 0);
  await upload(page, '#step-fit input[type=file]', 'held-out-area25.csv', Buffer.from(heldCsv));
  await page.waitForFunction(() => /24 patches held out/.test(document.querySelector('#step-fit')?.textContent ?? ''));
  await page.click('#step-fit button.primary');
  await page.waitForSelector('#step-results:not([hidden]) table.compare', { timeout: 120000 });
  // the rows stream in: wait for the run's summary line
  await page.waitForFunction(() => /^3 of 3 fits in/.test(document.querySelector('#step-fit .fit-log li:last-child')?.textContent ?? ''), null, { timeout: 120000 });
  const held = await page.locator('#step-results table.compare tbody td[data-col="held-mean"]').allTextContents();
  assert.ok(held.length >= 3 && held.every((v) => Number.isFinite(Number(v))), `held-out means are numbers: ${held}`);
  const rows = await page.locator('#step-results table.compare tbody tr').count();
  assert.ok(rows >= 3, `three fitted models in the comparison table, got ${rows}`);
  assert.ok(await noErrorNear(page, '#step-fit button.primary'));

  // 4 Results: every plot has marks.
  const need = { 'xy-arrows': 24, 'lab-a-L': 48, 'lab-C-L': 48, 'de2000-bars': 72, 'xyz-scatter': 72, 'swatch-pairs': 48 };
  for (const [name, min] of Object.entries(need)) {
    const m = await marks(page, name);
    assert.ok(m >= min, `${name}: ${m} marks, expected ≥ ${min} (${JSON.stringify(await markCounts(page, name))})`);
  }
  const arrows = (await markCounts(page, 'xy-arrows')).arrow ?? 0;
  assert.ok(arrows >= 20, `reference → estimate arrows drawn (${arrows})`);
  // Sorting by a column reorders (or keeps) rows without losing any.
  await page.click('#step-results th[data-col="train-mean"] button');
  assert.equal(await page.locator('#step-results table.compare tbody tr').count(), rows);
  const cells = await page.locator('#step-results table.compare tbody td[data-col="train-mean"]').allTextContents();
  const nums = cells.map(Number);
  assert.ok(nums.every(Number.isFinite), `training means are numbers: ${cells}`);
  assert.deepEqual(nums, [...nums].sort((a, b) => a - b));
  // Hover: a patch's id and numbers.
  const dot = page.locator('figure[data-plot="lab-a-L"] svg > g[aria-label="dot"] circle').first();
  await dot.hover();
  await page.waitForFunction(() => /ΔE00 \d/.test(document.querySelector('figure[data-plot="lab-a-L"] g[aria-label="tip"]')?.textContent ?? ''));
  assert.match(await page.textContent('figure[data-plot="lab-a-L"] g[aria-label="tip"]'), /[A-D][1-6][\s\S]*L\*a\*b\*/);
  // Every plot exports as SVG and PNG.
  const [svgDl] = await Promise.all([page.waitForEvent('download'), page.click('figure[data-plot="de2000-bars"] button:has-text("SVG")')]);
  const svgText = fs.readFileSync(await svgDl.path(), 'utf8');
  assert.match(svgText, /^<svg[^>]*xmlns="http:\/\/www.w3.org\/2000\/svg"/);
  assert.ok((svgText.match(/<rect/g) ?? []).length >= 72);
  assert.match(svgText, /ΔL \(lightness\)/);
  const [pngDl] = await Promise.all([page.waitForEvent('download'), page.click('figure[data-plot="xy-arrows"] button:has-text("PNG")')]);
  const png = fs.readFileSync(await pngDl.path());
  assert.equal(png.subarray(1, 4).toString('latin1'), 'PNG');
  assert.ok(png.length > 5000, `PNG has content (${png.length} bytes)`);
  await screenshot(page, 'journey-4-results');

  // 5 Apply
  await step(page, 'apply');
  await page.click('#step-apply button.primary');
  await page.waitForSelector('#step-apply .apply-images:not([hidden])', { timeout: 60000 });
  assert.match(await page.textContent('#step-apply .legend-box'), /viridis/);
  const cv = page.locator('#step-apply canvas.apply-img').first();
  const cb = await cv.boundingBox();
  await page.mouse.move(cb.x + cb.width * 0.55, cb.y + cb.height * 0.7);
  await page.waitForFunction(() => /X .* Y .* Z .* x .* y .* L\*/.test(document.querySelector('#step-apply .readout')?.textContent ?? ''));
  // Keyboard: focus the Y map and move the read-out with the arrow keys.
  const before = await page.textContent('#step-apply .readout');
  await page.focus('#step-apply canvas.apply-img >> nth=1');
  await page.keyboard.press('Shift+ArrowLeft');
  await page.waitForFunction((b0) => document.querySelector('#step-apply .readout')?.textContent !== b0, before);
  await screenshot(page, 'journey-5-apply');

  // 6 Export the profile JSON and load it back.
  await step(page, 'export');
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#step-export button[data-export="Profile JSON"]')]);
  const saved = path.join(repoRoot, 'test-artifacts', 'journey-profile.json');
  await dl.saveAs(saved);
  const profileText = fs.readFileSync(saved, 'utf8');
  JSON.parse(profileText);
  const [dlCsv] = await Promise.all([page.waitForEvent('download'), page.click('#step-export button[data-export="Per-patch CSV"]')]);
  const csv = fs.readFileSync(await dlCsv.path(), 'utf8').trim().split('\n');
  const nIds = await page.evaluate(() => { const s = window.tristim.session; return (s.results.find((r) => r.key === s.selected) ?? s.results[0]).ids.length; });
  assert.equal(csv.length, 1 + nIds);
  await upload(page, '#step-export input[type=file]', 'journey-profile.json', Buffer.from(profileText));
  await page.waitForSelector('#step-export [data-imported]', { timeout: 30000 });
  assert.equal(await page.locator('#step-results table.compare tbody tr').count(), rows + 1);
  // The imported profile predicts exactly what the fitted one did on the same data.
  const same = await page.evaluate(() => {
    const rs = window.tristim.session.results;
    const imp = rs[rs.length - 1];
    const orig = rs.find((r) => r.fit.profile === imp.fit.profile && r !== imp);
    return { sameData: imp.evaluation.same_data_as_training, a: Array.from(orig.fit.evaluation.fit.fitted), b: Array.from(imp.evaluation.estimated), la: orig.fit.evaluation.loo?.dE00?.mean, lb: imp.fit.evaluation.loo?.dE00?.mean };
  });
  assert.equal(same.sameData, true);
  assert.deepEqual(same.b, same.a);
  assert.equal(same.lb, same.la);
  const [icc] = await Promise.all([page.waitForEvent('download'), page.click('#step-export button[data-export="ICC profile"]')]);
  const bytes = fs.readFileSync(await icc.path());
  assert.equal(bytes.subarray(36, 40).toString('latin1'), 'acsp');
  await upload(page, '#step-export input[type=file]', 'journey.icc', bytes);
  await page.waitForFunction(() => /ICC v/.test(document.querySelector('#step-export .import-result')?.textContent ?? ''));
  const [cube] = await Promise.all([page.waitForEvent('download'), page.click('#step-export button[data-export=".cube LUT"]')]);
  const cubeBytes = fs.readFileSync(await cube.path());
  // The page's downloads are byte-identical to the CLI's for the same profile (issue 15): the
  // native `tristim export` on the downloaded profile JSON writes the same ICC and .cube bytes.
  const cliIcc = path.join(repoRoot, 'test-artifacts', 'journey-cli.icc');
  const cliCube = path.join(repoRoot, 'test-artifacts', 'journey-cli.cube');
  execFileSync(path.join(repoRoot, 'build/native/core/tristim'), ['export', '--profile', saved, '--icc', cliIcc, '--cube', cliCube]);
  assert.equal(firstDifference(bytes, fs.readFileSync(cliIcc)), -1, 'page ICC = CLI ICC, byte for byte');
  assert.equal(firstDifference(cubeBytes, fs.readFileSync(cliCube)), -1, 'page .cube = CLI .cube, byte for byte');
  await upload(page, '#step-export input[type=file]', 'journey.cube', cubeBytes);
  await page.waitForFunction(() => /3D LUT/.test(document.querySelector('#step-export .import-result')?.textContent ?? ''));
  // The per-patch CSV loads back as a reference (its X_ref, Y_ref, Z_ref columns).
  await upload(page, '#step-export input[type=file]', 'journey-patches.csv', Buffer.from(csv.join('\n') + '\n'));
  await page.waitForFunction(() => /loaded as the reference/.test(document.querySelector('#step-export .import-result')?.textContent ?? ''));
  assert.match(await page.textContent('#step-reference .summary'), /journey-patches\.csv/);
  await screenshot(page, 'journey-6-export');

  // Every control on every step has an accessible name and can take keyboard focus.
  const unnamed = await page.evaluate(() => [...document.querySelectorAll('input, select, button, [role=slider], canvas[tabindex]')]
    .filter((el) => !(el.labels?.length || el.getAttribute('aria-label') || el.getAttribute('aria-labelledby') || el.textContent.trim() || el.title))
    .map((el) => el.outerHTML.slice(0, 80)));
  assert.deepEqual(unnamed, []);
  const unfocusable = await page.evaluate(() => [...document.querySelectorAll('input, select, button, [role=slider]')]
    .filter((el) => el.tabIndex < 0 && !el.disabled).map((el) => el.outerHTML.slice(0, 80)));
  assert.deepEqual(unfocusable, []);
  // No step says an engine function is missing.
  assert.deepEqual(await page.locator('[data-unavailable]').evaluateAll((es) => es.map((e) => e.dataset.unavailable)), []);
});
