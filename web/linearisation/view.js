// Step 2b: the linearisation stage — from the chart image's stored values (a JPEG, TIFF or PNG is
// display-encoded; a RAW is linear) to values proportional to light. The user picks a row of the
// engine's linearisation table and its options; the step fits it on the paired chart patches as
// the fit will (handlers.js), and shows the three recovered curves against the grey-based ones
// with R² per channel (Shen, Xin, Yang & Lou 2008, Fig 5 and Tables I–II), a warning for a curve
// that is not monotonic over the data, the patches left out as clipped, and the spectral
// characterisation made with it (eqs 26–28): estimated vs measured reflectance of any patch and
// the spectral RMS per patch. The choice is the recipe's `linearisation` stage
// (app.session.linearisation), which the fit step applies.
import { h, field, select, showError, clearError, fmt, progressBar } from '../lib/ui.js';
import { optionsForm, completeChoice } from '../lib/options_form.js';
import { pairData, excludeFlags } from '../lib/pairs.js';
import { figure, cssColours } from '../plots/common.js';
import { oecfPlot } from '../plots/inverse_oecf.js';
import { reflectancePlot, patchBarsPlot } from '../plots/reflectance.js';
import { storedFullScale } from '../fit/view.js';

const SPECTRAL_STYLES = {
  measured: { label: 'measured (the chart\'s reference spectrum)', dash: null },
  estimated: { label: 'estimated from the linearised camera RGB, eq (27)', dash: '6,3' },
};
const CHANNELS = ['R', 'G', 'B'];

export function mount(section, app) {
  const { engine } = app;
  const rows = app.catalog.linearisations;          // the engine's linearisation table (id, label, reference, needs and needs_text, options)
  const byId = Object.fromEntries(rows.map((r) => [r.id, r]));
  const choice = (app.session.linearisation = completeChoice(byId[app.session.linearisation?.method] ?? byId.identity ?? rows[0], app.session.linearisation));
  const st = (app.session.linearisationSettings ??= { patch: '' });
  const spectralInfo = app.catalog.spectral;        // the engine's spectral characterisation row (its training-set options)
  const spectralChoice = (app.session.spectral = completeChoice(spectralInfo, app.session.spectral));

  const methodSel = select(rows.map((r) => ({ value: r.id, label: `${r.label} (${r.id})` })), choice.method);
  const about = h('p', { class: 'hint', dataset: { role: 'linearisation-about' } });
  const formBox = h('div', { class: 'controls linearisation-options' });
  const encoding = h('p', { class: 'summary', dataset: { role: 'linearisation-encoding' } });
  const advice = h('p', { class: 'warning', role: 'status', hidden: true, dataset: { role: 'linearisation-advice' } });
  const progress = progressBar('Fitting the linearisation');
  const summary = h('p', { class: 'summary', 'aria-live': 'polite', dataset: { role: 'linearisation-summary' } });
  const greysNote = h('p', { class: 'hint', dataset: { role: 'linearisation-greys' } });
  const monotonicWarn = h('p', { class: 'warning', role: 'alert', hidden: true, dataset: { role: 'linearisation-monotonic' } });
  const clipWarn = h('p', { class: 'warning', role: 'status', hidden: true, dataset: { role: 'linearisation-clipped' } });
  const extrapWarn = h('p', { class: 'warning', role: 'status', hidden: true, dataset: { role: 'linearisation-extrapolated' } });
  const spectralForm = h('div', { class: 'controls spectral-options' });
  const r2Box = h('div', { class: 'table-box' });
  const curveBox = h('div', { class: 'plot-box' });
  const patchSel = select([], st.patch);
  const spectralNote = h('p', { class: 'summary', dataset: { role: 'linearisation-spectral' } });
  const spectralBox = h('div', { class: 'plot-box' });
  const barsBox = h('div', { class: 'plot-box' });

  section.append(
    h('p', {}, 'A RAW file holds values proportional to the light that reached the sensor; a JPEG, TIFF or PNG holds display-encoded values '
      + '(a tone curve, a gamma). A colorimetric fit needs the former: the linearisation stage recovers each channel\'s inverse opto-electronic '
      + 'conversion function (OECF) — from a stated encoding (gamma, sRGB), from the chart\'s grey patches (ISO 14524 style), or from its '
      + `non-grey patches with known reflectances (${byId.Shen2008?.reference ?? 'the Shen2008 row of the linearisation table'}). `
      + 'The fit (step 3) trains on the linearised camera RGB, and the profile\'s recipe records the choice.'),
    encoding, advice,
    h('div', { class: 'controls' }, field('Linearisation', methodSel, 'A row of the engine\'s linearisation table')),
    about, formBox, progress.el, summary, greysNote, monotonicWarn, clipWarn, extrapWarn, r2Box, curveBox,
    h('h3', {}, 'Spectral characterisation with this linearisation (Shen et al. 2008, eqs 26–28)'),
    h('p', { class: 'hint' }, 'W = [r][û]⁺ (eq 27) maps the linearised camera RGB of the chart\'s patches to their reflectances; estimated and measured '
      + 'reflectance of a patch, and the spectral RMS (eq 28) of every patch (W is fitted on the training patches named below, errors shown for all).'),
    h('p', { class: 'hint', dataset: { role: 'spectral-about' } }, `${spectralInfo.label} — ${spectralInfo.reference}.`),
    spectralForm,
    h('div', { class: 'controls' }, field('Patch to plot', patchSel)),
    spectralNote, spectralBox, barsBox);

  const persist = () => {
    app.save('linearisation', JSON.parse(JSON.stringify(choice))); app.save('linearisationSettings', { ...st });
    app.save('spectral', JSON.parse(JSON.stringify(spectralChoice)));
  };
  const image = () => app.derived.image?.metadata;
  const stored = () => image()?.encoding === 'stored';

  function renderForm() {
    const info = byId[choice.method];
    about.textContent = `${info.label}${info.reference ? ` — ${info.reference}` : ''}; ${info.needs_text}.`;
    formBox.replaceChildren(...optionsForm(info, choice, () => changed()));
  }

  /// The chart image's encoding and what the current choice means for it.
  function renderEncoding() {
    const m = image();
    if (!m) { encoding.textContent = 'No chart image yet (step 2).'; advice.hidden = true; return; }
    encoding.textContent = m.encoding === 'stored'
      ? `The chart image is a ${m.format.toUpperCase()}, ${m.bits} bit per sample, values as stored (full scale ${m.white_level}): not linear.`
        + (m.declared_colour ? ` It declares ${m.declared_colour.split(';').join(', ')} (not applied).` : '')
      : `The chart image is a camera RAW (${[m.make, m.model].filter(Boolean).join(' ') || 'unknown camera'}): black-subtracted sensor values, linear already — “identity” is the right choice.`;
    const msg = m.encoding === 'stored' && choice.method === 'identity'
      ? 'The image is not linear, and “identity” leaves it so: the fit would model the encoding’s curve as colour error. Choose gamma or sRGB if you know the encoding, otherwise Shen2008 (non-grey patches) or a grey-based curve.'
      : m.encoding !== 'stored' && choice.method !== 'identity'
        ? `The image is a RAW, linear already: “${choice.method}” bends linear data. Choose “identity” unless the RAW is known to be non-linear.`
        : '';
    advice.hidden = !msg;
    advice.textContent = msg;
  }

  /// The paired training patches, as the fit step pairs them (the engine's pairing with the fit
  /// step's sample flags, sampling.exclude_flags); `excluded`: the engine's "A3 (saturated)" lines.
  async function training() {
    const s = app.derived.sample, r = app.derived.reference;
    if (!s || !r) return null;
    const exclude_flags = excludeFlags(app.session.fitChoice, app.catalog.sampleFlags);
    return { ...(await pairData(engine, s, r, { exclude_flags })), reference: r };
  }

  let seq = 0, stale = true;
  async function run() {
    const mine = ++seq;
    stale = false;
    clearError(methodSel);
    for (const i of formBox.querySelectorAll('[data-option]')) clearError(i);
    renderEncoding();
    const d = await training().catch((e) => { showError(methodSel, e, 'Pairing'); return undefined; });
    if (d === undefined) return null;
    if (!d) { summary.textContent = 'The linearisation is fitted on the chart\'s patches: it needs a reference (step 1) and a sampled chart (step 2).'; return null; }
    const rs = d.reference.settings;
    const builtIn = !rs.referenceFile;
    progress.start(`Fitting ${choice.method}…`);
    try {
      const out = await engine.call('linearisationFit', {
        choice, ids: d.ids, rgb: d.rgb, xyz: d.xyz, white: Array.from(d.reference.white),
        chart: builtIn ? rs.chart : null, surface: builtIn ? app.session.surface ?? { method: 'none' } : null,
        fullScale: storedFullScale(image()), illuminant: rs.illuminant, observer: rs.observer, spectralChoice,
      }, { onProgress: progress.update });
      if (mine !== seq) return null;
      app.derived.linearisation = out;
      render(out, d);
      app.mark('linearisation', stored() && choice.method === 'identity' ? '' : 'done');
      return out;
    } catch (e) {
      if (mine !== seq || e.code === 'CANCELLED') return null;
      app.derived.linearisation = null;
      // next to the input that caused it: J/K for too few samples, else the method picker
      showError(inputFor(e) ?? methodSel, e, choice.method);
      summary.textContent = `No ${choice.method} linearisation on these patches (see the message above); the fit would fail the same way.`;
      for (const b of [greysNote, r2Box, curveBox, spectralBox, barsBox, spectralNote, patchSel]) b.replaceChildren();
      app.mark('linearisation', '');
      monotonicWarn.hidden = clipWarn.hidden = extrapWarn.hidden = true;
      return null;
    } finally { if (mine === seq) progress.done(); }
  }

  /// The option an error is about (its error slot), or null for the method picker.
  function inputFor(e) {
    const opt = (name) => formBox.querySelector(`[data-option="${name}"]`);
    if (e.code === 'TOO_FEW_PATCHES') return opt('J') ?? opt('K');
    if (e.code === 'MISSING_COLUMN' && choice.settings.basis === 'user') return opt('basis');
    if (/\bgrey\b/i.test(e.message) && ['UNKNOWN_ID', 'PATCH_MISMATCH', 'INVALID_ARGUMENT'].includes(e.code)) return opt('grey');
    return null;
  }

  function render(out, d) {
    const { lin, comparison: cmp } = out;
    const warnings = lin.message ? lin.message.split('; ') : [];
    const clipped = warnings.filter((w) => /clipped/.test(w));
    const noted = warnings.filter((w) => !/clipped/.test(w) && !/not increasing/.test(w) && !/^extrapolated /.test(w));
    const left = d.excluded;   // the engine's lines: "A3 (saturated)", "D1 (outside the frame)"
    summary.dataset.method = lin.method;
    summary.textContent = `${byId[lin.method]?.label ?? lin.method}: `
      + (lin.fitted.length ? `fitted on ${lin.fitted.length} of ${d.ids.length} paired patches` : `a stated curve (nothing fitted), applied to the ${d.ids.length} paired patches`)
      + (lin.full_scale > 1 ? `, x = stored value / ${fmt(lin.full_scale, lin.full_scale % 1 ? 2 : 0)}` : '')
      + `. Options: ${optionText(lin)}.`
      + (noted.length ? ` Notes: ${noted.join('; ')}.` : '');
    greysNote.textContent = cmp?.greys?.length
      ? `Grey patches (${cmp.greys.length}): ${cmp.greys.join(', ')} — ${cmp.reason || 'given'}.`
      : `No grey patches to compare with${cmp?.error ? `: ${cmp.error.message} (${cmp.error.code})` : cmp?.reason ? ` (${cmp.reason})` : ''}.`;
    monotonicWarn.hidden = lin.monotonic;
    monotonicWarn.textContent = lin.monotonic ? '' : `Not monotonic over the data range: ${warnings.filter((w) => /not increasing/.test(w)).join('; ') || lin.message}. `
      + 'A decreasing stretch maps two exposures to one value; try a lower order K or another method.';
    clipWarn.hidden = !clipped.length && !left.length;
    clipWarn.textContent = [left.length ? `Left out of the fit (step 2): ${left.join(', ')}.` : '',
      ...clipped.map((w) => `${w[0].toUpperCase()}${w.slice(1)}.`),
      stored() && image().bits === 8 && (clipped.length || left.length) ? 'An 8-bit image keeps nothing above 255: expose the chart so that its white stays below the top code.' : '']
      .filter(Boolean).join(' ');
    renderExtrapolated(lin);
    renderR2(lin, cmp);
    renderCurves(out, d);
    renderSpectral(out.spectral, d);
  }

  /// The patches whose stored value lies outside the fitted range of a channel (the engine's
  /// lin.extrapolated: Shen2008 fits on the non-grey patches and is applied to all).
  function renderExtrapolated(lin) {
    const list = lin.extrapolated ?? [];
    extrapWarn.hidden = !list.length;
    if (!list.length) { extrapWarn.replaceChildren(); return; }
    const byPatch = new Map();
    for (const e of list) byPatch.set(e.patch, [...(byPatch.get(e.patch) ?? []), e]);
    const pct = (v) => `${v > 0 ? '+' : ''}${fmt(100 * v, 1)} %`;
    extrapWarn.replaceChildren(
      `Extrapolated: ${byPatch.size} patch${byPatch.size > 1 ? 'es lie' : ' lies'} outside the range the curve was fitted on `
        + `(${lin.fitted.length} patches), so the curve is extended beyond its data there. By how much, relative to the end of the fitted range passed: `,
      ...[...byPatch].flatMap(([id, es], k) => [k ? '; ' : '', h('span', { dataset: { patch: id } },
        `${id} ${es.map((e) => `${CHANNELS[e.channel]} ${pct(e.relative)}`).join(', ')}`)]),
      '. Their linear values are less certain than the fitted patches\'.');
  }

  function renderR2(lin, cmp) {
    const self = cmp?.source === 'self';
    const r2 = cmp?.r_squared ?? [NaN, NaN, NaN];
    const what = self ? 'R² of the fit through the greys (coefficient of determination)'
      : `R² between the recovered and the grey-based OECF (squared correlation over the greys' range, Shen et al. Tables I–II; grey-based: degree ${cmp?.K ?? '–'})`;
    r2Box.replaceChildren(h('p', { class: 'hint' }, what + (cmp?.source === 'page' ? '. Computed here with the engine\'s grey-polynomial, by the definition the engine uses for Shen2008.' : '.')),
      h('table', { class: 'compare linearisation-r2' },
      h('caption', {}, 'R² per channel'),
      h('thead', {}, h('tr', {}, h('th', { scope: 'col' }, 'channel'), h('th', { scope: 'col' }, 'R²'), h('th', { scope: 'col' }, 'fitted range of x'), h('th', { scope: 'col' }, 'monotonic'))),
      h('tbody', {}, CHANNELS.map((c, i) => h('tr', { dataset: { channel: c } },
        h('th', { scope: 'row' }, c),
        h('td', { dataset: { col: 'r2', value: String(r2[i]) } }, Number.isFinite(r2[i]) ? r2[i].toFixed(4) : '–'),
        h('td', {}, `${fmt(lin.domain[i][0], 3)} – ${fmt(lin.domain[i][1], 3)}`),
        h('td', {}, lin.monotonic ? 'yes' : (lin.message.includes(`channel ${c}: the curve is not increasing`) ? 'NO' : 'yes')))))));
  }

  function renderCurves(out, d) {
    const { lin, comparison: cmp } = out;
    const rows = [];
    const engineCurves = cmp?.source === 'engine' ? cmp.curves : null;
    CHANNELS.forEach((c, i) => {
      if (engineCurves) {
        const s = engineCurves[i];
        s.x.forEach((x, k) => { rows.push({ channel: c, kind: 'estimated', x, y: s.estimated[k] }); rows.push({ channel: c, kind: 'grey-based', x, y: s.grey_based[k] }); });
      } else if (cmp?.curves) {
        const s = cmp.curves[i];
        s.x.forEach((x, k) => rows.push({ channel: c, kind: 'estimated', x, y: s.estimated[k] }));
        s.x_grey.forEach((x, k) => rows.push({ channel: c, kind: 'grey-based', x, y: s.grey_based[k] }));
      } else {
        const s = out.curves[i];
        const top = s.linear[s.linear.length - 1] || 1;
        s.x.forEach((x, k) => rows.push({ channel: c, kind: 'estimated', x, y: s.linear[k] / top }));
      }
    });
    const fs = lin.full_scale;
    const ticks = [];
    d.ids.forEach((id, k) => CHANNELS.forEach((c, i) => ticks.push({ channel: c, id, x: d.rgb[3 * k + i] / fs })));
    const scaled = engineCurves ? 'both scaled to 1 at the brightest fitted patch' : cmp?.curves ? 'both scaled to 1 at the top of the greys\' range' : 'scaled to 1 at the top of its range';
    curveBox.replaceChildren(figure(oecfPlot(rows, ticks), { name: 'linearisation-oecf',
      caption: `Inverse OECF per channel (as Shen et al. 2008 Fig 5): ${byId[lin.method]?.label ?? lin.method} (solid)`
        + (cmp?.curves || engineCurves ? ' against the grey-based curve (dashed)' : '') + `, ${scaled}. `
        + `Ticks below: each patch's stored value / ${fmt(fs, fs % 1 ? 2 : 0)} per channel (R, G, B rows).` }));
  }

  function renderSpectral(sp, d) {
    if (!sp) {
      spectralNote.textContent = 'Spectral characterisation needs the reflectances of a built-in chart (step 1); the reference of step 1 is a file of XYZ.';
      spectralBox.replaceChildren(); barsBox.replaceChildren(); patchSel.replaceChildren();
      return;
    }
    if (sp.error) {
      spectralNote.textContent = `No spectral characterisation: ${sp.error.message} (${sp.error.code}).`;
      spectralBox.replaceChildren(); barsBox.replaceChildren();
      return;
    }
    const ids = sp.est_ids;
    const current = ids.includes(st.patch) ? st.patch : worstPatch(sp);   // the user's patch, else the worst estimated
    patchSel.replaceChildren(...ids.map((id) => h('option', { value: id, selected: id === current }, id)));
    patchSel.value = current;
    spectralNote.dataset.rmsMean = String(sp.summary.spectral_rms_mean);
    spectralNote.dataset.trainingSet = sp.training_set;
    spectralNote.dataset.trainingPatches = String(sp.training_patches);
    const left = sp.ids.filter((id) => !sp.training_ids.includes(id));
    spectralNote.textContent = `W trained on ${sp.training_patches} of ${sp.ids.length} patches (${sp.training_set === 'non-grey'
      ? `the non-grey ones, as the paper does; greys left out: ${left.join(', ') || 'none found'}` : 'all, greys included'}). `
      + `All ${sp.ids.length} patches: spectral RMS mean ${fmt(sp.summary.spectral_rms_mean, 4)}, max ${fmt(sp.summary.spectral_rms_max, 4)} (reflectance factor); `
      + `CIEDE2000 of the estimated reflectances mean ${fmt(sp.summary.dE00_mean)}, max ${fmt(sp.summary.dE00_max)} `
      + `(${d.reference.settings.illuminant}, CIE ${d.reference.settings.observer}).`;
    drawPatch(sp, current);
    const colours = colourOf(d);
    const at = new Map(sp.ids.map((id, i) => [id, i]));
    const bars = sp.ids.map((id) => ({ id, value: sp.rms[at.get(id)], fill: colours.get(id) ?? '#999',
      title: `${id}: spectral RMS ${fmt(sp.rms[at.get(id)], 4)}, ΔE00 ${fmt(sp.dE00[at.get(id)])}` }));
    barsBox.replaceChildren(figure(patchBarsPlot(bars, { label: '↑ spectral RMS (reflectance factor)' }), { name: 'linearisation-spectral-rms',
      caption: 'Spectral RMS between estimated and measured reflectance per patch, eq (28) (bars in the patch\'s colour)' }));
  }
  function drawPatch(sp, id) {
    const k = sp.est_ids.indexOf(id);
    if (k < 0) { spectralBox.replaceChildren(); return; }
    const colour = '#333';
    const curves = [];
    sp.measured.values[k].forEach((v, w, a) => curves.push({ id, kind: 'measured', wavelength: sp.measured.wavelengths[w], value: v, colour, last: w === a.length - 1 }));
    sp.estimated[k].forEach((v, w) => curves.push({ id, kind: 'estimated', wavelength: sp.wavelengths[w], value: v, colour, last: false }));
    const i = sp.ids.indexOf(id);
    spectralBox.replaceChildren(figure(reflectancePlot(curves, { styles: SPECTRAL_STYLES }), { name: 'linearisation-reflectance',
      caption: `Patch ${id}: measured reflectance (solid) and estimated from the linearised camera RGB (dashed); spectral RMS ${fmt(sp.rms[i], 4)}, ΔE00 ${fmt(sp.dE00[i])}` }));
  }
  const worstPatch = (sp) => sp.ids[sp.rms.reduce((a, v, i, r) => (v > r[a] ? i : a), 0)];
  /// Display colour of each patch (the reference's sRGB), by id.
  function colourOf(d) {
    const r = d.reference;
    const css = r.sRGB ? cssColours(r.sRGB) : [];
    return new Map(r.ids.map((id, i) => [id, css[i]]));
  }

  // ---- events ----
  function changed() { persist(); app.emit('linearisation', choice); schedule(); }
  function schedule() { stale = true; if (!section.hidden) run(); else renderEncoding(); }
  methodSel.addEventListener('change', () => {
    const info = byId[methodSel.value];
    for (const k of Object.keys(choice)) delete choice[k];
    Object.assign(choice, completeChoice(info, null));
    renderForm(); changed();
  });
  patchSel.addEventListener('change', () => {
    st.patch = patchSel.value; persist();
    const sp = app.derived.linearisation?.spectral;
    if (sp && !sp.error) drawPatch(sp, patchSel.value);
  });
  for (const topic of ['sample', 'reference', 'surface']) app.on(topic, schedule);
  app.on('step', (s) => { if (s === 'linearisation' && stale) run(); });

  spectralForm.replaceChildren(...optionsForm(spectralInfo, spectralChoice, () => { persist(); schedule(); }));
  renderForm();
  renderEncoding();
  return { run, choice: () => choice, controls: { methodSel, patchSel, formBox } };
}

/// "K=2, J=8, L=2, basis=munsell1269" (every option the method has).
const optionText = (c) => [...Object.entries(c.parameters ?? {}), ...Object.entries(c.settings ?? {})]
  .map(([k, v]) => `${k}=${v === '' ? 'automatic' : v}`).join(', ') || 'none';
