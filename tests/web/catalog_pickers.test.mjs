// The page owns no method knowledge (issue 43): every picker it shows — each <select>, the model and
// objective checklists, and the options form of every method row — lists what the engine's tables
// list, with the tables' ids and labels. The expected rows come from the wasm module loaded here in
// node (tests/wasm/load.mjs), not from the page's copy of the catalog, so a picker whose list,
// order, labels, option bounds or families drift from the engine fails; so does a number input of
// the custom grid, the sampled area, the Lab, the Surface step, the Absolute mode or the light trap whose label, unit, bounds, step or default is
// not the table's (or, for a row whose min is exclusive, whose box accepts min). A <select> the registry
// below does not know fails too: a new picker states where its choices come from.
import test from 'node:test';
import assert from 'node:assert/strict';
import { screenshot } from './harness.mjs';
import { openPage, step } from './journey.mjs';
import { loadTristim } from '../wasm/load.mjs';

/// [{value, label}] of the engine's rows: `label(row)` the text the picker must show.
const rows = (list, label = (r) => r.label ?? r.name) => list.map((r) => ({ value: String(r.id), label: label(r) }));

/// Every <select> of the page outside an options form: its step, its field's label, its options.
const selects = (page) => page.$$eval('select:not([data-option])', (els) => els.map((s) => ({
  step: s.closest('section[data-step]')?.dataset.step,
  name: (s.labels?.[0]?.textContent ?? s.getAttribute('aria-label') ?? s.dataset.role ?? '').trim(),
  options: [...s.options].map((o) => ({ value: o.value, label: o.textContent, title: o.title })),
})));

/// The controls of an options form (data-option) in `scope`, as the form built them.
const formControls = (page, scope) => page.$$eval(`${scope} [data-option]`, (els) => els.map((el) => ({
  name: el.dataset.option,
  tag: el.tagName.toLowerCase(),
  type: el.type,
  label: (el.labels?.[0]?.textContent ?? '').trim(),
  min: el.getAttribute('min'), max: el.getAttribute('max'), step: el.getAttribute('step'),
  choices: el.tagName === 'SELECT' ? [...el.options].map((o) => [o.value, o.textContent]) : null,
})));

/// Each OptionSpec of `info` against the form's controls: one control per option, of its type,
/// labelled with the option's label, bounded by its min/max (none when min == max), nothing else.
function checkForm(where, info, controls, wrong) {
  const want = info.options.map((o) => o.name);
  const got = controls.map((c) => c.name);
  if (JSON.stringify(got) !== JSON.stringify(want)) { wrong.push(`${where}: controls ${got.join(',')} for options ${want.join(',')}`); return; }
  info.options.forEach((o, k) => {
    const c = controls[k];
    const say = (what) => wrong.push(`${where} option ${o.name}: ${what}`);
    if (c.label !== o.label) say(`label '${c.label}', the table says '${o.label}'`);
    if (o.type === 'boolean' && c.type !== 'checkbox') say(`a ${c.type} for a boolean`);
    if (o.type === 'text' && c.type !== 'text') say(`a ${c.type} for a text`);
    if (o.type === 'choice' && JSON.stringify(c.choices) !== JSON.stringify(o.choices.map((x) => [x, x]))) say(`choices ${JSON.stringify(c.choices)}, the table has ${o.choices}`);
    if (o.type === 'number' || o.type === 'integer') {
      if (c.type !== 'number') say(`a ${c.type} for a ${o.type}`);
      const bounded = o.max > o.min;
      if ((bounded ? String(o.min) : null) !== c.min || (bounded ? String(o.max) : null) !== c.max) say(`bounds [${c.min}, ${c.max}], the table's [${o.min}, ${o.max}]`);
      if (c.step !== (o.type === 'integer' ? '1' : 'any')) say(`step ${c.step} for a ${o.type}`);
    }
  });
}

/// Picks `value` in the <select> labelled `name` on step `stepName` (as a user's change would).
const choose = (page, stepName, name, value) => page.evaluate(([st, n, v]) => {
  const s = [...document.querySelectorAll(`#step-${st} select`)].find((x) => x.labels?.[0]?.textContent.trim() === n);
  s.value = v;
  s.dispatchEvent(new Event('change'));
}, [stepName, name, value]);

test('every picker lists the engine catalog\'s ids and labels, and every options form its option table', async () => {
  const T = await loadTristim();
  const charts = T.listCharts(), cameras = T.listCameras(), models = T.listModels(), families = T.listModelFamilies();
  const presets = T.listSurfacePresets();
  // key: "<step>/<field label>" -> the options the picker must show, or {owned: why} for a picker
  // whose choices are the page's own (presentation, or data of this session rather than a table).
  const registry = {
    'reference/Chart': rows(charts),
    'reference/Illuminant': rows(T.listIlluminants()),
    'reference/Observer': rows(T.listObservers()),
    'surface/Surface correction': rows(T.listSurfaceCorrections()),
    'surface/Camera sensitivities': rows(cameras),
    'surface/Measurement geometry (the instrument that measured the reference): k1, k2, k_ins of eq (2)': { owned: 'custom, then the presets (checked below)' },
    'surface/Capture geometry (how the camera sees the chart): k1′, k2′, k_ins′ of eq (1)': { owned: 'custom, then the presets (checked below)' },
    'images/Flat-field correction': rows(T.listFlatFieldModes()),
    // The layouts the engine has, named after the built-in charts; 'custom' is named by the page.
    'images/Chart layout': T.listChartLayouts().map((id) => ({ value: id, label: charts.find((c) => c.id === id)?.name ?? null })),
    // An extra chart image (issue 48): the layouts, as the first image's (a custom grid takes a reference file).
    'images/Its chart (layout and reference)': T.listChartLayouts().map((id) => ({ value: id, label: charts.find((c) => c.id === id)?.name ?? null })),
    'images/Patches of the same colour': { owned: 'the recipe\'s two duplicates rules, once and each (docs/multi-image.md)' },
    'linearisation/Linearisation': rows(T.listLinearisations(), (r) => `${r.label} (${r.id})`),
    'linearisation/Patch to plot': { owned: 'the patches of this session\'s chart' },
    'apply/Apply to': { owned: 'where the image comes from (a UI choice)' },
    'apply/Colour map for Y': { owned: 'display colour maps (d3)' },
    'absolute/Colour map': { owned: 'display colour maps (d3)' },
    // The engine's sensitivity choices in its order: 'none' itself, 'given' as this session's sets
    // (none at start), 'camera' as the built-in cameras.
    'absolute/Sensitivities for A_R, A_G, A_B': T.listAbsoluteSensitivities().flatMap((r) => (r.id === 'none' ? [{ value: r.id, label: r.label }] : r.id === 'camera' ? rows(cameras) : [])),
    'absolute/Patches': { owned: 'where the patches come from (a UI choice)' },
    'absolute/Chart (known reflectances)': { owned: 'the built-in charts and a file (checked below)' },
    'absolute/Illuminant of the photo': { owned: 'the built-in illuminants and a file (checked below)' },
    'absolute/Show': { owned: 'the sets of this session' },
    'absolute/Against the built-in camera': rows(cameras),
    'absolute/Colour matrix': { owned: 'the Guarnera2018 family of the model table (checked below)' },
    'absolute/Exposure fusion': rows(T.listFusionModes()),
    'absolute/Example: light on the chart': rows(T.listExampleLights()),
    'absolute/Example: colour training': rows(T.listExampleTrainings()),
    'absolute/White of the test figures': rows(T.listAbsoluteWhiteRules()),
    'export/Second profile (dual-illuminant)': { owned: 'the profiles of this session' },
    'export/IDT from': { owned: 'where the IDT\'s data come from (a UI choice)' },
    'export/Camera': rows(cameras),
    'export/Illuminant': rows(T.listIlluminants()),
    'export/Chromatic adaptation': { owned: 'the adaptations tristim idt takes (each checked against the engine below)' },
    'lab/Camera': { owned: 'the built-in cameras, after the CMFs in exercise 2 (checked below)' },
    'lab/Chart': [...T.listLabCharts()].map((id) => ({ value: id, label: charts.find((c) => c.id === id)?.name ?? null })),
    'lab/Illuminant': rows(T.listIlluminants()),
    'lab/ColorChecker patch': { owned: 'the patches of the CC24 (exercise 1)' },
    'lab/File': rows(T.listLabFileKinds()),
    'lab/OECF (TIFF, JPEG)': { owned: 'the renderer\'s OECFs, labelled by their ids (checked below)' },
    'lab/First light (match)': rows(T.listIlluminants()),
    'lab/Second light': rows(T.listIlluminants()),
    'lab/Observer': rows(T.listObservers()),
    'lab/Match for': rows(T.listMetamerMatches()),
    'lab/Munsell chip': { owned: 'the engine\'s Munsell ids, loaded when the picker opens (checked below)' },
    'lab/or Munsell chips': { owned: 'the engine\'s Munsell ids for a chart of one\'s own, loaded when the picker opens (checked below)' },
    'lab/Training chart': rows(T.listShenTrainings()),
    'lab/Light on the scene': rows(T.listExampleLights()),
  };
  const b = await openPage();
  try {
    const { page } = b;
    const wrong = [];
    const found = await selects(page);
    const seen = new Set();
    for (const s of found) {
      const key = `${s.step}/${s.name}`;
      seen.add(key);
      const want = registry[key];
      if (!want) { wrong.push(`${key}: a picker the test does not know (options ${s.options.map((o) => o.value).join(', ')})`); continue; }
      if (want.owned) continue;
      const got = s.options.map(({ value, label }) => ({ value, label }));
      const expected = want.map((o) => ({ value: o.value, label: o.label ?? got.find((g) => g.value === o.value)?.label }));
      if (JSON.stringify(got) !== JSON.stringify(expected)) wrong.push(`${key}: shows ${JSON.stringify(got)}, the engine ${JSON.stringify(expected)}`);
    }
    for (const key of Object.keys(registry)) if (!seen.has(key)) wrong.push(`${key}: not on the page (the registry is stale)`);

    // Pickers that add the page's own entries around an engine table: the table's part is exact.
    const byKey = Object.fromEntries(found.map((s) => [`${s.step}/${s.name}`, s.options]));
    const tail = (key, n) => JSON.stringify((byKey[key] ?? []).slice(-n).map(({ value, label }) => ({ value, label })));
    const head = (key, n) => JSON.stringify((byKey[key] ?? []).slice(0, n).map(({ value, label }) => ({ value, label })));
    if (tail('absolute/Sensitivities for A_R, A_G, A_B', cameras.length) !== JSON.stringify(rows(cameras))) wrong.push('absolute sensitivities: not the built-in cameras');
    // Its hint is the chosen row's label and citation (eq 7), for a value of each row shown.
    for (const r of T.listAbsoluteSensitivities().filter((x) => x.id !== 'given')) {
      await choose(page, 'absolute', 'Sensitivities for A_R, A_G, A_B', r.id === 'none' ? 'none' : cameras[0].id);
      const hint = await page.evaluate(() => document.querySelector('#step-absolute select[data-role="abs-camera"]')?.closest('.field')?.querySelector('small.hint')?.textContent);
      if (hint !== `${r.label} — ${r.reference}`) wrong.push(`absolute sensitivities ${r.id}: hint '${hint}'`);
    }
    await choose(page, 'absolute', 'Sensitivities for A_R, A_G, A_B', 'none');
    if (head('absolute/Chart (known reflectances)', charts.length) !== JSON.stringify(rows(charts))) wrong.push('absolute chart: not the built-in charts');
    if (head('absolute/Illuminant of the photo', T.listIlluminants().length) !== JSON.stringify(rows(T.listIlluminants()))) wrong.push('absolute illuminant: not the built-in illuminants');
    const guarnera = models.filter((m) => m.family === 'Guarnera2018');
    if (JSON.stringify((byKey['absolute/Colour matrix'] ?? []).map((o) => o.label)) !== JSON.stringify(guarnera.map((m) => `${m.label} — ${m.reference}`))) wrong.push('absolute colour matrix: not the Guarnera2018 family');
    // A training row's transform is a Guarnera2018 matrix the picker offers.
    for (const t of T.listExampleTrainings()) {
      if (t.transform && !guarnera.some((m) => m.id === `Guarnera2018-${t.transform}`)) wrong.push(`example training ${t.id}: transform ${t.transform} is not a Guarnera2018 model`);
    }
    // The example pickers' hints are the chosen row's `about` (the engine's words), for every row.
    for (const [name, list] of [['Example: light on the chart', T.listExampleLights()], ['Example: colour training', T.listExampleTrainings()]]) {
      for (const r of list) {
        await choose(page, 'absolute', name, r.id);
        const hint = await page.evaluate((n) => [...document.querySelectorAll('#step-absolute select')]
          .find((x) => x.labels?.[0]?.textContent.trim() === n)?.closest('.field')?.querySelector('small.hint')?.textContent, name);
        if (hint !== r.about) wrong.push(`absolute ${name} ${r.id}: hint '${hint}', the row's about '${r.about}'`);
      }
      await choose(page, 'absolute', name, list[0].id);
    }
    // The Export step's adaptations are ones the engine's IDT accepts; the Lab's cameras end in the
    // engine's 52, its charts are the renderer's (lab_chart_ids).
    for (const o of byKey['export/Chromatic adaptation'] ?? []) {
      try { T.idtCamera(cameras[0].id, 'D55', o.value); } catch (e) { wrong.push(`export adaptation ${o.value}: the engine refuses it (${T.errorMessage?.(e) ?? e})`); }
    }
    for (const s of found.filter((x) => x.step === 'lab' && x.name === 'Camera')) {
      if (JSON.stringify(s.options.slice(-cameras.length).map(({ value, label }) => ({ value, label }))) !== JSON.stringify(rows(cameras))) wrong.push('lab camera: not the built-in cameras');
    }
    // The Lab's OECFs are the renderer's; the exercise charts are ones it draws; the chips are Munsell ids.
    const oecfs = found.find((x) => x.step === 'lab' && x.name === 'OECF (TIFF, JPEG)')?.options.map((o) => o.value);
    if (JSON.stringify(oecfs) !== JSON.stringify([...T.listLabOecfs()])) wrong.push(`lab OECF: ${oecfs}, the renderer has ${[...T.listLabOecfs()]}`);
    for (const o of byKey['lab/Training chart'] ?? []) if (![...T.listLabCharts()].includes(o.value)) wrong.push(`lab training chart ${o.value}: not a chart the renderer draws`);
    const munsell = new Set([...T.listMunsell()]);
    for (const o of byKey['lab/Munsell chip'] ?? []) if (!munsell.has(o.value)) wrong.push(`lab Munsell chip ${o.value}: not in the engine's set`);
    for (const o of byKey['lab/or Munsell chips'] ?? []) if (!munsell.has(o.value)) wrong.push(`lab render Munsell chip ${o.value}: not in the engine's set`);
    // The flat-field modes cite their table row (the option's title).
    for (const o of byKey['images/Flat-field correction'] ?? []) {
      const m = T.listFlatFieldModes().find((x) => x.id === o.value);
      if (o.title !== m?.reference) wrong.push(`flat-field ${o.value}: title '${o.title}', the table's reference '${m?.reference}'`);
    }
    // Step 2's custom grid and sampled area: one number input per row of the engine's layout option
    // table (layout_option_table), in its order, labelled "label (unit)", with its bounds, step and default.
    // An extra chart image's panel (fieldset.second-chart) has its own custom grid (its sampled area is the first's).
    const inputsOf = (sel) => page.$$eval(sel, (els) => els.map((el) => ({
      name: el.dataset.layoutOption, type: el.type, label: (el.labels?.[0]?.textContent ?? el.getAttribute('aria-label') ?? '').trim(),
      min: el.getAttribute('min'), max: el.getAttribute('max'), step: el.getAttribute('step'), value: el.getAttribute('value'), title: el.title,
    })));
    const layoutInputs = await inputsOf('#step-images input[data-layout-option]:not(fieldset.second-chart input)');
    const extraInputs = await inputsOf('#step-images fieldset.second-chart input[data-layout-option]');
    const layoutTable = T.listLayoutOptions();
    if (JSON.stringify(layoutInputs.map((i) => i.name)) !== JSON.stringify(layoutTable.map((o) => o.name))) wrong.push(`layout inputs ${layoutInputs.map((i) => i.name)}, the table's ${layoutTable.map((o) => o.name)}`);
    const gridNames = layoutTable.map((o) => o.name).filter((n) => n !== 'area');
    if (JSON.stringify(extraInputs.map((i) => i.name)) !== JSON.stringify(gridNames)) wrong.push(`extra image's layout inputs ${extraInputs.map((i) => i.name)}, the table's ${gridNames}`);
    for (const o of layoutTable) for (const i of [layoutInputs, extraInputs].map((list) => list.find((x) => x.name === o.name))) {
      if (!i) continue;
      const want = { name: o.name, type: 'number', label: o.unit ? `${o.label} (${o.unit})` : o.label, min: String(o.min), max: String(o.max),
        step: String(o.step || (o.type === 'integer' ? 1 : 'any')), value: String(o.default_number), title: o.description };
      if (JSON.stringify(i) !== JSON.stringify(want)) wrong.push(`layout input ${o.name}: ${JSON.stringify(i)}, the table ${JSON.stringify(want)}`);
    }
    // The surface presets: every preset of the table (by id, with its label), the page's '' = custom.
    for (const role of ['Measurement geometry', 'Capture geometry']) {
      const opts = found.find((s) => s.step === 'surface' && s.name.startsWith(role))?.options ?? [];
      if (JSON.stringify(opts.map((o) => o.value).sort()) !== JSON.stringify(['', ...presets.map((p) => p.id)].sort())) wrong.push(`${role}: ${opts.map((o) => o.value)}`);
      for (const p of presets) if (!opts.find((o) => o.value === p.id)?.label.startsWith(`${p.id} — ${p.label}`)) wrong.push(`${role} ${p.id}: label`);
    }

    // The Surface step's, the Absolute mode's and the Lab's number boxes: one input per row of the
    // engine's surface_option_table, absolute_option_table (its number rows), sensitivity_option_table
    // and lab_option_table — the bounds fit_surface, the Table IV simulation, the absolute recipe,
    // the sensitivity estimate and the lab's functions enforce — marked data-<table>-option, labelled "label (unit)", with the row's bounds,
    // step, default and description.
    const numberTables = [['surface', '#step-surface', T.listSurfaceOptions()],
      ['absolute', '#step-absolute', T.listAbsoluteOptions().filter((o) => o.type === 'number')],
      ['sensitivity', '#step-absolute', T.listSensitivityOptions()], ['lab', '#step-lab', T.listLabOptions()]];
    for (const [table, scope, list] of numberTables) {
      const attr = `data-${table}-option`;
      const boxes = await page.$$eval(`${scope} input[${attr}]`, (els, a) => els.map((el) => ({
        name: el.getAttribute(a), type: el.type, label: (el.labels?.[0]?.textContent ?? '').trim(),
        min: el.getAttribute('min'), max: el.getAttribute('max'), step: el.getAttribute('step'), value: el.getAttribute('value'), title: el.title,
      })), attr);
      if (JSON.stringify(boxes.map((i) => i.name).sort()) !== JSON.stringify(list.map((o) => o.name).sort())) wrong.push(`${table} inputs ${boxes.map((i) => i.name)}, the table's ${list.map((o) => o.name)}`);
      for (const o of list) {
        const want = { name: o.name, type: 'number', label: o.unit ? `${o.label} (${o.unit})` : o.label, min: String(o.min), max: String(o.max),
          step: String(o.step || (o.type === 'integer' ? 1 : 'any')), value: String(o.default_number), title: o.description };
        const got = boxes.find((x) => x.name === o.name);
        if (got && JSON.stringify(got) !== JSON.stringify(want)) wrong.push(`${table} input ${o.name}: ${JSON.stringify(got)}, the table ${JSON.stringify(want)}`);
        // A row whose min the engine refuses (min_exclusive: the zone parameter w) makes its box
        // invalid at min, valid at the default; another row's box is valid at min.
        const validAt = (v) => page.evaluate(([sel, val]) => {
          const el = document.querySelector(sel);
          const before = el.value;
          el.value = val;
          el.dispatchEvent(new Event('input'));
          const ok = el.checkValidity();
          el.value = before;
          el.dispatchEvent(new Event('input'));
          return ok;
        }, [`${scope} input[${attr}="${o.name}"]`, String(v)]);
        if (got && (await validAt(o.min)) === !!o.min_exclusive) wrong.push(`${table} input ${o.name}: ${o.min} is ${o.min_exclusive ? 'accepted' : 'refused'}, the engine ${o.min_exclusive ? 'refuses' : 'accepts'} it`);
        if (got && !(await validAt(o.default_number))) wrong.push(`${table} input ${o.name}: its default ${o.default_number} is marked invalid`);
      }
    }

    // Step 2's light trap: one box per row of the engine's table for the chart image's size
    // (light_trap_option_table), labelled "label (unit)", with its bounds, step and description.
    const [W, H] = await page.$eval('#step-images rect.image-frame', (r) => [Number(r.getAttribute('width')), Number(r.getAttribute('height'))]);
    const trapRows = T.listLightTrapOptions(W, H);
    await page.waitForFunction(() => document.querySelector('#step-images fieldset.light-trap input[data-light-trap-option]'), null, { timeout: 30000 });
    const trapBoxes = await page.$$eval('#step-images fieldset.light-trap:not(fieldset.second-chart fieldset) input[data-trap]', (els) => els.map((el) => ({
      name: el.dataset.lightTrapOption, type: el.type, label: el.getAttribute('aria-label'), min: el.getAttribute('min'), max: el.getAttribute('max'),
      step: el.getAttribute('step'), title: el.title })));
    const wantTrap = trapRows.map((o) => ({ name: o.name, type: 'number', label: o.unit ? `${o.label} (${o.unit})` : o.label, min: String(o.min),
      max: String(o.max), step: String(o.step || 1), title: o.description }));
    if (JSON.stringify(trapBoxes) !== JSON.stringify(wantTrap)) wrong.push(`light trap boxes ${JSON.stringify(trapBoxes)}, the table for ${W} x ${H}: ${JSON.stringify(wantTrap)}`);

    // Step 3: the model checklist in the engine's families (their order, labels, advice), each
    // family's models in the table's order with their labels and citations; the objectives.
    await step(page, 'fit');
    const groups = await page.$$eval('#step-fit .family', (els) => els.map((g) => ({
      id: g.dataset.family, label: g.querySelector('h4')?.textContent, about: g.querySelector(':scope > small')?.textContent ?? '',
      models: [...g.querySelectorAll('input[data-model]')].map((cb) => ({ id: cb.value, label: cb.labels[0].textContent, title: cb.closest('.check').title })),
    })));
    const wantGroups = families.map((f) => ({ id: f.id, label: f.label, about: f.about,
      models: models.filter((m) => m.family === f.id).map((m) => ({ id: m.id, label: m.label, title: m.reference })) }));
    groups.forEach((g, k) => {
      if (JSON.stringify(g) !== JSON.stringify(wantGroups[k])) wrong.push(`model family ${k}: shows ${JSON.stringify(g).slice(0, 300)}, the engine ${JSON.stringify(wantGroups[k]).slice(0, 300)}`);
    });
    if (groups.length !== wantGroups.length) wrong.push(`${groups.length} model families shown, the engine has ${wantGroups.length}`);
    const objectives = await page.$$eval('#step-fit input[data-objective]', (els) => els.map((cb) => ({ value: cb.value, label: cb.labels[0].textContent })));
    if (JSON.stringify(objectives) !== JSON.stringify(rows(T.listObjectives()))) wrong.push(`objectives: shows ${JSON.stringify(objectives)}`);
    for (const o of T.listObjectives()) {
      if (!o.options.length) continue;
      checkForm(`objective ${o.id}`, o, await formControls(page, `#step-fit details.objective-options[data-objective="${o.id}"]`), wrong);
    }

    await screenshot(page, 'catalog-pickers-fit');

    // Step 2b and 1b: each row of the method table picked in turn, its options form checked.
    await step(page, 'linearisation');
    for (const r of T.listLinearisations()) {
      await choose(page, 'linearisation', 'Linearisation', r.id);
      checkForm(`linearisation ${r.id}`, r, await formControls(page, '#step-linearisation .linearisation-options'), wrong);
    }
    await choose(page, 'linearisation', 'Linearisation', 'identity');
    await step(page, 'surface');
    for (const r of T.listSurfaceCorrections()) {
      await choose(page, 'surface', 'Surface correction', r.id);
      checkForm(`surface ${r.id}`, r, await formControls(page, '#step-surface .surface-options'), wrong);
      // The row's citation and equation, as the engine writes them.
      const text = await page.$$eval('#step-surface p.hint', (ps) => ps.map((p) => p.textContent).join('\n'));
      if (!text.includes(`${r.label} — ${r.reference}${r.equation ? ` (${r.equation})` : ''}.`)) wrong.push(`surface ${r.id}: no hint gives the row's label, reference and equation`);
      // A row of Saunderson geometries shows the preset pickers; the others do not.
      const presetsShown = await page.$eval('#step-surface .surface-presets', (el) => !el.hidden);
      if (presetsShown !== Object.keys(r.geometry).length > 0) wrong.push(`surface ${r.id}: preset pickers ${presetsShown ? 'shown' : 'hidden'}`);
    }
    await screenshot(page, 'catalog-pickers-surface');
    await choose(page, 'surface', 'Surface correction', 'none');

    // Step 1: a built-in chart's swatches sit at their cells of the engine's layout.
    await step(page, 'reference');
    for (const c of charts) {
      await choose(page, 'reference', 'Chart', c.id);
      await page.waitForFunction(([name, n]) => document.querySelector('#step-reference .summary')?.textContent.includes(`built-in chart ${name},`)
        && document.querySelectorAll('#step-reference .swatch').length === n, [c.name, c.patches], { timeout: 30000 });
      const cells = await page.$$eval('#step-reference .swatch', (els) => els.map((e) => [e.dataset.id, e.style.gridRow, e.style.gridColumn]));
      const layout = T.chartLayout({ chart: c.id });
      const at = new Map(layout.patches.map((p) => [p.id, [String(p.row + 1), String(p.column + 1)]]));
      const misplaced = cells.filter(([id, r, col]) => JSON.stringify([r.split(' ')[0], col.split(' ')[0]]) !== JSON.stringify(at.get(id)));
      if (misplaced.length) wrong.push(`${c.id}: swatches off their layout cells: ${misplaced.slice(0, 3).join('; ')}`);
      const columns = await page.$eval('#step-reference .swatches', (el) => el.style.gridTemplateColumns);
      if (!columns.startsWith(`repeat(${layout.columns},`)) wrong.push(`${c.id}: ${columns}, the layout has ${layout.columns} columns`);
    }
    await choose(page, 'reference', 'Chart', 'passport');

    assert.deepEqual(wrong, []);
    assert.deepEqual(b.problems, []);
  } finally {
    await b.close();
  }
});
