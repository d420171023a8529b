// The declarations themselves: every method table is listed with its option schema, field names
// are the C++ ones (snake_case), structs take their C++ defaults for fields left out, and bad
// input of any kind (unknown field, wrong type, unknown id) comes back as a coded Error.
import test from 'node:test';
import assert from 'node:assert/strict';
import { loadTristim, throwsCode } from './load.mjs';

/// Keys anywhere in a value that look camelCase (nTerms, conditionNumber); scientific names such
/// as sRGB, dE00, XYZ, white_RGB are not camelCase.
function camelKeys(v, path = '', out = []) {
  if (v && typeof v === 'object' && !ArrayBuffer.isView(v)) {
    for (const [k, x] of Object.entries(v)) {
      if (/[a-z][A-Z][a-z]/.test(k)) out.push(`${path}.${k}`);
      camelKeys(x, `${path}.${k}`, out);
    }
  }
  return out;
}

test('method tables: objectives, linearisations, surface corrections, with option schemas', async () => {
  const T = await loadTristim();
  const objectives = T.listObjectives();
  assert.deepEqual(objectives.map((o) => o.id), ['ls', 'psm', 'de2000']);
  const de = objectives.find((o) => o.id === 'de2000');
  assert.match(de.reference, /CIEDE2000/);
  const alg = de.options.find((o) => o.name === 'algorithm');
  assert.equal(alg.type, 'choice');
  assert.equal(alg.default_text, 'auto', 'the page\'s CIEDE2000 default is the engine\'s');
  assert.ok(alg.choices.includes('lm') && alg.choices.includes('bobyqa'));
  const psm = objectives.find((o) => o.id === 'psm');
  assert.deepEqual(psm.options.map((o) => o.name), ['initial_step', 'expansion', 'contraction', 'step_threshold', 'max_iterations']);
  assert.equal(psm.options.find((o) => o.name === 'expansion').default_number, 2);
  assert.equal(T.listLinearisations()[0].id, 'identity');
  assert.equal(T.listSurfaceCorrections()[0].id, 'none');
  for (const list of [objectives, T.listLinearisations(), T.listSurfaceCorrections(), T.listModels(), T.listCharts(), T.listIlluminants()])
    assert.deepEqual(camelKeys(list), []);
  assert.ok(T.listIlluminants().some((i) => i.id === 'F11' && /fluorescent/.test(i.name)));
});

test('the catalog\'s other tables: observers, flat-field modes, surface equations and geometries, needs', async () => {
  const T = await loadTristim();
  assert.deepEqual(T.listObservers(), [{ id: '1931', name: 'CIE 1931 2°' }, { id: '1964', name: 'CIE 1964 10°' }]);
  assert.deepEqual(T.listFlatFieldModes().map((m) => m.id), ['pixel', 'radial']);
  const surfaces = Object.fromEntries(T.listSurfaceCorrections().map((r) => [r.id, r]));
  assert.equal(surfaces['scaler-offset'].equation, "R' = μR + ρ, eq (5)");
  assert.deepEqual(surfaces['scaler-offset'].coefficients, ['mu', 'rho']);
  assert.deepEqual(surfaces.saunderson.geometry.capture, { k1: 'k1_capture', k2: 'k2_capture', k_ins: 'k_ins_capture' });
  assert.deepEqual(surfaces.none.geometry, {});
  for (const r of T.listLinearisations()) assert.ok(r.needs_text, r.id);
  for (const list of [T.listObservers(), T.listFlatFieldModes(), T.listModelFamilies(), T.listSurfaceCorrections()])
    assert.deepEqual(camelKeys(list), []);
});

test('quantile: the engine\'s one percentile (Summary\'s rule); patch keys', async () => {
  const T = await loadTristim();
  const v = Float64Array.from([7, 1, 4, 10, 2, 3]);
  assert.equal(T.quantile(v, 0.5), 3.5);
  assert.equal(T.quantile(v, 0.25), 2.25);
  assert.ok(Number.isNaN(T.quantile(Float64Array.from([NaN]), 0.5)));
  throwsCode(assert, () => T.quantile(v, 2), 'INVALID_ARGUMENT');
  assert.equal(T.normalisePatchId(' a01 '), 'A1');
});

test('choices: completed from the table, parsed from the CLI syntax, refused with codes', async () => {
  const T = await loadTristim();
  const psm = T.listObjectives().find((o) => o.id === 'psm');
  const c = T.completeChoice(psm, { method: 'psm', parameters: { expansion: 3 } });
  assert.equal(c.parameters.expansion, 3);
  assert.equal(c.parameters.contraction, 0.5);
  assert.deepEqual(T.parseChoice('psm:expansion=3'), { method: 'psm', parameters: { expansion: 3 }, settings: {} });
  throwsCode(assert, () => T.completeChoice(psm, { method: 'psm', parameters: { nope: 1 } }), 'UNKNOWN_ID');
  throwsCode(assert, () => T.completeChoice(psm, { method: 'psm', parameters: { contraction: 7 } }), 'INVALID_ARGUMENT');
});

test('chart layouts and the corner homography come from the engine', async () => {
  const T = await loadTristim();
  assert.deepEqual(T.listChartLayouts(), ['cc24', 'cc24-2005', 'passport', 'sg140', 'sg140-2005', 'custom']);
  const p = T.chartLayout({ chart: 'passport' });
  assert.equal(p.rows, 4);
  assert.equal(p.columns, 6);
  assert.equal(p.patches.length, 24);
  assert.equal(p.patches[23].id, 'D6');
  assert.ok(p.gap > 0);
  // The grid with its gaps fills the corners edge to edge.
  [p.patches[0].u0, p.patches[0].v0, p.patches[23].u1 - 1, p.patches[23].v1 - 1].forEach((v) => assert.ok(Math.abs(v) < 1e-12, v));
  const sg = T.chartLayout({ chart: 'sg140' });
  assert.equal(sg.patches.find((q) => q.row === 9 && q.column === 13).id, 'N10');
  assert.equal(T.chartLayout({ chart: 'custom', rows: 2, columns: 3 }).patches[5].id, 'R2C3');
  assert.deepEqual(camelKeys(p), []);
  const c = [10, 20, 110, 25, 120, 90, 5, 80];
  const H = T.homographyUnitSquare(c);
  assert.equal(H.length, 9);
  [[0, 0], [1, 0], [1, 1], [0, 1]].forEach(([u, v], i) => {
    const w = H[6] * u + H[7] * v + H[8];
    assert.ok(Math.abs((H[0] * u + H[1] * v + H[2]) / w - c[2 * i]) < 1e-9);
    assert.ok(Math.abs((H[3] * u + H[4] * v + H[5]) / w - c[2 * i + 1]) < 1e-9);
  });
  throwsCode(assert, () => T.chartLayout({ chart: 'nope' }), 'UNKNOWN_ID');
  throwsCode(assert, () => T.chartLayout({ chart: 'custom', rows: 0, columns: 3 }), 'INVALID_ARGUMENT');
  throwsCode(assert, () => T.homographyUnitSquare([1, 2, 3, 4, 5, 6, 7]), 'INVALID_ARGUMENT');
});

test('structs: fields left out take the C++ defaults; unknown fields and wrong types are refused', async () => {
  const T = await loadTristim();
  const rgb = Float64Array.from([0.1, 0.2, 0.3, 0.5, 0.4, 0.2, 0.2, 0.6, 0.1, 0.3, 0.3, 0.7, 0.8, 0.7, 0.6]);
  const xyz = Float64Array.from(rgb, (v, i) => 50 * v + (i % 3));
  const e = T.evaluateModel('matrix-3x3', rgb, xyz, { objective: 'ls' }, -1, true);
  assert.equal(e.fit.status, 'ok');
  assert.equal(e.has_loo, true);
  assert.equal(e.fit.model.coefficients.length, 9);
  assert.ok(Array.isArray(e.training.patches.dE00) && e.training.patches.dE00.length === 5);
  assert.deepEqual(camelKeys(e), []);
  const noLoo = T.evaluateModel('matrix-3x3', rgb, xyz, {}, -1, false);
  assert.equal(noLoo.loo, null);
  throwsCode(assert, () => T.evaluateModel('matrix-3x3', rgb, xyz, { objectiv: 'ls' }, -1, true), 'INVALID_ARGUMENT');
  throwsCode(assert, () => T.evaluateModel('matrix-3x3', rgb, xyz, { psm: { expansion: 'big' } }, -1, true), 'INVALID_ARGUMENT');
  throwsCode(assert, () => T.evaluateModel('matrix-3x3', rgb.subarray(0, 14), xyz, {}, -1, true), 'INVALID_ARGUMENT');
  const ids = ['A1', 'A2', 'A3', 'A4', 'A5'];
  const fit = (characterisation) => T.fitTables({ characterisation }, ids, rgb, xyz);
  throwsCode(assert, () => fit({ model: 'matrix-3x3', objective: { method: 'psm', parameters: { nope: 1 } } }), 'UNKNOWN_ID');
  throwsCode(assert, () => fit({ model: 'matrix-3x3', objective: { method: 'de2000', settings: { algorithm: 'magic' } } }), 'INVALID_ARGUMENT');
  throwsCode(assert, () => fit('matrix-3x3'), 'INVALID_ARGUMENT');
  throwsCode(assert, () => T.fitTables('{"format": "tristim-recipe", "version": 9}', ids, rgb, xyz), 'RECIPE_VERSION');
  throwsCode(assert, () => T.referenceChart(42, 'D50', '1931'), 'INVALID_ARGUMENT');
  throwsCode(assert, () => T.sampleChart({}, { chart: 'cc24' }, [0, 0, 1, 0, 1, 1, 0, 1]), 'INVALID_ARGUMENT');
  // The module stays usable after every refusal.
  assert.equal(fit({ model: 'matrix-3x3' }).evaluation.fit.status, 'ok');
});

test('recipes: the fit returns the completed recipe, the profile embeds it, JSON round trip', async () => {
  const T = await loadTristim();
  const rgb = Float64Array.from([0.1, 0.2, 0.3, 0.5, 0.4, 0.2, 0.2, 0.6, 0.1, 0.3, 0.3, 0.7, 0.8, 0.7, 0.6, 0.4, 0.1, 0.5]);
  const xyz = Float64Array.from(rgb, (v, i) => 40 * v + 5 * v * v + (i % 3));
  const ids = ['A1', 'A2', 'A3', 'A4', 'A5', 'A6'];
  const recipe = { reference: { chart: 'cc24', illuminant: 'D65' }, sampling: { exclude: ['A6'] },
    characterisation: { model: 'matrix-3x3', objective: { method: 'de2000', parameters: { rms: 1 } } } };
  const r = T.fitTables(recipe, ids, rgb, xyz);
  assert.deepEqual(r.ids, ['A1', 'A2', 'A3', 'A4', 'A5']);
  assert.deepEqual(r.excluded, ['A6 (excluded)']);
  assert.equal(r.evaluation.fit.objective, 'de2000');
  // Completed: every option of the objective is written, with the table's defaults.
  assert.equal(r.recipe.characterisation.objective.settings.algorithm, 'auto');
  assert.equal(r.recipe.characterisation.objective.parameters.rms, 1);
  assert.equal(r.recipe.linearisation.method, 'identity');
  assert.deepEqual(camelKeys(r), []);
  const p = T.profileFromJson(r.profile);  // the profile's document, as its JSON text parses
  assert.deepEqual(p, JSON.parse(r.profile));
  const { format, ...embedded } = p.recipe;
  assert.equal(format, 'tristim-recipe');
  assert.deepEqual(embedded, r.recipe);
  assert.deepEqual(p.model.coefficients.flat(), Array.from(r.evaluation.fit.model.coefficients));
  const text = T.recipeToJson(r.recipe);
  assert.deepEqual(T.recipeFromJson(text), r.recipe);
  assert.deepEqual(T.fitTables(text, ids, rgb, xyz).evaluation.fit.model.coefficients, r.evaluation.fit.model.coefficients);
  throwsCode(assert, () => T.recipeFromJson(text.replace('"version": 1', '"version": 2')), 'RECIPE_VERSION');
  throwsCode(assert, () => T.recipeFromJson(text.replace('"area"', '"aera"')), 'RECIPE_INVALID');
  throwsCode(assert, () => T.completeRecipe({ characterisation: { model: 'nope' } }), 'UNKNOWN_ID');
  throwsCode(assert, () => T.completeRecipe({ sampling: { aera: 0.5 } }), 'INVALID_ARGUMENT');
});
