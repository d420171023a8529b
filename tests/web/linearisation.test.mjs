// Journey: a non-linear chart image and the linearisation step (issue 11). The example Passport
// RAW, encoded with gamma 1/2.2 as an 8-bit JPEG and a 16-bit TIFF at test time
// (image_fixtures.mjs), is loaded in the images step (its encoding shown, the chart detected on
// decode); in step 2b Shen2008 (non-grey patches) and gamma recover curves that agree with the
// grey-based ones (R² > 0.99 per channel, as the engine computes it); the fit trains on the
// linearised RGB and its training ΔE00 is close to the RAW's. Bad input: Shen2008 with more basis
// functions than the non-grey patches allow shows TOO_FEW_PATCHES next to J.
import assert from 'node:assert/strict';
import { screenshot } from './harness.mjs';
import { step, upload, errorNear, pageTest } from './journey.mjs';
import { loadTristim } from '../wasm/load.mjs';
import { encodedPassport, tiff16, jpegInPage, EXAMPLE } from './image_fixtures.mjs';

const CHART = '#step-images input[data-slot="chart"]';
const SUMMARY = '#step-linearisation [data-role="linearisation-summary"]';
const METHOD = '#step-linearisation select >> nth=0';

/// Training mean ΔE00 of each fitted model (the first objective), by model id.
const trainingErrors = (page) => page.evaluate(() => Object.fromEntries(window.tristim.session.results
  .filter((r) => r.objective === window.tristim.catalog.objectives[0].id).map((r) => [r.modelId, r.fit.evaluation.training.dE00.mean])));

const MODELS = ['matrix-3x3', 'Finlayson2015-2', 'Shen2008'];
async function fit(page) {
  await step(page, 'fit');
  // the three models this test compares, with the first objective (the page's default compares everything)
  for (const [attr, keep] of [['model', MODELS], ['objective', ['ls']]]) {
    const boxes = page.locator(`#step-fit input[data-${attr}]`);
    for (let i = 0; i < await boxes.count(); i++) await boxes.nth(i).setChecked(keep.includes(await boxes.nth(i).getAttribute(`data-${attr}`)));
  }
  await page.click('#step-fit button.primary');
  await page.waitForFunction(() => /fits in [\d.]+ s\.$/.test(document.querySelector('#step-fit .fit-log li:last-child')?.textContent ?? ''),
    null, { timeout: 120000 });
  // the run keeps its results, then the selected one and its recipe (IndexedDB writes in between)
  await page.waitForFunction(() => { const s = window.tristim.session; return s.recipe && s.recipe === s.results?.find((r) => r.key === s.selected)?.recipe; });
  return trainingErrors(page);
}

/// Loads a chart image and waits until it is decoded, detected and sampled (24 patches).
async function load(page, name, bytes) {
  const runs = Number(await page.getAttribute('#step-images .detect-panel', 'data-runs') ?? 0);
  await step(page, 'images');
  await upload(page, CHART, name, bytes);
  await page.waitForFunction(([n, r]) => document.querySelector('#step-images .file-state')?.textContent.startsWith(n)
    && Number(document.querySelector('#step-images .detect-panel').dataset.runs ?? 0) > r, [name, runs], { timeout: 60000 });
  await page.waitForFunction((n) => window.tristim.derived.sample?.ids.length === 24 && window.tristim.session['files.chart']?.name === n, name);
}

/// Chooses a linearisation (and options) and waits for its fit: {r2: [R, G, B], text}.
async function linearise(page, method, options = {}) {
  await step(page, 'linearisation');
  const before = await page.evaluate(() => window.tristim.derived.linearisation);
  await page.selectOption(METHOD, method);
  for (const [name, v] of Object.entries(options)) {
    await page.fill(`#step-linearisation [data-option="${name}"]`, String(v));
    await page.dispatchEvent(`#step-linearisation [data-option="${name}"]`, 'change');
  }
  await page.waitForFunction(([m, b]) => {
    const d = window.tristim.derived.linearisation;
    return d && d !== b && d.lin.method === m && document.querySelector('#step-linearisation .progress').hidden;
  }, [method, before], { timeout: 60000 });
  const r2 = await page.$$eval('#step-linearisation .linearisation-r2 td[data-col="r2"]', (tds) => tds.map((td) => Number(td.dataset.value)));
  return { r2, text: await page.textContent(SUMMARY) };
}

pageTest('JPEG and 16-bit TIFF charts: encoding shown, Shen2008 and gamma recover the OECF, the fit matches the RAW', async ({ page }) => {
  const T = await loadTristim();
  const img = encodedPassport(T);
  const raw = await trainingErrors(page);   // the example RAW, fitted on the first visit
  const models = MODELS.filter((m) => m in raw);
  assert.equal(models.length, MODELS.length, 'the example was fitted (every model compared on the first visit)');

  // 8-bit JPEG: decoded as stored, its encoding shown, the chart found on decode.
  const jpeg = await jpegInPage(page, img.width, img.height, img.rgba8);
  assert.equal(jpeg.subarray(0, 3).toString('hex'), 'ffd8ff');
  await load(page, 'passport-gamma.jpg', jpeg);
  assert.match(await page.textContent('#step-images .meta'), /JPEG, 8-bit RGB, 867×578, values as stored \(0–255\)/);
  assert.match(await page.textContent('#step-images .encoding-note'), /Not linear.*step 2b/);
  const corners = await page.evaluate(() => Array.from(window.tristim.derived.sample.corners));
  assert.ok(corners.every((v, i) => Math.abs(v - EXAMPLE.corners[i]) < 6), `corners ${corners}`);

  // identity on a JPEG: the step says so
  await step(page, 'linearisation');
  await page.waitForSelector('#step-linearisation [data-role="linearisation-advice"]:not([hidden])');
  assert.match(await page.textContent('#step-linearisation [data-role="linearisation-encoding"]'), /JPEG, 8 bit per sample.*full scale 255/);

  // The JPEG fitted as if it were linear: the encoding's curve becomes colour error.
  const identityFit = await fit(page);
  assert.match(await page.textContent('#step-fit .summary'), /not linear.*“identity”: choose one in step 2b/);

  // Shen2008 (defaults K = 2, J = 8, L = 2): curves against the grey-based ones, R² per channel.
  const shen = await linearise(page, 'Shen2008');
  for (const v of shen.r2) assert.ok(v > 0.99, `Shen2008 R² ${shen.r2}`);
  const engineR2 = await page.evaluate(() => Array.from(window.tristim.derived.linearisation.lin.r_squared));
  assert.deepEqual(shen.r2, engineR2, 'the R² shown is the engine\'s');
  // the greys, found automatically (ΔE00 from the neutral of the same L* < 2), are left out of the fit
  const greys = await page.evaluate(() => window.tristim.derived.linearisation.lin.greys);
  assert.ok(greys.length >= 4 && greys.every((id) => /^D[1-6]$/.test(id)), `greys ${greys}`);
  assert.match(shen.text, new RegExp(`fitted on ${24 - greys.length} of 24 paired patches`));
  assert.match(await page.textContent('#step-linearisation [data-role="linearisation-greys"]'),
    new RegExp(`Grey patches \\(${greys.length}\\): ${greys.join(', ')} — automatic`));
  assert.ok(await page.locator('figure[data-plot="linearisation-oecf"] svg').count() === 1);
  assert.ok(await page.isHidden('#step-linearisation [data-role="linearisation-monotonic"]'));
  assert.ok(await page.locator('figure[data-plot="linearisation-spectral-rms"] svg g[aria-label="bar"] rect').count() === 24);
  assert.ok(await page.locator('figure[data-plot="linearisation-reflectance"]').count() === 1);
  const rms = Number(await page.getAttribute('#step-linearisation [data-role="linearisation-spectral"]', 'data-rms-mean'));
  assert.ok(rms > 0 && rms < 0.08, `spectral RMS ${rms}`);
  await screenshot(page, 'linearisation-1-jpeg-shen2008');
  const shenFit = await fit(page);

  // gamma 2.2: the encoding's own inverse.
  const gamma = await linearise(page, 'gamma');
  for (const v of gamma.r2) assert.ok(v > 0.99, `gamma R² ${gamma.r2}`);
  const gammaFit = await fit(page);
  const recipe = await page.evaluate(() => window.tristim.session.recipe);
  assert.equal(recipe.linearisation.method, 'gamma', JSON.stringify(await page.evaluate(() => ({ lin: window.tristim.session.linearisation,
    log: document.querySelector('#step-fit .fit-log').textContent, results: window.tristim.session.results.map((r) => r.recipe.linearisation.method) }))));
  assert.equal(recipe.capture.saturation, 255, 'the recipe records the JPEG\'s full scale');

  // 16-bit TIFF, gamma kept.
  await load(page, 'passport-gamma.tif', tiff16(img.width, img.height, img.rgb16));
  assert.match(await page.textContent('#step-images .meta'), /TIFF, 16-bit RGB, 867×578, values as stored \(0–65535\)/);
  const tiffGamma = await linearise(page, 'Shen2008');
  for (const v of tiffGamma.r2) assert.ok(v > 0.99, `TIFF Shen2008 R² ${tiffGamma.r2}`);
  await linearise(page, 'gamma');
  const tiffFit = await fit(page);
  assert.equal((await page.evaluate(() => window.tristim.session.recipe)).capture.saturation, 65535);

  // The fits on linearised data measure as the RAW's do (identity on the JPEG would not).
  for (const m of models) {
    const line = `${m}: RAW ${raw[m].toFixed(3)}, JPEG identity ${identityFit[m].toFixed(3)}, JPEG Shen2008 ${shenFit[m].toFixed(3)}, JPEG gamma ${gammaFit[m].toFixed(3)}, TIFF gamma ${tiffFit[m].toFixed(3)}`;
    console.log(line);
    assert.ok(Math.abs(gammaFit[m] - raw[m]) < 0.05 * raw[m] + 0.05, line);
    assert.ok(Math.abs(tiffFit[m] - raw[m]) < 0.05 * raw[m] + 0.05, line);
    assert.ok(shenFit[m] < 1.5 * raw[m] + 0.5, line);
    // a 3×3 cannot absorb the encoding's curve (a root-polynomial or the 10-term polynomial partly can)
    if (m === 'matrix-3x3') assert.ok(identityFit[m] > gammaFit[m] + 2 && identityFit[m] > shenFit[m] + 2, line);
  }

  // Bad input: J = 20 needs K + J = 22 non-grey patches; the Passport has 18.
  await step(page, 'linearisation');
  await page.selectOption(METHOD, 'Shen2008');
  await page.fill('#step-linearisation [data-option="J"]', '20');
  await page.dispatchEvent('#step-linearisation [data-option="J"]', 'change');
  const e = await errorNear(page, '#step-linearisation [data-option="J"]');
  assert.equal(e.code, 'TOO_FEW_PATCHES', e.text);
  await screenshot(page, 'linearisation-2-too-few');
});
