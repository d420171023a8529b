// The Lab mode's exercises, one panel each: a short text beside each plot, the CLI equivalent and
// the engine's numbers (web/lab/handlers.js; core/include/tristim/lab/exercises.hpp).
//  1. Spectra to colour: a patch's reflectance, the stimulus under three lights, its XYZ, Lab and
//     xy for the 1931 and 1964 observers.
//  2. Why a 3×3 is not enough: the Luther condition, training vs leave-one-out, over-fitting.
import { h, field, select, showError, clearError, numberValue, fmt } from '../lib/ui.js';
import { options } from '../lib/catalog.js';
import { labPanel } from './panel.js';
import { figure } from '../plots/common.js';
import { stimulusPlot, overfitPlot } from './plots.js';
import { labOptionBoxes } from './options.js';

export function spectraPanel(app) {
  const ids = app.catalog.layouts.cc24?.patches?.map((p) => p.id) ?? ['A1'];
  const patchSel = select(ids, 'C3');
  const btn = h('button', { type: 'button', 'data-action': 'lab-ex1' }, 'Compute');
  const out = h('div', { 'data-lab': 'ex1' });
  const cli = h('pre', { class: 'cli' });
  async function run() {
    clearError(btn);
    cli.textContent = '';
    let e;  // the exercise's lights and observers are the engine's (lab_spectra_to_colour)
    try { e = await app.engine.call('labSpectra', { chart: 'cc24', patch: patchSel.value }); } catch (err) { showError(btn, err, 'Exercise 1'); return null; }
    cli.textContent = e.illuminants.map((i) => `tristim reference --chart cc24 --illuminant ${i} --observer 1964   # row ${patchSel.value}`).join('\n');
    const rows = e.rows.map((r) => h('tr', {}, h('td', {}, r.illuminant), h('td', {}, r.observer),
      ...[...r.XYZ, ...r.Lab, r.x, r.y].map((v, i) => h('td', { class: 'num' }, fmt(v, i < 6 ? 2 : 4)))));
    out.replaceChildren(
      figure(stimulusPlot(e), { name: `lab-ex1-${e.patch}`, caption: `ColorChecker ${e.patch}: reflectance and colour stimulus` }),
      h('p', { class: 'explain' },
        'The eye (or a camera) never sees the reflectance: it sees R(λ)·S(λ). Under A the stimulus leans to the red end, '
        + 'under F11 it is three narrow spikes. XYZ integrates the stimulus against the CMFs (CIE 15: X = k Σ R S x̄, '
        + 'k = 100 / Σ S ȳ); CIELAB divides by the light\'s own white first, the simplest chromatic adaptation, so '
        + 'L*a*b* moves far less than xy between lights. The 1964 (10°) observer gives other numbers for the same stimulus.'),
      h('div', { class: 'table-scroll' }, h('table', { class: 'data', 'data-lab': 'ex1-table' },
        h('thead', {}, h('tr', {}, ...['illuminant', 'observer', 'X', 'Y', 'Z', 'L*', 'a*', 'b*', 'x', 'y'].map((t) => h('th', { scope: 'col' }, t)))),
        h('tbody', {}, ...rows))));
    return e;
  }
  btn.addEventListener('click', run);
  const panel = labPanel({ id: 'ex1', title: 'Exercise 1 · Spectra to colour: integration, observers, illuminants, adaptation',
    controls: [field('ColorChecker patch', patchSel)], buttons: [btn], cli, hint: 'The same on the command line (the patch\'s row):' }, out);
  return { panel, run, params: { patch: patchSel } };
}

export function overfitPanel(app) {
  const cams = [{ value: 'cmf', label: 'The CIE 1931 CMFs (a Luther camera)' }, ...options(app.catalog.cameras)];
  const camSel = select(cams, 'Canon_EOS_5D_Mark_II');
  const boxes = labOptionBoxes(app);
  const noiseIn = boxes.box('overfit.noise', 'ex2-noise');
  const btn = h('button', { type: 'button', 'data-action': 'lab-ex2' }, 'Fit and compare');
  const out = h('div', { 'data-lab': 'ex2' });
  const cli = h('pre', { class: 'cli' });
  async function run() {
    clearError(btn);
    let noise;
    try { noise = numberValue(noiseIn); } catch (e) { showError(btn, e, 'Exercise 2'); return null; }
    cli.textContent = `tristim lab overfit --camera ${camSel.value} --illuminant D65 --noise ${noise}`;
    let rows;
    try { rows = await app.engine.call('labOverfit', { camera: camSel.value, illuminant: 'D65', noise }); } catch (e) { showError(btn, e, 'Exercise 2'); return null; }
    const body = rows.map((r) => h('tr', {}, h('td', {}, r.model), h('td', {}, r.training), h('td', { class: 'num' }, String(r.terms)),
      h('td', { class: 'num' }, String(r.patches)),
      ...(r.ok ? [r.train_dE00, r.loo_dE00, r.test_dE00].map((v) => h('td', { class: 'num' }, fmt(v, 3)))
        : [h('td', { colspan: 3 }, `refused: ${r.error_code} (more terms than patches)`)])));
    out.replaceChildren(
      figure(overfitPlot(rows, 'cc24'), { name: 'lab-ex2-cc24', caption: 'Trained on the 24 patches of the ColorChecker Classic' }),
      h('p', { class: 'explain' },
        'With the CMFs as the camera, a 3×3 is exact: the Luther condition. A real camera leaves an error no matrix removes. '
        + 'More terms always lower the training error — 22 terms on 24 patches nearly interpolate them, noise included — '
        + 'while leave-one-out and the 1269 Munsell chips the fit never saw show the price: over-fitting. 35 terms on 24 '
        + 'patches have infinitely many exact fits and are refused; on the 140 patches of the SG they fit and stay moderate.'),
      figure(overfitPlot(rows, 'sg140'), { name: 'lab-ex2-sg140', caption: 'Trained on the 140 patches of the ColorChecker SG' }),
      h('div', { class: 'table-scroll' }, h('table', { class: 'data', 'data-lab': 'ex2-table' },
        h('thead', {}, h('tr', {}, ...['model', 'training', 'terms', 'patches', 'training ΔE00', 'leave-one-out ΔE00', 'Munsell ΔE00'].map((t) => h('th', { scope: 'col' }, t)))),
        h('tbody', {}, ...body))));
    return rows;
  }
  btn.addEventListener('click', run);
  const panel = labPanel({ id: 'ex2', title: 'Exercise 2 · Why a 3×3 is not enough: the Luther condition and over-fitting',
    controls: [field('Camera', camSel), boxes.field(noiseIn)], buttons: [btn], cli }, out);
  return { panel, run, params: { camera: camSel, noise: noiseIn } };
}
