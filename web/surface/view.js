// Step 1b: the surface correction of the reference (Abed, Berns & Masaoka 2013). The chart's
// reflectances were measured by an instrument in one geometry; the camera sees the chart in
// another. The user picks a row of the engine's surface table and its coefficients (or Saunderson
// geometry presets), sees the reflectances before and after and the ΔE00 the correction makes,
// and — with a second measurement of the chart — the Phase I ranking of every correction. The
// choice is the recipe's `surface` stage (app.session.surface), which the fit step applies.
import { h, field, select, setOptions, showError, clearError, numberValue, fmt, progressBar, readText } from '../lib/ui.js';
import { options as asOptions } from '../lib/catalog.js';
import { optionsForm, completeChoice } from '../lib/options_form.js';
import { figure } from '../plots/common.js';
import { reflectancePlot, patchBarsPlot, beforeAfterBarsPlot } from '../plots/reflectance.js';
import { cssColours } from '../plots/common.js';

const EXAMPLE = { name: 'sg_d8_sci_coolpi.csv', chart: 'sg140-2005', url: 'examples/sg_d8_sci_coolpi.csv',
  label: 'ColorChecker SG (Jan 2007) measured d:8, specular included (COOLPI, Konica Minolta CM-600d)' };

export function mount(section, app) {
  const { engine } = app;
  // The engine's surface table: MethodInfo rows with each row's equation, coefficient names and,
  // for a row of Saunderson geometries, the option each geometry field sets per role.
  const rows = app.catalog.surfaces;
  const presets = app.catalog.surfacePresets ?? [];
  const byId = Object.fromEntries(rows.map((r) => [r.id, r]));
  /// [[geometry field, option name]] a preset sets in `role` for row `id` ([] for a row without geometries).
  const geometryOf = (id, role) => Object.entries(byId[id]?.geometry?.[role] ?? {});
  const takesGeometry = (id) => Object.keys(byId[id]?.geometry ?? {}).length > 0;
  // A correction's citation is its table row's reference (the engine's one place for it).
  const cite = (id) => (byId[id] ? `${byId[id].label}: ${byId[id].reference}` : '');
  const choice = (app.session.surface = completeChoice(byId[app.session.surface?.method] ?? rows[0], app.session.surface));
  // The step's numbers from the engine's rows (surface_option_table: label, unit, bounds, step,
  // default — what fit_surface and the simulated Table IV accept).
  const spec = Object.fromEntries(app.catalog.surfaceOptions.map((o) => [o.name, o]));
  const labelOf = (name) => (spec[name].unit ? `${spec[name].label} (${spec[name].unit})` : spec[name].label);
  const numberBox = (name, role, value) => h('input', { type: 'number', 'data-surface-option': name, 'data-role': role, size: 6,
    min: spec[name].min, max: spec[name].max, step: spec[name].step || 'any', value: value ?? spec[name].default_number, title: spec[name].description });
  const st = (app.session.surfaceSettings ??= { measurement: '45-0', capture: 'diffuse', free: 'capture',
    range: [spec.range_min.default_number, spec.range_max.default_number], patches: '' });

  const methodSel = select(rows.map((r) => ({ value: r.id, label: r.label })), choice.method);
  // Every preset in both pickers (an instrument geometry can describe a capture too: d:8 SCI is a
  // diffuse booth whose camera sees the whole specular component), those of the role first.
  const ofRole = (p, role) => p.role === role || p.role === 'both';
  const presetOptions = (role) => [{ value: '', label: 'custom (the coefficients below)' },
    ...[...presets.filter((p) => ofRole(p, role)), ...presets.filter((p) => !ofRole(p, role))]
      .map((p) => ({ value: p.id, label: `${p.id} — ${p.label}: k1 ${p.geometry.k1}, k2 ${p.geometry.k2}, k_ins ${p.geometry.k_ins}` }))];
  const measSel = select(presetOptions('measurement'), st.measurement);
  const capSel = select(presetOptions('capture'), st.capture);
  const presetBox = h('div', { class: 'controls surface-presets' },
    field('Measurement geometry (the instrument that measured the reference): k1, k2, k_ins of eq (2)', measSel),
    field('Capture geometry (how the camera sees the chart): k1′, k2′, k_ins′ of eq (1)', capSel));
  const presetSource = h('p', { class: 'hint' });
  const formBox = h('div', { class: 'controls surface-options' });
  const about = h('p', { class: 'hint' });
  const note = h('p', { class: 'summary', 'aria-live': 'polite', dataset: { role: 'surface-summary' } });
  const patchInput = h('input', { type: 'text', value: st.patches, placeholder: 'automatic', size: 30 });
  const curveBox = h('div', { class: 'plot-box' });
  const barBox = h('div', { class: 'plot-box' });

  // Second measurement (Phase I ranking)
  const fileInput = h('input', { type: 'file', accept: '.csv,.txt,.cgats,.it8' });
  const exampleBtn = h('button', { type: 'button' }, 'Use the example second measurement');
  const rangeMin = numberBox('range_min', 'surface-range-min', st.range[0]);
  const rangeMax = numberBox('range_max', 'surface-range-max', st.range[1]);
  const compareState = h('p', { class: 'file-state' });
  const progress = progressBar('Fitting surface corrections');
  const rankBox = h('div', { class: 'table-box' });
  const rankPlots = h('div', { class: 'plot-box' });
  const useNote = h('p', { class: 'unavailable', role: 'status', hidden: true, dataset: { role: 'surface-use-note' } });

  // Simulated Table IV
  const cameraSel = select(asOptions(app.catalog.cameras), 'Nikon_D850');
  const noiseInput = numberBox('noise', 'surface-noise');
  const table4Btn = h('button', { type: 'button', 'data-role': 'surface-table4' }, 'Run the simulated Table IV');
  const table4Box = h('div', { class: 'table-box' });

  section.append(
    h('p', {}, 'A chart\'s reference reflectances come from an instrument with its own illumination and viewing geometry '
      + '(d:8 with or without the specular component, 45°:0°); the camera sees the same glossy or semi-gloss surface in another '
      + '(a diffuse booth, lamps at 45°). The surface correction converts the reference to the capture geometry '
      + `(${['saunderson', 'scaler-offset'].map(cite).filter(Boolean).join('; ')}). `
      + 'It applies to a built-in chart\'s spectra; the fit (step 3) uses the corrected reference, and the profile\'s recipe records the choice.'),
    h('div', { class: 'controls' }, field('Surface correction', methodSel, 'A row of the engine\'s surface table')),
    about, presetBox, presetSource, formBox, note,
    h('div', { class: 'controls' }, field('Patches to plot (ids separated by spaces; empty: the darkest, the lightest and the two the correction moves most)', patchInput)),
    curveBox, barBox,
    h('h3', {}, 'Phase I: fit every correction to a second measurement of the chart'),
    h('p', { class: 'hint' }, 'A spectral CSV of the same patches in the other geometry (a wavelength_nm column, one column per patch id, '
      + 'reflectance factors as fractions). Each correction is fitted from the step-1 chart\'s reflectances onto it by minimising the spectral RMS '
      + '(bounded NLopt, Fig. 6 of the paper); CIEDE2000 before and after under the step-1 illuminant and observer.'),
    h('div', { class: 'controls' }, field('Second measurement (spectral CSV)', fileInput), exampleBtn,
      field(labelOf('range_min'), rangeMin), field(labelOf('range_max'), rangeMax)),
    compareState, progress.el, useNote, rankBox, rankPlots,
    h('h3', {}, 'Table IV by simulation: five methods, trained on one chart, tested on a matte chart'),
    h('p', { class: 'hint' }, 'No capture-geometry measurement of a real chart is at hand, so the virtual camera renders the paper\'s experiment: '
      + 'instrument Eye-one 45°:0°, capture a diffuse booth, the Table III coefficients of each chart; Phase II fits (scaler-offset and Saunderson '
      + 'jointly with a 3×3 anchored to a PTFE white, R_w = 0.99), the plain 3×3 and 3×4 matrices, and the corrected 3×3 (eqs 6–13).'),
    h('div', { class: 'controls' }, field('Camera sensitivities', cameraSel), field(labelOf('noise'), noiseInput), table4Btn),
    table4Box);

  const persist = () => { app.save('surface', JSON.parse(JSON.stringify(choice))); app.save('surfaceSettings', { ...st }); };
  const reference = () => app.derived.reference;
  const builtIn = () => reference() && !reference().settings.referenceFile;

  function renderForm() {
    const info = byId[choice.method];
    about.textContent = info.reference ? `${info.label} — ${info.reference}${info.equation ? ` (${info.equation})` : ''}.` : info.label;
    presetBox.hidden = !takesGeometry(choice.method);
    const chosen = [st.measurement, st.capture].map((id) => presets.find((p) => p.id === id)).filter(Boolean);
    presetSource.hidden = presetBox.hidden || !chosen.length;
    presetSource.textContent = chosen.map((p) => `${p.id}: ${p.source}`).join(' · ');
    formBox.replaceChildren(...optionsForm(info, choice, () => { if (takesGeometry(choice.method)) unsetPresets(); changed(); }));
  }
  function unsetPresets() {
    for (const [role, sel] of [['measurement', measSel], ['capture', capSel]]) {
      const p = presets.find((x) => x.id === st[role]);
      if (p && geometryOf(choice.method, role).some(([f, n]) => choice.parameters[n] !== p.geometry[f])) { st[role] = ''; sel.value = ''; }
    }
  }
  function applyPreset(role) {
    const p = presets.find((x) => x.id === st[role]);
    if (!p) return;
    for (const [f, n] of geometryOf(choice.method, role)) choice.parameters[n] = p.geometry[f];
  }

  let previewSeq = 0;
  async function preview() {
    clearError(methodSel);
    const ref = reference();
    if (!ref) { note.textContent = 'The surface step needs a reference (step 1).'; return null; }
    if (!builtIn()) {
      note.textContent = 'The reference of step 1 is an uploaded file: the surface stage corrects a built-in chart\'s spectra, so it stays “none” for this reference.';
      curveBox.replaceChildren(); barBox.replaceChildren();
      return null;
    }
    const seq = ++previewSeq;
    const { chart, illuminant, observer } = ref.settings;
    try {
      const p = await engine.call('surfacePreview', { chart, choice, illuminant, observer });
      if (seq !== previewSeq) return null;
      app.derived.surface = p;
      render(p, ref.settings);
      app.mark('surface', choice.method === 'none' ? '' : 'done');
      return p;
    } catch (e) {
      showError(methodSel, e, 'Surface correction');
      note.textContent = '';
      return null;
    }
  }

  function render(p, rs) {
    const n = p.ids.length;
    let worst = 0, sum = 0;
    for (let i = 0; i < n; i++) { sum += p.dE00[i]; if (p.dE00[i] > p.dE00[worst]) worst = i; }
    note.textContent = choice.method === 'none'
      ? `No correction: the fit uses the reflectances as measured (${n} patches of ${rs.chart}).`
      : `Correction ${p.text}. Between the reference as measured and as corrected: mean ΔE00 ${fmt(sum / n)}, max ${fmt(p.dE00[worst])} (${p.ids[worst]}), `
        + `${n} patches, illuminant ${rs.illuminant}, CIE ${rs.observer} observer. The fit step uses the corrected reference.`;
    note.dataset.mean = String(sum / n);
    const colours = cssColours(p.sRGB);
    const chosen = patchesToPlot(p);
    const curves = [];
    const cmp = compareFor(rs.chart);
    for (const i of chosen) {
      const colour = curveColour(p.XYZ_before[3 * i + 1], colours[i]);
      const wl = p.measured.wavelengths;
      for (const [kind, set] of [['measured', p.measured], ['corrected', p.corrected]]) {
        if (kind === 'corrected' && choice.method === 'none') continue;
        set.values[i].forEach((v, w) => curves.push({ id: p.ids[i], kind, wavelength: wl[w], value: v, colour, last: w === wl.length - 1 }));
      }
      const t = cmp?.targetById?.[p.ids[i]];
      if (t) t.values.forEach((v, w) => curves.push({ id: p.ids[i], kind: 'target', wavelength: t.wavelengths[w], value: v, colour, last: false }));
    }
    curveBox.replaceChildren(figure(reflectancePlot(curves), { name: 'surface-reflectances',
      caption: `Reflectance factors of ${chosen.map((i) => p.ids[i]).join(', ')}: as measured (solid)${choice.method === 'none' ? ' (no correction chosen)' : `, corrected by ${p.text} (dashed)`}${cmp ? ', the second measurement (dotted)' : ''}` }));
    const bars = p.ids.map((id, i) => ({ id, value: p.dE00[i], fill: colours[i], title: `${id}: ΔE00 ${fmt(p.dE00[i])}` }));
    barBox.replaceChildren(choice.method === 'none' ? '' : figure(patchBarsPlot(bars), { name: 'surface-de00',
      caption: `CIEDE2000 between each patch's reference as measured and as corrected (${rs.illuminant}, CIE ${rs.observer}): what the correction changes` }));
  }

  // The typed patch ids as the engine's matching keys (its normalise_patch_id: "A01" is "A1").
  let wanted = [];
  async function readPatches() {
    const ids = patchInput.value.trim().split(/[\s,;]+/).filter(Boolean);
    wanted = ids.length ? await engine.call('patchKeys', { ids }) : [];
  }
  function patchesToPlot(p) {
    if (wanted.length) return wanted.map((id) => p.ids.indexOf(id)).filter((i) => i >= 0);
    const Y = (i) => p.XYZ_before[3 * i + 1];
    const idx = p.ids.map((_, i) => i);
    const dark = idx.reduce((a, b) => (Y(b) < Y(a) ? b : a)), light = idx.reduce((a, b) => (Y(b) > Y(a) ? b : a));
    const moved = idx.filter((i) => i !== dark && i !== light).sort((a, b) => p.dE00[b] - p.dE00[a]).slice(0, 2);
    return [dark, light, ...moved];
  }

  // ---- Phase I ranking ----
  let compare = null;   // {name, chart, fits, targetById}
  const compareFor = (chart) => (compare && compare.chart === chart ? compare : null);

  async function runCompare(file) {
    clearError(fileInput);
    const ref = reference();
    const chart = file.chart ?? (builtIn() ? ref.settings.chart : null);
    if (!chart) { showError(fileInput, Object.assign(new Error('a second measurement is compared with a built-in chart\'s reflectances: choose one in step 1'), { code: 'NO_REFERENCE' }), file.name); return null; }
    for (const c of [rangeMin, rangeMax]) clearError(c);
    try { st.range = [numberValue(rangeMin), numberValue(rangeMax)]; } catch (e) { showError(e.input, e, 'Phase I'); return null; }
    persist();
    const starts = rows.map((r) => {
      const start = completeChoice(r, r.id === choice.method ? choice : null);
      for (const role of Object.keys(r.geometry)) {
        const pr = presets.find((x) => x.id === st[role]);
        if (pr) for (const [f, n] of geometryOf(r.id, role)) start.parameters[n] = pr.geometry[f];
      }
      return { start, free: st.free };
    });
    progress.start('Fitting every surface correction…');
    try {
      const out = await engine.call('surfaceCompare', { chart, text: file.text, fileName: file.name, starts,
        options: { range_min: st.range[0], range_max: st.range[1], observer: ref?.settings.observer ?? '1931' }, illuminant: ref?.settings.illuminant ?? 'D50' },
      { onProgress: (m) => progress.update(m) });
      const targetById = {};
      const f0 = out.fits[0];
      f0.patches.forEach(({ patch: id }, i) => { targetById[id] = { wavelengths: f0.wavelengths, values: f0.target.values[i] }; });   // matching keys, as p.ids
      const best = out.fits.reduce((a, f) => (f.dE00.after.mean < a.dE00.after.mean ? f : a));
      compare = { name: file.name, chart, fits: out.fits, targetById, colours: cssColours(out.sRGB), selected: best.choice.method };
      compareState.textContent = `${file.name}: ${f0.patches.length} patches paired with ${chart} over ${f0.wavelengths[0]}–${f0.wavelengths.at(-1)} nm.`;
      renderRanking();
      await app.save('surfaceCompare', file);
      if (app.derived.surface) render(app.derived.surface, reference().settings);
      return compare;
    } catch (e) {
      showError(fileInput, e, file.name);
      return null;
    } finally { progress.done(); }
  }

  function renderRanking() {
    const { fits, name, chart } = compare;
    const before = fits[0].dE00.before;
    const head = ['correction', 'fitted coefficients', 'spectral RMS (reflectance factor) before → after', 'mean ΔE00', 'max ΔE00', 'status', ''];
    const table = h('table', { class: 'compare surface-ranking' },
      h('caption', {}, `Phase I, ${chart} → ${name}: each correction fitted over ${st.range[0]}–${st.range[1]} nm (minimum spectral RMS). `
        + `Before any correction: mean ΔE00 ${fmt(before.mean)}, max ${fmt(before.max)}.`),
      h('thead', {}, h('tr', {}, head.map((t) => h('th', { scope: 'col' }, t)))),
      h('tbody', {}, fits.map((f) => {
        const use = h('button', { type: 'button' }, 'Use');
        use.addEventListener('click', () => {
          Object.assign(choice, JSON.parse(JSON.stringify(f.choice))); methodSel.value = choice.method; syncPresetsFromChoice(); renderForm(); changed();
          const mine = reference()?.settings.chart;
          useNote.hidden = !mine || mine === compare.chart;
          useNote.textContent = `These coefficients were fitted on ${compare.chart}; step 1's chart is ${mine}. Surface coefficients depend on the material `
            + '(gloss, medium): they carry over only to a chart with the same surface (Abed et al. 2013, Table III).';
        });
        const label = byId[f.choice.method]?.label ?? f.choice.method;
        const tr = h('tr', { dataset: { method: f.choice.method }, class: f.choice.method === compare.selected ? 'selected' : null,
          title: 'Click to plot this correction below' });
        tr.addEventListener('click', (e) => { if (e.target.tagName !== 'BUTTON') { compare.selected = f.choice.method; renderRanking(); } });
        tr.append(
          h('th', { scope: 'row' }, label, byId[f.choice.method]?.equation ? h('small', { class: 'hint' }, ` ${byId[f.choice.method].equation}`) : null),
          h('td', {}, h('code', {}, coefficientText(f)), f.free.length ? h('small', { class: 'hint' }, ` (fitted: ${f.free.join(', ')})`) : null),
          h('td', { dataset: { col: 'rms' } }, `${fmt(f.spectral_rms.before, 4)} → ${fmt(f.spectral_rms.after, 4)}`),
          h('td', { dataset: { col: 'mean' } }, fmt(f.dE00.after.mean)),
          h('td', { dataset: { col: 'max' } }, fmt(f.dE00.after.max)),
          h('td', { title: f.message || null }, f.status),
          h('td', {}, f.choice.method === 'none' ? '' : use));
        return tr;
      })));
    rankBox.replaceChildren(table);
    renderCompareFit(fits.find((f) => f.choice.method === compare.selected) ?? fits[0]);
  }

  /// The selected Phase I fit: curves of the patches it moves most, and ΔE00 before/after per patch.
  function renderCompareFit(f) {
    const ids = f.patches.map((p) => p.patch), n = ids.length, wl = f.wavelengths;
    const idx = ids.map((_, i) => i);
    const worst = (key) => [...idx].sort((a, b) => f.patches[b][key] - f.patches[a][key]).slice(0, 2);
    const Y = (i) => f.measured.values[i].reduce((a, v) => a + v, 0);
    const chosen = [...new Set([...worst('dE00_before'), ...worst('dE00_after'), idx.reduce((a, b) => (Y(b) > Y(a) ? b : a))])];
    const curves = [];
    for (const [k, i] of chosen.entries()) {
      const colour = PALETTE[k % PALETTE.length];
      for (const [kind, set] of [['measured', f.measured], ['corrected', f.corrected], ['target', f.target]]) {
        if (kind === 'corrected' && f.choice.method === 'none') continue;
        set.values[i].forEach((v, w) => curves.push({ id: ids[i], kind, wavelength: wl[w], value: v, colour, last: w === wl.length - 1 }));
      }
    }
    const label = byId[f.choice.method]?.label ?? f.choice.method;
    const bars = f.patches.map((p, i) => ({ id: p.patch, before: p.dE00_before, after: p.dE00_after, fill: compare.colours[i] ?? '#888' }));
    rankPlots.replaceChildren(
      figure(reflectancePlot(curves), { name: 'surface-compare-reflectances',
        caption: `${label}: the two patches farthest apart before and after the correction and the lightest (${chosen.map((i) => ids[i]).join(', ')}) — ${compare.chart} as measured (solid), corrected (dashed), ${compare.name} (dotted)` }),
      figure(beforeAfterBarsPlot(bars), { name: 'surface-compare-de00',
        caption: `CIEDE2000 between ${compare.chart} and ${compare.name} per patch: before (grey) and after (patch colour) ${label}; mean ${fmt(f.dE00.before.mean)} → ${fmt(f.dE00.after.mean)} over ${n} patches` }));
  }
  /// A fitted choice's coefficients (its row's, in the row's order) to 4 significant digits.
  const coefficientText = (f) => {
    if (f.choice.settings?.spectral) return 'per wavelength (spectral)';
    return (byId[f.choice.method]?.coefficients ?? []).map((n) => `${n}=${Number(f.choice.parameters[n]).toPrecision(4)}`).join(', ') || '—';
  };

  function syncPresetsFromChoice() {
    for (const [role, sel] of [['measurement', measSel], ['capture', capSel]]) {
      const names = geometryOf(choice.method, role);
      const p = names.length ? presets.find((x) => names.every(([f, n]) => choice.parameters[n] === x.geometry[f])) : null;
      st[role] = p?.id ?? ''; sel.value = st[role];
    }
  }

  // ---- Table IV ----
  async function runTable4() {
    for (const c of [table4Btn, noiseInput]) clearError(c);
    table4Btn.disabled = true;
    try {
      const noise = numberValue(noiseInput, 0);
      const { methods, cells } = await engine.call('surfaceTable4', { camera: cameraSel.value, illuminant: reference()?.settings.illuminant ?? 'D50', noise });
      const trainings = [...new Set(cells.map((c) => c.training))];
      const cell = (t, m) => cells.find((c) => c.training === t && c.method === m);
      table4Box.replaceChildren(h('table', { class: 'compare surface-table4' },
        h('caption', {}, `Simulated Table IV (${cameraSel.value.split('_').join(' ')}, ${reference()?.settings.illuminant ?? 'D50'}, noise σ ${noiseInput.value}): `
          + 'CIEDE2000 mean / max and ΔE_xyz mean (Y_white = 1) on the matte test chart'),
        h('thead', {}, h('tr', {}, h('th', { scope: 'col' }, 'training chart'), methods.map((m) => h('th', { scope: 'col' }, m)))),
        h('tbody', {}, trainings.map((t) => h('tr', {}, h('th', { scope: 'row' }, t), methods.map((m) => {
          const c = cell(t, m);
          return h('td', { dataset: { method: m }, title: c.ok ? `${c.status}${c.surface !== 'none' ? ` · ${c.surface}` : ''}` : c.message },
            c.ok ? `${fmt(c.dE00.mean)} / ${fmt(c.dE00.max)} · ${fmt(c.dE_xyz.mean, 4)}` : c.error_code);
        }))))));
    } catch (e) { showError(e.input ?? table4Btn, e, 'Table IV'); } finally { table4Btn.disabled = false; }
  }
  table4Btn._errorSlot = h('p', { class: 'field-error', role: 'alert', hidden: true, id: 'table4-error' });
  table4Btn.setAttribute('aria-describedby', 'table4-error');
  table4Btn.after(table4Btn._errorSlot);

  // ---- events ----
  function changed() { persist(); preview(); app.emit('surface', choice); }
  methodSel.addEventListener('change', () => {
    const info = byId[methodSel.value];
    for (const k of Object.keys(choice)) delete choice[k];
    Object.assign(choice, completeChoice(info, null));
    for (const role of Object.keys(info.geometry)) applyPreset(role);
    renderForm(); changed();
  });
  for (const [role, sel] of [['measurement', measSel], ['capture', capSel]]) {
    sel.addEventListener('change', () => { st[role] = sel.value; applyPreset(role); renderForm(); changed(); });
  }
  patchInput.addEventListener('change', async () => {
    st.patches = patchInput.value; persist();
    await readPatches();
    if (app.derived.surface) render(app.derived.surface, reference().settings);
  });
  fileInput.addEventListener('change', async () => {
    const f = fileInput.files[0];
    const text = f && await readText(fileInput, f);
    if (text != null) await runCompare({ name: f.name, text });
  });
  exampleBtn.addEventListener('click', () => loadExample());
  table4Btn.addEventListener('click', runTable4);
  app.on('reference', () => preview());

  async function loadExample() {
    clearError(fileInput);
    try {
      const r = await fetch(EXAMPLE.url);
      if (!r.ok) throw Object.assign(new Error(`${EXAMPLE.url}: HTTP ${r.status}`), { code: 'NOT_FOUND' });
      const out = await runCompare({ name: EXAMPLE.name, chart: EXAMPLE.chart, text: await r.text() });
      if (out) compareState.textContent += ` The example: ${EXAMPLE.label}, against X-Rite's reference spectra of the SG (before Nov 2014; 45°:0°).`;
      return out;
    } catch (e) { showError(fileInput, e, EXAMPLE.name); return null; }
  }

  renderForm();
  if (st.patches) readPatches().then(() => { if (app.derived.surface) render(app.derived.surface, reference().settings); }, () => {});
  const ready = (async () => {   // a kept second measurement is compared again once the reference is back
    await app.views.reference?.ready;
    if (app.session.surfaceCompare) await runCompare(app.session.surfaceCompare);
  })();
  return { preview, runCompare, loadExample, runTable4, ready, choice: () => choice, controls: { methodSel, measSel, capSel, fileInput, exampleBtn, patchInput } };
}

/// Curve colours when patches are told apart by line, not by their own colour (Okabe–Ito, CVD-safe).
const PALETTE = ['#0072B2', '#D55E00', '#009E73', '#CC79A7', '#E69F00', '#56B4E9'];

/// A very light patch drawn in grey (a white line is invisible on the page).
const curveColour = (Y, css) => (Y > 70 ? '#9a9a9a' : css);
