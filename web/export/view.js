// Step 6: download the selected profile as JSON, the per-patch CSV, an ICC profile, a .cube LUT
// and a DNG camera profile (DCP); load any of them back (a profile JSON becomes a result again,
// evaluated on this chart).
import { h, field, showError, clearError, download, select, setOptions } from '../lib/ui.js';
import { options } from '../lib/catalog.js';

export function mount(section, app) {
  const { engine } = app;
  const which = h('p', { class: 'summary' });
  const btn = (label, fn, needsProfile = () => true) => {
    const b = h('button', { type: 'button', dataset: { export: label } }, label);
    b._errorSlot = h('p', { class: 'field-error', role: 'alert', hidden: true, id: `export-${label.replace(/\W+/g, '-')}-error` });
    b.setAttribute('aria-describedby', b._errorSlot.id);
    b.addEventListener('click', async () => {
      clearError(b);
      const r = selected();
      if (!r && needsProfile()) { showError(b, Object.assign(new Error('no profile yet'), { code: 'NO_PROFILE' }), label); return; }
      try { await fn(r); } catch (e) { showError(b, e, label); }
    });
    return h('div', { class: 'field' }, b, b._errorSlot);
  };
  const base = (r) => `tristim-${r.modelId}-${r.objective}`.replace(/[^\w.-]+/g, '_');
  const exports = h('div', { class: 'controls' },
    btn('Profile JSON', (r) => download(`${base(r)}.json`, r.fit.profile, 'application/json')),
    btn('Per-patch CSV', async (r) => {
      // The engine's per-patch CSV: estimates, every ΔE, and the leave-one-out estimates when there are.
      // Its ids as the reference file spelled them (r.labels; "A01" stays "A01"), not the matching keys.
      const e = r.fit.evaluation;
      const ids = r.labels?.length === r.ids.length ? r.labels : r.ids;
      const { text } = await engine.call('patchCsv', { ids, rgb: r.rgb, xyz: r.xyz, estimated: e.fit.fitted, white: r.white, loo: e.loo_XYZ ?? [] });
      download(`${base(r)}-patches.csv`, text, 'text/csv');
    }),
    btn('ICC profile', async (r) => { const { bytes } = await engine.call('exportIcc', { profile: r.fit.profile }); download(`${base(r)}.icc`, bytes, 'application/vnd.iccprofile'); }),
    btn('.cube LUT', async (r) => { const { text } = await engine.call('exportCube', { profile: r.fit.profile, size: 33 }); download(`${base(r)}.cube`, text, 'text/plain'); }),
    btn('DCP', async (r) => {
      const model = cameraModel.value.trim();
      if (!model) throw Object.assign(new Error('a DCP names its camera: fill in the camera model (make and model)'), { code: 'INVALID_ARGUMENT' });
      const options = { camera_model: model, hue_sat_map: hueSatMap.checked && !hueSatMap.disabled ? [90, 30, 30] : [0, 0, 0] };
      // A second profile of the camera under another illuminant makes it dual-illuminant (the
      // engine orders them by colour temperature and refuses two equal illuminants).
      const second = (app.session.results ?? []).find((x) => x.key === dcpSecond.value && x.key !== r.key);
      const { bytes } = second
        ? await engine.call('exportDcpDual', { profile: r.fit.profile, second: second.fit.profile, options })
        : await engine.call('exportDcp', { profile: r.fit.profile, options });
      const name = dcpName(model);
      download(name, bytes, 'application/octet-stream');
      // The download read back by the engine's strict reader (what `tristim inspect` prints).
      dcpSummary.replaceChildren(h('p', {}, dcpText(name, bytes.length, await engine.call('readDcp', { bytes: bytes.slice() }))));
    }));

  // DCP: the camera as the RAW names it (make + model, as LibRaw and RawTherapee's decoder give
  // them and as `tristim export --raw` takes it), editable; RawTherapee only picks a DCP by itself
  // when its dcpprofiles folder holds "<Make> <Model>.dcp", so that is the download's name.
  const cameraModel = h('input', { type: 'text', id: 'dcp-camera-model', size: 32, placeholder: 'Make Model, e.g. Canon EOS 550D' });
  let modelEdited = false;
  cameraModel.addEventListener('input', () => { modelEdited = true; describeDcp(); });
  const hueSatMap = h('input', { type: 'checkbox', id: 'dcp-hue-sat-map' });
  const dcpSecond = select([{ value: '', label: 'none (single illuminant)' }], '');
  dcpSecond.id = 'dcp-second';
  const dcpNote = h('p', { class: 'hint dcp-file-name' });
  const dcpSummary = h('div', { class: 'dcp-summary', 'aria-live': 'polite' });
  const dcpName = (model) => `${model.replace(/[\\/:*?"<>|]+/g, '_')}.dcp`;
  const rawCamera = () => {
    const m = app.derived.image?.metadata ?? {};
    return [m.make, m.model].filter(Boolean).join(' ');
  };
  function describeDcp() {
    if (!modelEdited) cameraModel.value = rawCamera();
    const r = selected();
    const linear = !r || (app.catalog.models.find((m) => m.id === r.modelId)?.linear ?? true);
    hueSatMap.disabled = linear;
    hueSatMap.parentElement?.toggleAttribute('data-disabled', linear);
    // Every other result can be the second profile (e.g. a profile JSON of the same camera fitted
    // under another illuminant, loaded back below).
    const others = (app.session.results ?? []).filter((x) => x.key !== r?.key);
    setOptions(dcpSecond, [{ value: '', label: 'none (single illuminant)' }, ...others.map((x) => ({ value: x.key, label: x.label }))],
      others.some((x) => x.key === dcpSecond.value) ? dcpSecond.value : '');
    const model = cameraModel.value.trim();
    dcpNote.textContent = model
      ? `RawTherapee uses a DCP by itself (input profile "Camera standard") when its dcpprofiles folder holds it as "${dcpName(model)}" — `
        + 'the download has that name, right when the camera model is as RawTherapee names the camera (make and model as in the RAW). '
        + 'Otherwise choose the file as a custom input profile.'
      : 'No camera model: decode the chart RAW in step 2, or type the make and model as RawTherapee names the camera.';
  }
  const dcpControls = h('div', { class: 'controls' },
    field('Camera model (UniqueCameraModel)', cameraModel, 'From the chart RAW\'s make and model; edit it if your raw converter names the camera differently.'),
    field('HueSatMap 90×30×30', hueSatMap, 'For a model that is not a 3×3 matrix: the DCP\'s ForwardMatrix carries its linear part at neutral, the HueSatMap the rest.'),
    field('Second profile (dual-illuminant)', dcpSecond, 'The same camera under another illuminant (e.g. A with D65): a dual-illuminant DCP, which raw converters interpolate by the white balance.'));

  // ACES Input Transform: the rawtoaces v1 IDT (rows summing to one, least-squares ΔE*ab, CAT02 or
  // Bradford) from a built-in camera's sensitivities with the 190 training spectra, or from this
  // chart's patches; the engine writes the CLF and the plain 3×3 that `tristim idt` writes.
  const idtSource = select([{ value: 'camera', label: 'Built-in camera sensitivities (190 training spectra)' },
    { value: 'sensitivities', label: 'Sensitivities CSV (wavelength, R, G, B; 190 training spectra)' },
    { value: 'chart', label: 'This chart\'s patches (the selected profile\'s data)' }], 'camera');
  idtSource.id = 'idt-source';
  const idtCamera = select(options(app.catalog.cameras), 'Canon_EOS_5D_Mark_II');
  idtCamera.id = 'idt-camera';
  const idtIlluminant = select(options(app.catalog.illuminants), 'D55');
  idtIlluminant.id = 'idt-illuminant';
  const idtAdaptation = select(['CAT02', 'Bradford'], 'CAT02');
  idtAdaptation.id = 'idt-adaptation';
  const idtSummary = h('div', { class: 'idt-summary', 'aria-live': 'polite' });
  // Uploaded sensitivities: kept as text and read by the engine (read_ssf_csv) when the IDT is made.
  // A button opens the file chooser (the step's one file input in the page stays the import below).
  const idtSsf = h('button', { type: 'button', id: 'idt-ssf' }, 'Choose a CSV…');
  let ssf = null;
  idtSsf.addEventListener('click', () => {
    const input = h('input', { type: 'file', accept: '.csv,.txt' });
    input.addEventListener('change', async () => {
      const f = input.files[0];
      clearError(idtSsf);
      if (!f) return;
      ssf = null;
      try { ssf = { name: f.name, text: await f.text() }; } catch (e) { showError(idtSsf, e, f.name); }
      idtSsf.textContent = ssf ? ssf.name : 'Choose a CSV…';
      describeIdt();
    });
    input.click();
  });
  const idtCommand = h('p', { class: 'hint idt-command' });
  const fromChart = () => idtSource.value === 'chart';
  const idtName = () => {
    const source = idtSource.value === 'sensitivities' ? (ssf?.name ?? 'sensitivities').replace(/\.[^.]*$/, '') : idtCamera.value;
    return (fromChart() ? `tristim-idt-chart-${idtAdaptation.value}` : `tristim-idt-${source}-${idtIlluminant.value}-${idtAdaptation.value}`).replace(/[^\w.-]+/g, '_');
  };
  async function idtFiles(r) {
    const adaptation = idtAdaptation.value;
    if (idtSource.value === 'sensitivities') {
      if (!ssf) throw Object.assign(new Error('choose a sensitivities CSV (wavelength, R, G, B) first'), { code: 'INVALID_ARGUMENT' });
      return engine.call('idtSensitivities', { text: ssf.text, name: ssf.name, illuminant: idtIlluminant.value, adaptation });
    }
    if (!fromChart()) return engine.call('idtCamera', { camera: idtCamera.value, illuminant: idtIlluminant.value, adaptation });
    // The chart: its camera RGB and reference XYZ, the reference white as its illuminant.
    const white = Array.from(r.white);
    return engine.call('idtChart', { rgb: r.rgb, xyz: r.xyz, white, adaptation, rgbName: r.label, referenceName: 'step 1 reference',
      illuminant: ['ReferenceWhiteXYZ', white.map((v) => v.toFixed(4)).join(' ')] });
  }
  function describeIdt() {
    const chart = fromChart(), upload = idtSource.value === 'sensitivities';
    idtCamera.disabled = chart || upload;
    idtIlluminant.disabled = chart;
    idtSsf.disabled = !upload;
    const source = upload ? `--sensitivities ${ssf?.name ?? '<file.csv>'}` : `--camera "${idtCamera.value}"`;
    idtCommand.textContent = chart
      ? 'From the chart: the white balance comes from its most neutral bright patch; the CLF takes camera values as this chart\'s RAW has them.'
      : `The same files as: tristim idt ${source} --illuminant ${idtIlluminant.value} --adaptation ${idtAdaptation.value} --out idt.clf --matrix idt.txt`;
  }
  for (const s of [idtSource, idtCamera, idtIlluminant, idtAdaptation]) s.addEventListener('change', describeIdt);
  const idtControls = h('div', { class: 'controls' },
    field('IDT from', idtSource), field('Camera', idtCamera), field('Sensitivities CSV', idtSsf), field('Illuminant', idtIlluminant),
    field('Chromatic adaptation', idtAdaptation, 'To the ACES white (rawtoaces v1 uses CAT02).'));
  const idtButtons = h('div', { class: 'controls' },
    btn('IDT (CLF)', async (r) => {
      const files = await idtFiles(r);
      const name = `${idtName()}.clf`;
      download(name, files.clf, 'application/xml');
      // The download read back by the engine's strict CLF reader.
      idtSummary.replaceChildren(h('p', {}, clfText(name, new TextEncoder().encode(files.clf).length, await engine.call('readClf', { text: files.clf }), files.json)));
    }, fromChart),
    btn('IDT 3×3 matrix', async (r) => download(`${idtName()}.txt`, (await idtFiles(r)).matrix, 'text/plain'), fromChart));

  const importInput = h('input', { type: 'file', accept: '.json,.csv,.icc,.icm,.cube,.dcp,.clf' });
  const imported = h('div', { class: 'import-result', 'aria-live': 'polite' });
  section.append(which, h('h3', {}, 'Download'), exports,
    h('h3', {}, 'DNG camera profile (DCP)'), dcpControls, dcpNote, dcpSummary,
    h('h3', {}, 'ACES Input Transform (CLF)'), idtControls, idtButtons, idtCommand, idtSummary,
    h('h3', {}, 'Load an export back'),
    field('Profile JSON, per-patch CSV, ICC, .cube, DCP or CLF', importInput,
      'A profile JSON is evaluated on the current chart and added to the results; a per-patch CSV can be used as a reference in step 1; ICC, .cube, DCP and CLF files are checked and summarised.'),
    imported);

  function selected() {
    const rs = app.session.results ?? [];
    return rs.find((r) => r.key === app.session.selected) ?? rs[0];
  }
  const describe = () => {
    const r = selected();
    which.textContent = r ? `Selected profile: ${r.label}.` : 'No profile yet: fit one in step 3, or load a profile JSON below.';
    describeDcp();
  };
  app.on('results', describe);
  app.on('step', (s) => { if (s === 'export') describe(); });

  importInput.addEventListener('change', async () => {
    const f = importInput.files[0];
    if (!f) return;
    clearError(importInput);
    imported.replaceChildren();
    try {
      const ext = f.name.toLowerCase().split('.').pop();
      if (ext === 'json') await importProfile(f);
      else if (ext === 'cube') {
        const c = await engine.call('readCube', { text: await f.text(), name: f.name });
        imported.append(h('p', {}, `${f.name}: a ${c.size}×${c.size}×${c.size} 3D LUT${c.shaper_size ? ` after a ${c.shaper_size}-row 1D shaper` : ''}${c.title ? ` “${c.title}”` : ''}, domain ${c.domain_min.join(' ')} … ${c.domain_max.join(' ')}.`));
      } else if (ext === 'icc' || ext === 'icm') {
        const hd = await engine.call('readIcc', { bytes: new Uint8Array(await f.arrayBuffer()), name: f.name });
        imported.append(h('p', {}, `${f.name}: ICC v${hd.version} ${hd.device_class} profile${hd.description ? ` “${hd.description}”` : ''}, ${hd.colour_space} → ${hd.pcs}, ${hd.size} bytes, tags ${hd.tags.join(' ')}.`));
      } else if (ext === 'dcp') {
        const bytes = new Uint8Array(await f.arrayBuffer());
        imported.append(h('p', {}, dcpText(f.name, bytes.length, await engine.call('readDcp', { bytes }))));
      } else if (ext === 'clf') {
        const text = await f.text();
        imported.append(h('p', {}, clfText(f.name, f.size, await engine.call('readClf', { text }))));
      } else if (ext === 'csv') {
        // The engine reads its own per-patch CSV as a reference (its X_ref, Y_ref, Z_ref columns).
        const r = await app.views.reference.useFile({ name: f.name, text: await f.text() });
        if (r instanceof Error) throw r;
        imported.append(h('p', {}, `${f.name}: loaded as the reference in step 1 (its X, Y, Z columns).`));
      } else throw Object.assign(new Error(`unknown file type .${ext}`), { code: 'UNSUPPORTED_FORMAT' });
    } catch (e) { showError(importInput, e, f.name); }
  });

  async function importProfile(f) {
    const text = await f.text();
    let json;
    try { json = JSON.parse(text); } catch (e) { throw Object.assign(new Error(`not JSON: ${e.message}`), { code: 'PARSE_ERROR' }); }
    const any = (app.session.results ?? [])[0];
    const data = any ?? null;
    if (!data) throw Object.assign(new Error('fit once (step 3) so there is chart data to evaluate the profile on'), { code: 'NO_DATA' });
    const evaluation = await engine.call('evaluate', { profile: text, rgb: data.rgb, xyz: data.xyz, ids: data.ids });
    const { profile } = evaluation;
    const modelLabel = app.catalog.models.find((m) => m.id === profile.model.id)?.label ?? profile.model.id;
    // Training errors: the profile evaluated on the current chart; leave-one-out: as stored in the
    // profile (from its own training data; the same data when same_data_as_training).
    const same = evaluation.same_data_as_training;
    const fit = {
      profile: text,
      display: evaluation.display,
      evaluation: {
        fit: { status: same ? 'imported' : 'imported (other training data)', message: '', condition_number: profile.fit.condition_number, fitted: evaluation.estimated },
        training: evaluation.metrics,
        loo: same ? json.metrics?.loo ?? null : null,
      },
    };
    const result = { key: `imported|${f.name}|${Date.now()}`, modelId: profile.model.id, objective: profile.objective,
      label: `${modelLabel} · ${profile.objective} (imported ${f.name})`, ids: data.ids, labels: data.labels, rgb: data.rgb, xyz: data.xyz, white: profile.colorimetry.white, fit, evaluation };
    const results = [...(app.session.results ?? []), result];
    await app.save('results', results);
    await app.save('selected', result.key);
    app.emit('results', results);
    imported.append(h('p', { dataset: { imported: result.key } }, `${f.name}: profile loaded and evaluated on the current chart; it is now selected in Results.`));
  }
  describe();
  describeIdt();
  return { importInput, cameraModel };
}

/// One line about a DCP as the engine's reader gives it (dcp_json): camera, illuminants, ForwardMatrix.
function dcpText(name, size, d) {
  const rows = (m) => m.map((row) => row.map((v) => v.toFixed(4)).join(' ')).join(' / ');
  const ill = d.illuminants.map((i, k) => `CalibrationIlluminant${k + 1} ${i.code} (${i.name}, ${i.temperature} K)`).join(', ');
  const fm = [d.forward_matrix1, d.forward_matrix2].filter(Boolean).map((m, k) => `ForwardMatrix${k + 1} ${rows(m)}`).join('; ');
  const hsm = d.hue_sat_map ? `HueSatMap ${d.hue_sat_map.dims.join('×')}` : 'no HueSatMap';
  return `${name}: DNG camera profile, UniqueCameraModel “${d.unique_camera_model}”, ${ill}; ${fm}; ${hsm}; ${size} bytes.`;
}

/// One line about a CLF as the engine's reader gives it (clf_json), with the fit's errors when known.
function clfText(name, size, c, fit) {
  const rows = c.matrix.map((row) => row.map((v) => v.toFixed(4)).join(' ')).join(' / ');
  const info = ['Camera', 'Sensitivities', 'CameraRGB', 'Illuminant', 'IlluminantFile', 'Training', 'Adaptation', 'WhiteBalance']
    .filter((k) => c.info[k] != null).map((k) => `${k} ${c.info[k]}`).join(', ');
  const white = c.aces_of_camera_1_1_1.map((v) => v.toFixed(4)).join(' ');
  const errors = fit ? `; fit on ${fit.errors.samples} samples: ΔE*ab mean ${fit.errors.delta_E76_mean.toFixed(2)}, max ${fit.errors.delta_E76_max.toFixed(2)}` : '';
  return `${name}: CLF “${c.name}”, ${c.input} → ${c.output}; ${info}; Matrix ${rows}${c.lut1d_entries ? `; LUT1D of ${c.lut1d_entries}` : ''}; camera (1, 1, 1) → ACES ${white}${errors}; ${size} bytes.`;
}
