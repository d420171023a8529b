// Step 2's second chart image (issue 48, docs/multi-image.md): "Add another chart image" — another
// photograph (any built-in chart; its reference is that chart's under step 1's illuminant and
// observer), decoded into the worker's slot 'chart2', its corners found by detection or dragged by
// hand, sampled as the first. The Fit then trains on the union of both charts' patches exactly as
// `tristim fit --recipe r.json --raw a --raw b` does: withImages() turns the fit's recipe into one
// with an `images` list, chartsOf() gives the worker each image's sample.
import { h, field, select, showError, clearError, fileBytes, progressBar } from '../lib/ui.js';
import { CornerEditor } from './corners.js';
import { patchTable } from './patch_table.js';

/// Mounts the second image's panel in `parent`; returns {restore, resample, input, forget, editor}.
export function mountSecond(parent, app) {
  const { engine } = app;
  // The built-in charts the engine has a layout for (the layout and the reference are the chart's).
  const charts = app.catalog.charts.filter((c) => app.catalog.layouts[c.id]);
  const saved = () => app.session.chart2 ?? {};
  const input = h('input', { type: 'file', dataset: { slot: 'chart2' } });
  const fileState = h('span', { class: 'file-state' });
  // By default the first image's chart (another shot of it), else the engine's first chart.
  const firstChart = () => charts.find((c) => c.id === app.session.layout?.chart)?.id ?? charts[0]?.id;
  const chartSel = select(charts.map((c) => ({ value: c.id, label: c.name })), saved().chart ?? firstChart());
  chartSel.dataset.role = 'chart2-chart';
  // How patches of the same colour in both images count (the recipe's `duplicates`).
  const dupSel = select([
    { value: 'once', label: 'once: the same patch of the same chart in both images is one row (mean RGB)' },
    { value: 'each', label: 'each: every image\'s patches are rows of their own' }], saved().duplicates ?? 'once');
  dupSel.dataset.role = 'duplicates';
  const remove = h('button', { type: 'button', hidden: true, onclick: () => forget() }, 'Remove the second image');
  const progress = progressBar('Decoding the second image');
  // The corner editor exists while a second image does (the step's own editor stays the only one
  // otherwise): made at its first decode, dropped by Remove.
  let editor = null;
  const editorBox = h('div', { class: 'second-editor' });
  const newEditor = () => {
    editor = new CornerEditor({ onChange: (c, final) => cornersChanged(c, final), grid: (layout, corners) => engine.call('grid', { layout, corners }), clipId: 'image-clip-2' });
    editorBox.replaceChildren(editor.el);
    return editor;
  };
  const note = h('p', { class: 'detect-text', 'aria-live': 'polite' });
  const summary = h('p', { class: 'summary', 'aria-live': 'polite' });
  const tableBox = h('div', { class: 'table-box' });
  const panel = h('fieldset', { class: 'second-chart', dataset: { state: 'empty' } },
    h('legend', {}, 'Add another chart image (optional): the fit trains on both charts\' patches'),
    h('div', { class: 'controls' }, h('div', { class: 'field-group' },
      field('Second chart image', input, 'Another photograph: the same chart elsewhere in the frame, or another chart (RAW, TIFF, PNG or JPEG)'), fileState, remove),
    field('Its chart (layout and reference)', chartSel, 'The reference is this chart under the illuminant and observer of step 1'),
    field('Patches of the same colour', dupSel)),
    progress.el, h('div', { class: 'images-layout' }, h('div', {}, editorBox, note), h('div', {}, summary, tableBox)));
  parent.append(panel);

  const layout = () => ({ chart: chartSel.value });
  const area = () => app.session.sampleOptions?.area ?? 0.5;
  const store = (patch) => app.save('chart2', { ...saved(), ...patch });
  let decodedGen = -1;

  async function setFile(file) {
    clearError(input);
    let bytes;
    try { bytes = await fileBytes(file); } catch (e) { showError(input, e, file.name); return; }
    if (!(await decode({ name: file.name, bytes }))) return;
    if (!saved().chart) chartSel.value = firstChart();
    await app.save('files.chart2', { name: file.name, bytes: bytes.buffer });
    await store({ chart: chartSel.value, duplicates: dupSel.value, corners: undefined, sha256: await engine.call('digest', { bytes }) });
    await detect();
  }
  input.addEventListener('change', () => { if (input.files[0]) setFile(input.files[0]); });

  async function decode(file) {
    progress.start(`Decoding ${file.name}…`);
    try {
      const r = await engine.call('decode', { slot: 'chart2', bytes: new Uint8Array(file.bytes).slice().buffer });
      decodedGen = engine.generation;
      fileState.textContent = `${file.name} — ${r.width}×${r.height}`;
      (editor ?? newEditor()).setImage(r);
      editor.setLayout(layout());
      remove.hidden = false;
      panel.dataset.state = 'decoded';
      return true;
    } catch (e) {
      if (e.code !== 'CANCELLED') showError(input, e, file.name);
      return false;
    } finally {
      progress.done();
    }
  }
  /// Decodes the stored file again when the worker was restarted since.
  async function ensureDecoded() {
    const f = app.session['files.chart2'];
    return !!f && (decodedGen === engine.generation || decode(f));
  }

  /// Looks for the chosen chart; takes its corners, or leaves the handles for the user to drag.
  async function detect() {
    note.textContent = 'Looking for the chart…';
    try {
      const { candidates } = await engine.call('detect', { slot: 'chart2', layout: layout() });
      if (!editor) return;   // removed meanwhile
      const c = candidates[0];
      editor.setCorners(c.corners);
      note.textContent = `Corners found automatically (confidence ${c.confidence.toFixed(2)}). Drag the handles to correct them.`;
    } catch (e) {
      if (e.code === 'CANCELLED' || !editor) return;
      note.textContent = `No ${chartSel.selectedOptions[0]?.textContent ?? 'chart'} found (${e.message}): drag the four corners onto the chart's outer patch corners (A1 first).`;
      editor.reset();
      return;
    }
    await cornersChanged(editor.corners, true);
  }

  let seq = 0, timer = null;
  function cornersChanged(c, final) {
    clearTimeout(timer);
    return new Promise((resolve) => {
      timer = setTimeout(async () => { await store({ corners: Array.from(c) }); resolve(resample()); }, final ? 0 : 120);
    });
  }

  /// Samples the second image at its corners: app.derived.sample2, emits 'sample2'.
  async function resample() {
    const n = ++seq;
    const corners = saved().corners;
    if (!corners || !(await ensureDecoded())) return null;
    try {
      const s = await engine.call('sample', { slot: 'chart2', layout: layout(), corners, sampleOptions: { area: area() } });
      if (n !== seq) return null;
      clearError(editor.el);
      s.corners = Array.from(corners);
      app.derived.sample2 = s;
      editor.setSample(s);
      tableBox.replaceChildren(patchTable(s));
      summary.textContent = `Second image: ${s.ids.length} patches sampled; ${s.flags.filter((f) => f.length).length} flagged.`;
      panel.dataset.state = 'sampled';
      app.emit('sample2', s);
      return s;
    } catch (e) {
      if (n !== seq || e.code === 'CANCELLED') return null;
      showError(editor.el, e, 'Second image corners');
      editor.setSample(null, e.code);
      return null;
    }
  }

  chartSel.addEventListener('change', async () => {
    editor?.setLayout(layout());
    await store({ chart: chartSel.value });
    if (app.session['files.chart2']) await detect();
  });
  dupSel.addEventListener('change', () => { store({ duplicates: dupSel.value }); app.emit('sample2', app.derived.sample2); });

  async function forget() {
    seq++;
    await app.save('files.chart2', undefined);
    await app.save('chart2', undefined);
    delete app.derived.sample2;
    input.value = '';
    fileState.textContent = summary.textContent = note.textContent = '';
    tableBox.replaceChildren();
    editorBox.replaceChildren();
    editor = null;
    remove.hidden = true;
    panel.dataset.state = 'empty';
    try { await engine.call('forget', { slot: 'chart2' }); } catch { /* the worker may have been restarted */ }
    app.emit('sample2', null);
  }

  /// A stored second image (a reload): decoded and sampled at its stored corners.
  async function restore() {
    if (!saved().chart) chartSel.value = firstChart();   // the session's layout is known by now
    const f = app.session['files.chart2'];
    if (!f) return;
    if (await decode(f)) {
      if (saved().corners) { editor.setCorners(saved().corners); await resample(); } else await detect();
    }
  }

  return { restore, resample, input, forget, get editor() { return editor; } };
}

/// The recipe of a fit on the chart image(s) of step 2: `recipe` itself with one image, or with
/// an `images` list — the first image's stages, then the second's (its chart's layout and
/// reference, step 1's illuminant and observer, no capture calibration) — and `duplicates`.
/// `exclude(flags)`: whether the fit leaves a flagged patch out.
export async function withImages(app, recipe, exclude) {
  const s2 = app.derived.sample2, c2 = app.session.chart2;
  if (!s2 || !c2?.corners) return recipe;
  const first = app.session['files.chart'];
  const sha = (app.derived.chartDigest ??= { bytes: null, sha256: '' });
  if (sha.bytes !== first.bytes) Object.assign(sha, { bytes: first.bytes, sha256: await app.engine.call('digest', { bytes: first.bytes }) });
  const { reference, capture, sampling } = recipe;
  const excludeFlagged = sampling.exclude_flagged;
  return {
    ...recipe,
    images: [
      { name: first.name, sha256: sha.sha256, reference, capture, sampling },
      { name: app.session['files.chart2'].name, sha256: c2.sha256,
        reference: { chart: c2.chart, illuminant: reference.illuminant, observer: reference.observer },
        sampling: { layout: { chart: c2.chart }, corners: s2.corners, area: sampling.area,
          exclude: excludeFlagged ? [] : s2.ids.filter((id, i) => exclude(s2.flags[i])), exclude_flagged: excludeFlagged } },
    ],
    duplicates: c2.duplicates ?? 'once',
  };
}

/// What the worker's fit pairs each image of `recipe.images` with: its sample (the engine's
/// ChartSample) and, for a reference file, the page's reference.
export function chartsOf(app, recipe, sample, reference) {
  if (!recipe.images?.length) return undefined;
  const { layout, homography, patches } = app.derived.sample2;
  return [{ sample, reference }, { sample: { layout, homography, patches }, reference: null }];
}
