// The Absolute mode's spectral sensitivities panel: eq (7)'s channel areas A_R, A_G, A_B come from
// a camera's R, G, B sensitivities (Guarnera, Bianco & Schettini 2018, section 3.1). Besides the
// 52 built-in cameras: (a) upload a CSV `wavelength_nm,R,G,B` (the engine's parser), or (b)
// estimate them from one photo of a chart with known reflectances under a known illuminant
// (Jiang, Liu, Gu & Süsstrunk 2013; the patch RGB of the chart step, or a patch file; a built-in
// chart and illuminant, or the user's own reflectance and illuminant files as the CLI's
// --reflectances / --illuminant take them), with the residual of the solve; (c) the upload or estimate plotted over a chosen built-in camera's
// curves, with the RMS difference and the area ratios. The chosen set stays in the worker and
// feeds the fit; the profile records it (areas_source).
import { h, field, select, setOptions, showError, clearError, numberValue, download, readText, onFileText } from '../lib/ui.js';
import { figure } from '../plots/common.js';
import { sensitivitiesPlot } from '../plots/sensitivities.js';
import { optionInput, optionLabel } from './option_input.js';
import { excludeFlags } from '../lib/pairs.js';

const fold = (s) => String(s).toLowerCase().replace(/[\s_-]+/g, ' ').trim();
const ratio = (a) => `${(a[0] / a[1]).toFixed(4)} / ${(a[2] / a[1]).toFixed(4)}`;

/// onChoice(which): called with 'upload' | 'estimate' when a set becomes available.
/// The areas' uncertainty as eq (7) uses them (ratios to A_G) and the engine's outside-the-basis warning.
function uncertaintyNote(u) {
  if (!u) return '';
  const pct = (v) => `${(100 * v).toFixed(2)} %`;
  return h('div', {},
    h('p', { 'data-role': 'abs-ssf-uncertainty', dataset: { uRG: u.u[0], uBG: u.u[1] } },
      `Uncertainty of the areas (k = ${u.coverage}, from ${u.loo_bases} leave-one-camera-out bases and K = ${u.components_tried.join(', ')}): `
      + `A_R/A_G ${u.ratio[0].toFixed(4)} ± ${pct(u.u[0])}, A_B/A_G ${u.ratio[1].toFixed(4)} ± ${pct(u.u[1])}. `
      + `Nearest basis camera: ${u.nearest_camera} (RMS ${u.nearest_distance.toFixed(3)}).`),
    u.warnings.length ? h('p', { class: 'warning', role: 'alert', 'data-role': 'abs-ssf-outside', dataset: { codes: u.warnings.join(' ') } },
      `Outside the basis (${u.warnings.join(', ')}): ${u.message}.`) : '');
}

export function mountSensitivities(app, { onChoice }) {
  const { engine } = app;
  const cameras = (app.catalog?.cameras ?? []).map((c) => ({ value: c.id, label: c.name }));
  const charts = (app.catalog?.charts ?? []).map((c) => ({ value: c.id, label: c.name }));
  const illuminants = (app.catalog?.illuminants ?? []).map((i) => ({ value: i.id, label: i.name }));

  // (a) upload
  const fileInput = h('input', { type: 'file', accept: '.csv,.txt,text/csv', 'data-role': 'abs-ssf-file' });
  const fileInfo = h('span', { class: 'file-state', 'data-role': 'abs-ssf-file-info' });
  // (b) estimate
  const sourceSel = select([{ value: 'chart', label: 'the chart step\'s sampled patches (step 2)' }, { value: 'file', label: 'a patch file (id, R, G, B: linear, black-subtracted)' }], 'chart');
  sourceSel.dataset.role = 'abs-ssf-source';
  const patchInput = h('input', { type: 'file', accept: '.csv,.txt,.cgats,.ti3,text/csv', 'data-role': 'abs-ssf-patch-file' });
  const chartSel = select([...charts, { value: 'file', label: 'a reflectance file (spectral CSV or CGATS)…' }], charts.some((c) => c.value === 'cc24') ? 'cc24' : charts[0]?.value);
  chartSel.dataset.role = 'abs-ssf-chart';
  const illSel = select([...illuminants, { value: 'file', label: 'an illuminant file (wavelength_nm, value)…' }], 'D65');
  illSel.dataset.role = 'abs-ssf-illuminant';
  // The user's own chart spectra / light, read by the engine when chosen (absSsfSpectra).
  const spectraInputs = {
    reflectances: h('input', { type: 'file', accept: '.csv,.txt,.cgats,.cie,.ti3,text/csv', 'data-role': 'abs-ssf-reflectance-file' }),
    illuminant: h('input', { type: 'file', accept: '.csv,.txt,text/csv', 'data-role': 'abs-ssf-illuminant-file' }),
  };
  const spectraInfo = {
    reflectances: h('span', { class: 'file-state', 'data-role': 'abs-ssf-reflectance-info' }),
    illuminant: h('span', { class: 'file-state', 'data-role': 'abs-ssf-illuminant-info' }),
  };
  const loaded = { reflectances: null, illuminant: null };   // file names the worker holds
  /// The chart or illuminant as named in file names and messages: its id, or the loaded file's name.
  const named = (sel, kind) => (sel.value === 'file' ? (loaded[kind] ?? 'file').replace(/\.[^.]*$/, '') : sel.value);
  // The estimate's numbers from the engine's rows (listSensitivityOptions: sensitivity_option_table).
  const rows = app.catalog?.sensitivityOptions ?? [];
  const numberBoxes = rows.map((o) => optionInput('sensitivity', o, { class: 'num', 'data-role': `abs-ssf-${o.name}` }));
  const blindBox = h('input', { type: 'checkbox', 'data-role': 'abs-ssf-blind' });
  const estimateBtn = h('button', { type: 'button', 'data-role': 'abs-ssf-estimate' }, 'Estimate the sensitivities (Jiang 2013)');
  estimateBtn._errorSlot = h('p', { class: 'field-error', role: 'alert', hidden: true });
  const estimateInfo = h('div', { class: 'summary', 'data-role': 'abs-ssf-estimate-info', 'aria-live': 'polite' });
  const csvBtn = h('button', { type: 'button', 'data-role': 'abs-ssf-download', hidden: true }, 'Download the estimate (CSV)');
  // (c) comparison
  const showSel = select([], '');
  showSel.dataset.role = 'abs-ssf-show';
  const compareSel = select(cameras, 'Canon_EOS_5D_Mark_II');
  compareSel.dataset.role = 'abs-ssf-compare';
  const plotBox = h('div', { class: 'abs-ssf-plot', 'data-role': 'abs-ssf-plot' });
  const compareInfo = h('div', { class: 'summary', 'data-role': 'abs-ssf-compare-info' });
  const compareBox = h('div', { class: 'abs-ssf-compare-box', hidden: true },
    h('div', { class: 'controls' }, field('Show', showSel), field('Against the built-in camera', compareSel, 'Dashed: its measured curves')), compareInfo, plotBox);

  const filePatchField = field('Patch file', patchInput, 'Linear camera RGB per patch, paired with the chart\'s reflectances by patch id');
  const reflField = h('div', {}, field('Reflectance file', spectraInputs.reflectances, 'One spectrum per patch, named by patch id (as the patches); percent or fractions'), spectraInfo.reflectances);
  const illField = h('div', {}, field('Illuminant file', spectraInputs.illuminant, 'Relative power: wavelength_nm and one value column'), spectraInfo.illuminant);
  const el = h('details', { class: 'abs-ssf', 'data-role': 'abs-ssf' },
    h('summary', {}, 'Sensitivities from a CSV or estimated from one photo of a chart'),
    h('p', { class: 'hint' }, 'Eq (7) divides each channel by its area A_R, A_G, A_B: the sensitivities decide the ratios between the channels. ',
      'Upload measured curves, or estimate them from one photo of a chart whose reflectances are known, under a known light: ',
      'Jiang, Liu, Gu & Süsstrunk (2013) — per channel, a few principal components of the built-in cameras\' curves, fitted to the patches with a smoothness constraint.'),
    h('div', { class: 'abs-ssf-grid' },
      h('fieldset', {}, h('legend', {}, 'Upload'), field('Sensitivities (CSV: wavelength_nm, R, G, B)', fileInput, 'Relative values; one factor for all three channels (their ratios matter)'), fileInfo),
      h('fieldset', {}, h('legend', {}, 'Estimate from one chart photo'),
        field('Patches', sourceSel), filePatchField,
        field('Chart (known reflectances)', chartSel), reflField, field('Illuminant of the photo', illSel), illField,
        numberBoxes.map((i, k) => field(optionLabel(rows[k]), i, rows[k].description)),
        h('label', { class: 'check' }, blindBox, ' leave the compared built-in camera out of the basis (a blind test of the estimate)'),
        h('div', { class: 'buttons' }, estimateBtn, csvBtn), estimateBtn._errorSlot, estimateInfo)),
    compareBox);
  const syncSource = () => { filePatchField.hidden = sourceSel.value !== 'file'; };
  sourceSel.addEventListener('change', syncSource);
  syncSource();
  const syncSpectra = () => { reflField.hidden = chartSel.value !== 'file'; illField.hidden = illSel.value !== 'file'; };
  chartSel.addEventListener('change', syncSpectra);
  illSel.addEventListener('change', syncSpectra);
  syncSpectra();
  for (const [kind, input] of Object.entries(spectraInputs)) {
    onFileText(input, async (text, f) => {
      loaded[kind] = null;
      spectraInfo[kind].textContent = '';
      try {
        const r = await engine.call('absSsfSpectra', { kind, text, name: f.name });
        loaded[kind] = f.name;
        const [lo, hi, n] = r.wavelengths;
        spectraInfo[kind].textContent = kind === 'illuminant'
          ? `${f.name}: ${n} wavelengths, ${lo}–${hi} nm.`
          : `${f.name}: ${r.columns} spectra, ${n} wavelengths, ${lo}–${hi} nm.`;
      } catch (e) { showError(input, e, f.name); }
    });
  }

  const sets = {};   // which -> {label, ssf, areas}
  let csv = null;

  function syncShow(which) {
    setOptions(showSel, Object.entries(sets).map(([v, s]) => ({ value: v, label: s.label })), which ?? showSel.value);
    compareBox.hidden = !Object.keys(sets).length;
  }
  async function plot() {
    const which = showSel.value, set = sets[which];
    if (!set) return;
    try {
      const cam = await engine.call('absSsfCompare', { camera: compareSel.value, which });
      const camLabel = compareSel.selectedOptions[0]?.textContent ?? compareSel.value;
      plotBox.replaceChildren(figure(sensitivitiesPlot({ shown: { label: set.label, ssf: set.ssf }, reference: { label: camLabel, ssf: cam.ssf } }),
        { name: 'absolute-sensitivities', caption: `Spectral sensitivities: ${set.label} (solid) against ${camLabel} (dashed), each set scaled so its largest value is 1` }));
      compareInfo.replaceChildren(h('table', { class: 'metrics' },
        h('thead', {}, h('tr', {}, ['', 'A_R/A_G / A_B/A_G (eq 7)', 'RMS difference, each channel at peak 1'].map((t) => h('th', {}, t)))),
        h('tbody', {},
          h('tr', {}, h('th', {}, set.label), h('td', { 'data-col': 'ratios-shown' }, ratio(set.areas)), h('td', { 'data-col': 'rms', rowspan: 2 }, cam.rms.toFixed(4))),
          h('tr', {}, h('th', {}, camLabel), h('td', { 'data-col': 'ratios-camera' }, ratio(cam.areas))))));
      compareInfo.dataset.rms = cam.rms;
    } catch (e) { showError(compareSel, e, 'Compare'); }
  }
  showSel.addEventListener('change', plot);
  compareSel.addEventListener('change', () => { clearError(compareSel); plot(); });

  function got(which, set) {
    sets[which] = set;
    syncShow(which);
    onChoice(which, set.label);
    return plot();
  }

  onFileText(fileInput, async (text, f) => {
    try {
      const r = await engine.call('absSsfUpload', { text, name: f.name });
      fileInfo.textContent = `${f.name}: R, G, B at ${r.ssf.wavelengths.length} wavelengths, ${r.ssf.wavelengths[0]}–${r.ssf.wavelengths.at(-1)} nm; A_R/A_G ${(r.areas[0] / r.areas[1]).toFixed(4)}, A_B/A_G ${(r.areas[2] / r.areas[1]).toFixed(4)}.`;
      await got('upload', { label: `uploaded ${f.name}`, ssf: r.ssf, areas: r.areas });
    } catch (e) { fileInfo.textContent = ''; showError(fileInput, e, f.name); }
  });

  /// The chart step's samples as {ids, rgb}, the patches the Fit step's flag rule leaves out (the
  /// engine's sample_flag_table; saturated by default) left out.
  function chartPatches() {
    const s = app.derived.sample;
    if (!s?.patches?.length) throw Object.assign(new Error('no sampled chart: place the chart in step 2 first, or choose a patch file'), { code: 'NO_PATCHES' });
    const left = excludeFlags(app.session.fitChoice, app.catalog.sampleFlags);
    const used = s.patches.filter((p) => !p.flags?.some((f) => left.includes(f)));
    const rgb = new Float64Array(3 * used.length);
    used.forEach((p, i) => rgb.set(p.mean, 3 * i));
    return { ids: used.map((p) => p.id), rgb, left: s.patches.length - used.length };
  }

  async function estimate() {
    for (const c of [estimateBtn, patchInput, sourceSel, ...numberBoxes, ...Object.values(spectraInputs)]) clearError(c);
    estimateBtn.disabled = true;
    let target = estimateBtn;
    try {
      for (const [kind, sel] of [['reflectances', chartSel], ['illuminant', illSel]]) {
        if (sel.value === 'file' && !loaded[kind]) {
          target = spectraInputs[kind];
          throw Object.assign(new Error(`choose ${kind === 'illuminant' ? 'an illuminant' : 'a reflectance'} file`), { code: 'NO_SPECTRA' });
        }
      }
      // each box's number (empty: the row's default), under the row's name as SensitivityOptions has it
      const numbers = Object.fromEntries(numberBoxes.map((i, k) => [rows[k].name, numberValue(i, rows[k].default_number)]));
      const msg = { chart: chartSel.value, illuminant: illSel.value,
        options: { ...numbers, exclude_cameras: blindBox.checked ? [compareSel.value] : [] } };
      let left = 0, from;
      if (sourceSel.value === 'file') {
        target = patchInput;
        const f = patchInput.files[0];
        if (!f) throw Object.assign(new Error('choose a patch file'), { code: 'NO_PATCHES' });
        const text = await readText(patchInput, f);
        if (text == null) return null;
        msg.patchFile = { text, name: f.name };
        from = f.name;
      } else {
        target = sourceSel;
        const p = chartPatches();
        Object.assign(msg, { ids: p.ids, rgb: p.rgb });
        left = p.left;
        from = 'the chart step';
      }
      const e = await engine.call('absSsfEstimate', msg);
      const res = e.residual.map((r, c) => `${'RGB'[c]} ${(100 * r).toFixed(2)} %`).join(', ');
      estimateInfo.replaceChildren(
        h('p', { 'data-role': 'abs-ssf-residual', dataset: { residual: e.residual_rms } },
          `${e.patches} patches from ${from}${left ? ` (${left} saturated left out)` : ''}${e.unpaired ? `, ${e.unpaired} without a reflectance in ${named(chartSel, 'reflectances')}` : ''}; `,
          `K = ${e.components} components from ${e.basis_cameras} cameras${blindBox.checked ? ` (${compareSel.selectedOptions[0]?.textContent} left out)` : ''}. Residual (RMS of predicted − measured RGB over RMS measured): ${(100 * e.residual_rms).toFixed(2)} % (${res})`,
          e.clipped ? `; ${e.clipped} negative samples set to 0.` : '.'),
        e.residual_rms > 0.05 ? h('p', { class: 'unavailable' }, 'The residual is large: are the RGB values linear and black-subtracted, the chart and illuminant the ones photographed, and no patch clipped?') : '',
        uncertaintyNote(e.uncertainty));
      csv = e.csv;
      csvBtn.hidden = false;
      await got('estimate', { label: e.label, ssf: e.ssf, areas: e.areas });
      return e;
    } catch (e) {
      const where = e.input ?? (['PATCH_MISMATCH', 'TOO_FEW_PATCHES', 'MISSING_COLUMN', 'NO_PATCHES'].includes(e.code) || target === patchInput
        || Object.values(spectraInputs).includes(target) ? target : estimateBtn);
      showError(where, e, 'Estimate');
      return null;
    } finally { estimateBtn.disabled = false; }
  }
  estimateBtn.addEventListener('click', estimate);
  csvBtn.addEventListener('click', () => { if (csv) download(`sensitivities-Jiang2013-${named(chartSel, 'reflectances')}-${named(illSel, 'illuminant')}.csv`, csv, 'text/csv'); });

  /// The built-in camera matching a series' make and model, for the comparison.
  function cameraHint(make, model) {
    const want = fold(`${make} ${model}`);
    const hit = cameras.find((c) => fold(c.label) === want || fold(c.value) === want);
    if (hit) { compareSel.value = hit.value; plot(); }
  }
  /// The worker restarted: the sets it held are gone.
  function forget() {
    for (const k of Object.keys(sets)) delete sets[k];
    csv = null; csvBtn.hidden = true; estimateInfo.replaceChildren(); fileInfo.textContent = ''; plotBox.replaceChildren();
    for (const kind of Object.keys(loaded)) { loaded[kind] = null; spectraInfo[kind].textContent = ''; spectraInputs[kind].value = ''; }
    syncShow();
  }
  return { el, estimate, cameraHint, forget, sets };
}
