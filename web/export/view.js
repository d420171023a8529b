// Step 6: download the selected profile as JSON, the per-patch CSV, an ICC profile, a .cube LUT
// and a DNG camera profile (DCP); load any of them back (a profile JSON becomes a result again,
// evaluated on this chart).
import { h, field, showError, clearError, download } from '../lib/ui.js';
import { readCube, readIccHeader } from './formats.js';

export function mount(section, app) {
  const { engine } = app;
  const which = h('p', { class: 'summary' });
  const btn = (label, fn) => {
    const b = h('button', { type: 'button', dataset: { export: label } }, label);
    b._errorSlot = h('p', { class: 'field-error', role: 'alert', hidden: true, id: `export-${label.replace(/\W+/g, '-')}-error` });
    b.setAttribute('aria-describedby', b._errorSlot.id);
    b.addEventListener('click', async () => {
      clearError(b);
      const r = selected();
      if (!r) { showError(b, Object.assign(new Error('no profile yet'), { code: 'NO_PROFILE' }), label); return; }
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
      const { bytes } = await engine.call('exportDcp', { profile: r.fit.profile, options });
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
    const model = cameraModel.value.trim();
    dcpNote.textContent = model
      ? `RawTherapee uses a DCP by itself (input profile "Camera standard") when its dcpprofiles folder holds it as "${dcpName(model)}" — `
        + 'the download has that name, right when the camera model is as RawTherapee names the camera (make and model as in the RAW). '
        + 'Otherwise choose the file as a custom input profile.'
      : 'No camera model: decode the chart RAW in step 2, or type the make and model as RawTherapee names the camera.';
  }
  const dcpControls = h('div', { class: 'controls' },
    field('Camera model (UniqueCameraModel)', cameraModel, 'From the chart RAW\'s make and model; edit it if your raw converter names the camera differently.'),
    field('HueSatMap 90×30×30', hueSatMap, 'For a model that is not a 3×3 matrix: the DCP\'s ForwardMatrix carries its linear part at neutral, the HueSatMap the rest.'));

  const importInput = h('input', { type: 'file', accept: '.json,.csv,.icc,.icm,.cube,.dcp' });
  const imported = h('div', { class: 'import-result', 'aria-live': 'polite' });
  section.append(which, h('h3', {}, 'Download'), exports,
    h('h3', {}, 'DNG camera profile (DCP, single illuminant)'), dcpControls, dcpNote, dcpSummary,
    h('h3', {}, 'Load an export back'),
    field('Profile JSON, per-patch CSV, ICC, .cube or DCP', importInput,
      'A profile JSON is evaluated on the current chart and added to the results; a per-patch CSV can be used as a reference in step 1; ICC, .cube and DCP files are checked and summarised.'),
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
        const c = readCube(await f.text());
        imported.append(h('p', {}, `${f.name}: a ${c.size}×${c.size}×${c.size} 3D LUT${c.title ? ` “${c.title}”` : ''}, domain ${c.domainMin.join(' ')} … ${c.domainMax.join(' ')}.`));
      } else if (ext === 'icc' || ext === 'icm') {
        const hd = readIccHeader(new Uint8Array(await f.arrayBuffer()));
        imported.append(h('p', {}, `${f.name}: ICC v${hd.version} ${hd.deviceClass} profile, ${hd.colourSpace} → ${hd.pcs}, ${hd.size} bytes, tags ${hd.tags.join(' ')}.`));
      } else if (ext === 'dcp') {
        const bytes = new Uint8Array(await f.arrayBuffer());
        imported.append(h('p', {}, dcpText(f.name, bytes.length, await engine.call('readDcp', { bytes }))));
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
        fit: { status: same ? 'imported' : 'imported (other training data)', message: '', condition_number: profile.condition_number, fitted: evaluation.estimated },
        training: evaluation.metrics,
        loo: same ? json.metrics?.loo ?? null : null,
      },
    };
    const result = { key: `imported|${f.name}|${Date.now()}`, modelId: profile.model.id, objective: profile.objective,
      label: `${modelLabel} · ${profile.objective} (imported ${f.name})`, ids: data.ids, labels: data.labels, rgb: data.rgb, xyz: data.xyz, white: profile.white, fit, evaluation };
    const results = [...(app.session.results ?? []), result];
    await app.save('results', results);
    await app.save('selected', result.key);
    app.emit('results', results);
    imported.append(h('p', { dataset: { imported: result.key } }, `${f.name}: profile loaded and evaluated on the current chart; it is now selected in Results.`));
  }
  describe();
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
