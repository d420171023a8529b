// Journey: the surface step (Abed, Berns & Masaoka 2013). A correction picked from the engine's
// table changes the reference by the ΔE00 the engine computes; the example second measurement
// (the SG measured d:8 SCI) gives the Phase I ranking with the engine's numbers; "Use" puts the
// fitted correction into the recipe, and the fit step trains on the corrected reference.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { screenshot, repoRoot } from './harness.mjs';
import { step, marks, upload, errorNear, pageTest } from './journey.mjs';
import { loadTristim } from '../wasm/load.mjs';

const fmt = (x, d = 2) => x.toFixed(d);

pageTest('surface: correction preview, Phase I ranking of the example, the choice in the recipe and the fit', async ({ page }) => {
  const T = await loadTristim();
  await step(page, 'surface');
  const summary = '#step-surface [data-role="surface-summary"]';
  await page.waitForFunction((s) => /No correction/.test(document.querySelector(s)?.textContent ?? ''), summary);
  const settings = await page.evaluate(() => window.tristim.derived.reference.settings);

  // 1. scaler-offset with μ = 1.05, ρ = −0.02: the mean ΔE00 shown is the engine's.
  await page.selectOption('#step-surface select >> nth=0', 'scaler-offset');
  await page.fill('#step-surface input[data-option="mu"]', '1.05');
  await page.dispatchEvent('#step-surface input[data-option="mu"]', 'change');
  await page.fill('#step-surface input[data-option="rho"]', '-0.02');
  await page.dispatchEvent('#step-surface input[data-option="rho"]', 'change');
  await page.waitForFunction((s) => /scaler-offset:mu=1\.05,rho=-0\.02/.test(document.querySelector(s)?.textContent ?? ''), summary);
  const choice = { method: 'scaler-offset', parameters: { mu: 1.05, rho: -0.02 }, settings: {} };
  const reference = { chart: settings.chart, illuminant: settings.illuminant, observer: settings.observer };
  const before = T.recipeReference({ reference }), after = T.recipeReference({ reference, surface: choice });
  const dE = T.deltaE('CIE2000', before.Lab, after.Lab);
  const mean = dE.reduce((a, v) => a + v, 0) / dE.length;
  const shown = Number(await page.getAttribute(summary, 'data-mean'));
  assert.ok(Math.abs(shown - mean) < 1e-12, `mean ΔE00 shown ${shown}, engine ${mean}`);
  assert.match(await page.textContent(summary), new RegExp(`mean ΔE00 ${fmt(mean)}, max ${fmt(Math.max(...dE))}`));
  assert.ok(await marks(page, 'surface-reflectances') >= 8, 'reflectance curves drawn');
  assert.ok(await marks(page, 'surface-de00') >= before.ids.length, 'one ΔE00 bar per patch');
  await screenshot(page, 'surface-1-scaler-offset');

  // 2. A spectral file without spectra: a coded error next to the input, the step stays usable.
  await upload(page, '#step-surface input[type=file]', 'cc24_Lab_D50.csv', fs.readFileSync(path.join(repoRoot, 'tests/web/fixtures/cc24_Lab_D50.csv')));
  const err = await errorNear(page, '#step-surface input[type=file]');
  assert.equal(err.code, 'MISSING_COLUMN');

  // 3. The example second measurement: every row of the ranking is the engine's Phase I fit.
  await page.click('#step-surface button:has-text("Use the example second measurement")');
  await page.waitForSelector('#step-surface table.surface-ranking tbody tr[data-method="saunderson"]', { timeout: 60000 });
  const sci = T.parsePatchFile(fs.readFileSync(path.join(repoRoot, 'examples/web/sg_d8_sci_coolpi.csv'), 'utf8'), 'sci.csv').spectra;
  const xrite = T.chartReflectances('sg140-2005');
  const options = { range_min: 400, range_max: 700, observer: settings.observer };
  const starts = {
    none: 'none', scaler: 'scaler', offset: 'offset', 'scaler-offset': choice,
    saunderson: 'saunderson:k1=0.04,k2=0.6,k_ins=0,k1_capture=0.092,k2_capture=0.6,k_ins_capture=0',
  };
  const fits = {};
  for (const [m, start] of Object.entries(starts)) {
    const f = T.fitSurface(start, xrite, sci, { ...options, free: 'capture' }, settings.illuminant);
    fits[m] = f;
    const row = `#step-surface table.surface-ranking tr[data-method="${m}"]`;
    assert.equal(await page.textContent(`${row} td[data-col="mean"]`), fmt(f.dE00.after.mean), `${m} mean ΔE00`);
    assert.equal(await page.textContent(`${row} td[data-col="max"]`), fmt(f.dE00.after.max), `${m} max ΔE00`);
    assert.equal(await page.textContent(`${row} td[data-col="rms"]`), `${fmt(f.spectral_rms.before, 4)} → ${fmt(f.spectral_rms.after, 4)}`, `${m} RMS`);
  }
  // the paper's ranking on this pair of measurements (offset < scaler, scaler-offset < offset)
  const m = (k) => fits[k].dE00.after.mean;
  assert.ok(m('offset') < m('scaler') && m('scaler-offset') < m('offset') && m('saunderson') < m('offset'), JSON.stringify(Object.keys(fits).map((k) => [k, m(k)])));
  assert.ok(await marks(page, 'surface-reflectances') > 0);
  await screenshot(page, 'surface-2-ranking');

  // 4. "Use" the fitted scaler-offset: it becomes the recipe's surface stage and the fit trains on it.
  await page.click('#step-surface table.surface-ranking tr[data-method="scaler-offset"] button');
  const fitted = fits['scaler-offset'].choice;
  await page.waitForFunction((mu) => window.tristim.session.surface?.parameters?.mu === mu, fitted.parameters.mu);
  if (settings.chart !== 'sg140-2005') assert.match(await page.textContent('#step-surface [data-role="surface-use-note"]'), /fitted on sg140-2005; step 1's chart is/);
  await step(page, 'fit');
  const results = await page.evaluate(() => window.tristim.views.fit.run());
  assert.ok(results?.length > 0, `the fit ran: ${await page.textContent('#step-fit .fit-log')} ${await page.textContent('#fit-error')}`);
  const r0 = await page.evaluate(() => ({ surface: window.tristim.session.results[0].recipe.surface, ids: window.tristim.session.results[0].ids, xyz: Array.from(window.tristim.session.results[0].xyz) }));
  assert.equal(r0.surface.method, 'scaler-offset');
  assert.equal(r0.surface.parameters.mu, fitted.parameters.mu);
  assert.equal(r0.surface.parameters.rho, fitted.parameters.rho);
  const corrected = T.recipeReference({ reference, surface: fitted });
  const k = corrected.ids.indexOf(r0.ids[0]);
  for (let c = 0; c < 3; c++) assert.ok(Math.abs(r0.xyz[c] - corrected.XYZ[3 * k + c]) < 1e-9, `trained on the corrected XYZ of ${r0.ids[0]}`);

  // 5. Phase II from the fit path: coefficients "joint" are fitted with the anchored 3×3 in the fit step.
  await step(page, 'surface');
  await page.selectOption('#step-surface select[data-option="fit"]', 'joint');
  await page.waitForFunction(() => window.tristim.session.surface?.settings?.fit === 'joint');
  await step(page, 'fit');
  assert.ok((await page.evaluate(() => window.tristim.views.fit.run()))?.length > 0, await page.textContent('#step-fit .fit-log'));
  assert.match(await page.textContent('#step-fit .fit-log'), /surface fitted jointly \(Phase II\): scaler-offset: mu=/);
  const j = await page.evaluate(() => { const r = window.tristim.session.results[0]; return { recipe: r.recipe.surface, applied: r.fit.surface, white: r.recipe.characterisation.white_patch }; });
  assert.equal(j.recipe.settings.fit, 'joint');
  assert.equal(j.applied.settings.fit, 'fixed');
  assert.notEqual(j.applied.parameters.mu, fitted.parameters.mu);
  assert.ok(j.white, 'the joint fit is anchored to a white patch');
  await screenshot(page, 'surface-3-joint-fit');
});
