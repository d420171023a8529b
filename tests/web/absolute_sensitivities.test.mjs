// Journey: the Absolute mode's spectral sensitivities (eq 7's channel areas; Jiang, Liu, Gu &
// Süsstrunk 2013). A bad CSV shows its code next to the upload; a good CSV (a built-in camera's
// curves written by the engine) is plotted against another built-in camera; the estimate from an
// uploaded patch file (the virtual camera's ColorChecker under D65) reports its residual and
// matches the camera it came from; the estimate from the chart step's samples (the page's example
// Passport photo) runs too; so does one from the user's own reflectance and illuminant files (a
// two-column illuminant refused next to its input); the estimate then feeds the absolute fit of the example bracket (the
// profile records it) and the maps carry the cells' labels.
import assert from 'node:assert/strict';
import { screenshot } from './harness.mjs';
import { step, upload, errorNear, noErrorNear, markCounts, pageTest } from './journey.mjs';
import { loadTristim } from '../wasm/load.mjs';

const S = '#step-absolute';
const CAMERA = 'Canon_EOS_5D_Mark_II';

pageTest('absolute sensitivities: upload (bad CSV coded), estimate from a patch file and from the chart step, plot, fit with the estimate, cell labels', async (b) => {
  const T = await loadTristim();
  const sim = T.simulateCamera(CAMERA, 'cc24', 'D65', {});
  const patchCsv = ['patch,R,G,B', ...sim.ids.map((id, i) => `${id},${sim.RGB[3 * i]},${sim.RGB[3 * i + 1]},${sim.RGB[3 * i + 2]}`)].join('\n');
  const nikonCsv = T.sensitivitiesToCsv(T.cameraSensitivities('Nikon_D850'));
  const { page } = b;
  await step(page, 'absolute');
  await page.click(`${S} [data-role="abs-ssf"] > summary`);

  // (a) upload: wavelengths going backwards -> NON_MONOTONIC next to the input; a good file -> chosen, plotted
  await upload(page, `${S} [data-role="abs-ssf-file"]`, 'backwards.csv', Buffer.from('wavelength_nm,R,G,B\n410,1,2,3\n400,1,2,3\n'));
  const bad = await errorNear(page, `${S} [data-role="abs-ssf-file"]`);
  assert.equal(bad.code, 'NON_MONOTONIC');
  assert.match(bad.text, /backwards\.csv/);
  await upload(page, `${S} [data-role="abs-ssf-file"]`, 'nikon.csv', Buffer.from(nikonCsv));
  await page.waitForFunction((s) => /nikon\.csv: R, G, B at 81 wavelengths/.test(document.querySelector(`${s} [data-role="abs-ssf-file-info"]`)?.textContent), S);
  assert.ok(await noErrorNear(page, `${S} [data-role="abs-ssf-file"]`));
  assert.equal(await page.$eval(`${S} [data-role="abs-camera"]`, (e) => e.value), '@upload');
  await page.waitForSelector(`${S} figure[data-plot="absolute-sensitivities"]`);
  const lines = await markCounts(page, 'absolute-sensitivities');
  assert.equal(lines.line, 6, JSON.stringify(lines));   // R, G, B of the upload (solid) and of the camera (dashed)
  const dashed = await page.$$eval(`${S} figure[data-plot="absolute-sensitivities"] svg > g[aria-label="line"][stroke-dasharray] path`, (p) => p.length);
  assert.equal(dashed, 3);
  const rmsNikon = Number(await page.$eval(`${S} [data-role="abs-ssf-compare-info"]`, (e) => e.dataset.rms));
  assert.ok(rmsNikon > 0.01, `Nikon D850 against ${CAMERA}: RMS ${rmsNikon}`);

  // (b) estimate from a patch file: a file whose ids are not the chart's -> PATCH_MISMATCH next to it
  await page.selectOption(`${S} [data-role="abs-ssf-source"]`, 'file');
  await page.selectOption(`${S} [data-role="abs-ssf-chart"]`, 'cc24');
  await page.selectOption(`${S} [data-role="abs-ssf-illuminant"]`, 'D65');
  await upload(page, `${S} [data-role="abs-ssf-patch-file"]`, 'other-ids.csv', Buffer.from('patch,R,G,B\nZ1,1,2,3\nZ2,2,3,4\n'));
  await page.click(`${S} [data-role="abs-ssf-estimate"]`);
  const mismatch = await errorNear(page, `${S} [data-role="abs-ssf-patch-file"]`);
  assert.equal(mismatch.code, 'PATCH_MISMATCH');
  await upload(page, `${S} [data-role="abs-ssf-patch-file"]`, 'cc24-d65.csv', Buffer.from(patchCsv));
  await page.click(`${S} [data-role="abs-ssf-estimate"]`);
  await page.waitForFunction((s) => document.querySelector(`${s} [data-role="abs-ssf-residual"]`)?.textContent.includes('cc24-d65.csv'), S);
  const residual = Number(await page.$eval(`${S} [data-role="abs-ssf-residual"]`, (e) => e.dataset.residual));
  assert.ok(residual > 0 && residual < 0.02, `residual ${residual}`);
  assert.match(await page.textContent(`${S} [data-role="abs-ssf-residual"]`), /24 patches/);
  assert.equal(await page.$eval(`${S} [data-role="abs-camera"]`, (e) => e.value), '@estimate');
  await page.waitForFunction((s) => /Jiang 2013/.test(document.querySelector(`${s} figure[data-plot="absolute-sensitivities"] figcaption`)?.textContent), S);
  const rmsEstimate = Number(await page.$eval(`${S} [data-role="abs-ssf-compare-info"]`, (e) => e.dataset.rms));
  assert.ok(rmsEstimate < 0.03, `estimate against ${CAMERA} (in the basis): RMS ${rmsEstimate}`);
  assert.ok(rmsEstimate < rmsNikon);
  // a blind test: the compared camera left out of the basis (the leave-one-camera-out)
  await page.check(`${S} [data-role="abs-ssf-blind"]`);
  await page.click(`${S} [data-role="abs-ssf-estimate"]`);
  await page.waitForFunction((s) => /51 cameras \(Canon EOS 5D Mark II left out\)/.test(document.querySelector(`${s} [data-role="abs-ssf-residual"]`)?.textContent), S);
  await page.waitForFunction(([s, r]) => Number(document.querySelector(`${s} [data-role="abs-ssf-compare-info"]`)?.dataset.rms) !== r, [S, rmsEstimate]);
  const rmsBlind = Number(await page.$eval(`${S} [data-role="abs-ssf-compare-info"]`, (e) => e.dataset.rms));
  assert.ok(rmsBlind > rmsEstimate && rmsBlind < 0.06, `blind estimate against ${CAMERA}: RMS ${rmsBlind} (in the basis ${rmsEstimate})`);
  await page.uncheck(`${S} [data-role="abs-ssf-blind"]`);
  await screenshot(page, 'absolute-sensitivities-1-estimate');

  // (b) from the chart step: the example Passport photo's samples (illuminant unknown: a shape, not a check of accuracy)
  assert.ok(await page.evaluate(() => window.tristim.derived.sample?.patches?.length > 0), 'the example chart is sampled');
  await page.selectOption(`${S} [data-role="abs-ssf-source"]`, 'chart');
  await page.selectOption(`${S} [data-role="abs-ssf-chart"]`, 'passport');
  await page.click(`${S} [data-role="abs-ssf-estimate"]`);
  await page.waitForFunction((s) => document.querySelector(`${s} [data-role="abs-ssf-residual"]`)?.textContent.includes('the chart step'), S, { timeout: 60000 });
  const chartResidual = Number(await page.$eval(`${S} [data-role="abs-ssf-residual"]`, (e) => e.dataset.residual));
  assert.ok(Number.isFinite(chartResidual) && chartResidual > 0 && chartResidual < 0.5, `chart-step residual ${chartResidual}`);

  // (c) the user's own chart spectra and light (the CLI's --reflectances / --illuminant files): the
  // built-in ColorChecker and D65 written out as files give the built-in estimate's residual again
  const refl = T.chartReflectances('cc24'), d65 = T.illuminantSpectrum('D65');
  const reflCsv = ['wavelength_nm,' + refl.names.join(','), ...Array.from(refl.wavelengths, (w, i) => [w, ...refl.values.map((v) => v[i])].join(','))].join('\n');
  const d65Csv = ['wavelength_nm,D65', ...Array.from(d65.wavelengths, (w, i) => `${w},${d65.values[0][i]}`)].join('\n');
  await page.selectOption(`${S} [data-role="abs-ssf-source"]`, 'file');
  await page.selectOption(`${S} [data-role="abs-ssf-chart"]`, 'file');
  await page.selectOption(`${S} [data-role="abs-ssf-illuminant"]`, 'file');
  await page.click(`${S} [data-role="abs-ssf-estimate"]`);
  assert.equal((await errorNear(page, `${S} [data-role="abs-ssf-reflectance-file"]`)).code, 'NO_SPECTRA');
  await upload(page, `${S} [data-role="abs-ssf-reflectance-file"]`, 'my-chart.csv', Buffer.from(reflCsv));
  await page.waitForFunction((s) => /my-chart\.csv: 24 spectra/.test(document.querySelector(`${s} [data-role="abs-ssf-reflectance-info"]`)?.textContent), S);
  await upload(page, `${S} [data-role="abs-ssf-illuminant-file"]`, 'two-lights.csv', Buffer.from('wavelength_nm,A,D65\n400,1,2\n410,1,2\n'));
  const two = await errorNear(page, `${S} [data-role="abs-ssf-illuminant-file"]`);
  assert.equal(two.code, 'INVALID_ARGUMENT');
  assert.match(two.text, /one value column; this one has 2 \(A, D65\)/);
  await upload(page, `${S} [data-role="abs-ssf-illuminant-file"]`, 'my-d65.csv', Buffer.from(d65Csv));
  await page.waitForFunction((s) => /my-d65\.csv: \d+ wavelengths/.test(document.querySelector(`${s} [data-role="abs-ssf-illuminant-info"]`)?.textContent), S);
  assert.ok(await noErrorNear(page, `${S} [data-role="abs-ssf-illuminant-file"]`));
  await page.click(`${S} [data-role="abs-ssf-estimate"]`);
  await page.waitForFunction((s) => /file:my-chart\.csv, file:my-d65\.csv/.test(document.querySelector(`${s} figure[data-plot="absolute-sensitivities"] figcaption`)?.textContent), S);
  const ownResidual = Number(await page.$eval(`${S} [data-role="abs-ssf-residual"]`, (e) => e.dataset.residual));
  assert.ok(Math.abs(ownResidual - residual) <= 1e-12 * residual, `own files ${ownResidual} vs built-in ${residual}`);
  await page.selectOption(`${S} [data-role="abs-ssf-illuminant"]`, 'D65');

  // the estimate from the patch file again, then it feeds the fit of the example bracket
  await page.selectOption(`${S} [data-role="abs-ssf-source"]`, 'file');
  await page.selectOption(`${S} [data-role="abs-ssf-chart"]`, 'cc24');
  await upload(page, `${S} [data-role="abs-ssf-patch-file"]`, 'cc24-d65.csv', Buffer.from(patchCsv));
  await page.click(`${S} [data-role="abs-ssf-estimate"]`);
  await page.waitForFunction((s) => document.querySelector(`${s} [data-role="abs-ssf-residual"]`)?.textContent.includes('cc24-d65.csv'), S);
  await page.click(`${S} [data-role="abs-example"]`);
  await page.waitForSelector(`${S} .abs-maps:not([hidden])`, { timeout: 180000 });
  assert.equal(await page.$$eval(`${S} [data-role="abs-luminance-labels"] text`, (t) => t.length), 36);
  assert.equal(await page.$$eval(`${S} [data-role="abs-source-labels"] text`, (t) => t.length), 36);
  await page.selectOption(`${S} [data-role="abs-camera"]`, '@estimate');
  await page.click(`${S} [data-role="abs-fit"]`);
  await page.waitForFunction((s) => /estimate:Jiang2013 cc24 D65 24 patches/.test(document.querySelector(`${s} [data-role="abs-fit-summary"]`)?.textContent), S, { timeout: 180000 });
  await page.waitForSelector(`${S} [data-role="abs-fit"]:not([disabled])`, { timeout: 180000 });
  assert.equal(await page.$eval(`${S} .abs-maps`, (e) => e.hidden), false);
  // the cells still within the paper's 2.4 % on average with the estimated areas
  const relY = await page.$$eval(`${S} [data-role="abs-figures"] [data-col="relY"]`, (e) => e.map((x) => parseFloat(x.textContent)));
  assert.ok(relY[1] < 2.4, `relative Y error on the scene's cells with the estimate ${relY[1]} %`);
  await page.click(`${S} [data-role="abs-labels"]`);
  assert.equal(await page.$eval(`${S} [data-role="abs-luminance-labels"]`, (e) => e.style.display), 'none');
  await page.click(`${S} [data-role="abs-labels"]`);
  await screenshot(page, 'absolute-sensitivities-2-fit');
});

pageTest('absolute example under F2 with reflective colour training (T2R chosen with it): the chart cells within Table 4', async ({ page }) => {
  await step(page, 'absolute');
  await page.selectOption(`${S} [data-role="abs-example-light"]`, 'F2');
  await page.selectOption(`${S} [data-role="abs-example-training"]`, 'reflective');
  await page.click(`${S} [data-role="abs-example"]`);
  await page.waitForSelector(`${S} .abs-maps:not([hidden])`, { timeout: 180000 });
  assert.match(await page.textContent(`${S} [data-role="abs-test-info"]`), /ColorChecker under F2/);
  assert.match(await page.textContent(`${S} [data-role="abs-fit-summary"]`), /Colour matrix T2R/);
  // columns: training stimuli, all 36 cells, the 24 chromatic (ColorChecker) cells, the 12-cell ladder
  const heads = await page.$$eval(`${S} [data-role="abs-figures"] thead th`, (e) => e.map((x) => x.textContent));
  assert.match(heads[3], /chromatic \(24\)/);
  const relY = await page.$$eval(`${S} [data-role="abs-figures"] [data-col="relY"]`, (e) => e.map((x) => parseFloat(x.textContent)));
  assert.equal(relY.length, 4);
  assert.ok(relY[2] < 2.4, `relative Y error on the ColorChecker cells under F2 ${relY[2]} %`);
  await screenshot(page, 'absolute-sensitivities-3-f2-reflective');
});
