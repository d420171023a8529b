// Step 2's second chart image (issue 48, docs/multi-image.md): "Add another chart image" — another
// photograph (any built-in chart; its reference is that chart's under step 1's illuminant and
// observer), decoded into the worker's slot 'chart2', its corners found by detection or dragged by
// hand, sampled as the first. The Fit then trains on the union of both charts' patches exactly as
// `tristim fit --recipe r.json --raw a --raw b` does: withImages() turns the fit's recipe into one
// with an `images` list, chartsOf() gives the worker each image's sample.
// Two charts in one image (docs/multi-image.md): when detection finds a second chart in step 2's
// own image, "Use both charts found" makes it the second chart (useCandidate: `sameImage`, sampled
// in the first image's slot with its frames and light trap); the recipe then lists that file twice,
// each entry with its own corners, as `tristim fit --recipe r.json --raw a --raw a` takes it.
import { h, field, select, showError, clearError, fileBytes, progressBar } from '../lib/ui.js';
import { CornerEditor } from './corners.js';
import { patchTable } from './patch_table.js';

/// Mounts the second image's panel in `parent`; returns {restore, resample, input, forget, editor,
/// useCandidate, firstChanged}. ensureFirst(): step 2's own image is decoded in this worker.
export function mountSecond(parent, app, { ensureFirst }) {
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
  // The second image's own dark frames and flat field (Abed 2013 App. C steps 1-2), decoded into
  // the worker's 'dark2' / 'flat2' slots, which calibrate 'chart2' (step 2's flat-field mode).
  const FRAME_SLOTS = { dark2: 'Its dark frame(s)', flat2: 'Its flat field' };
  const frameIns = {}, frameStates = {}, frameGen = {};
  const framesBox = h('div', { class: 'controls second-frames', hidden: true });
  for (const [slot, label] of Object.entries(FRAME_SLOTS)) {
    frameIns[slot] = h('input', { type: 'file', dataset: { slot }, multiple: slot === 'dark2' });
    frameStates[slot] = h('span', { class: 'file-state' });
    framesBox.append(h('div', { class: 'field-group' }, field(label, frameIns[slot], slot === 'dark2'
      ? 'Lens capped, same settings as this image; several files are averaged' : 'A uniform surface filling this image\'s frame'),
    frameStates[slot], h('button', { type: 'button', 'aria-label': `Remove ${label.toLowerCase()}`, onclick: () => forgetFrame(slot) }, 'Remove')));
    frameIns[slot].addEventListener('change', () => setFrames(slot, [...frameIns[slot].files]));
  }
  // Its reference: the chart's built-in data, or a file of the user's (CSV/CGATS, as step 1 takes),
  // read under step 1's illuminant and observer (app.derived.reference2; the recipe's entry then
  // has a "file" reference, and `fit --recipe` takes its --xyz).
  const refIn = h('input', { type: 'file', accept: '.csv,.txt,.cgats,.ti3,.it8', dataset: { role: 'chart2-reference' } });
  const refState = h('span', { class: 'file-state' });
  const refClear = h('button', { type: 'button', hidden: true, onclick: () => setReference(null) }, 'Use the built-in reference');
  framesBox.append(h('div', { class: 'field-group' }, field('Its reference file (optional)', refIn,
    'Measured colours of this chart (CSV or CGATS: XYZ, L*a*b* or spectra), in place of the built-in ones'), refState, refClear));
  refIn.addEventListener('change', () => { if (refIn.files[0]) setReference(refIn.files[0]); });
  const note = h('p', { class: 'detect-text', 'aria-live': 'polite' });
  const summary = h('p', { class: 'summary', 'aria-live': 'polite' });
  const tableBox = h('div', { class: 'table-box' });
  const panel = h('fieldset', { class: 'second-chart', dataset: { state: 'empty' } },
    h('legend', {}, 'Add another chart image (optional): the fit trains on both charts\' patches'),
    h('div', { class: 'controls' }, h('div', { class: 'field-group' },
      field('Second chart image', input, 'Another photograph: the same chart elsewhere in the frame, or another chart (RAW, TIFF, PNG or JPEG)'), fileState, remove),
    field('Its chart (layout and reference)', chartSel, 'The reference is this chart under the illuminant and observer of step 1, unless a reference file is given below'),
    field('Patches of the same colour', dupSel)), framesBox,
    progress.el, h('div', { class: 'images-layout' }, h('div', {}, editorBox, note), h('div', {}, summary, tableBox)));
  parent.append(panel);

  // The second chart of step 2's own image: that image's layout (the chart detection found twice).
  const same = () => !!saved().sameImage;
  const layout = () => (same() ? app.session.layout : { chart: chartSel.value });
  const area = () => app.session.sampleOptions?.area ?? 0.5;
  const store = (patch) => app.save('chart2', { ...saved(), ...patch });
  let decodedGen = -1;

  async function setFile(file) {
    clearError(input);
    let bytes;
    try { bytes = await fileBytes(file); } catch (e) { showError(input, e, file.name); return; }
    if (same()) await store({ sameImage: undefined, corners: undefined });   // a file replaces the first image's second chart
    if (!(await decode({ name: file.name, bytes }))) return;
    if (!saved().chart) chartSel.value = firstChart();
    await app.save('files.chart2', { name: file.name, bytes: bytes.buffer });
    await store({ chart: chartSel.value, duplicates: dupSel.value, corners: undefined, sameImage: undefined, sha256: await engine.call('digest', { bytes }) });
    await detect();
  }
  input.addEventListener('change', () => { if (input.files[0]) setFile(input.files[0]); });

  async function decode(file) {
    progress.start(`Decoding ${file.name}…`);
    try {
      const r = await engine.call('decode', { slot: 'chart2', bytes: new Uint8Array(file.bytes).slice().buffer });
      decodedGen = engine.generation;
      fileState.textContent = `${file.name} — ${r.width}×${r.height}`;
      shown(r);
      return true;
    } catch (e) {
      if (e.code !== 'CANCELLED') showError(input, e, file.name);
      return false;
    } finally {
      progress.done();
    }
  }
  /// The panel shows image r ({width, height, preview}) with the layout's grid.
  function shown(r) {
    chartSel.disabled = same();
    framesBox.hidden = same();   // the second chart of step 2's image has that image's frames
    if (same() && app.session.layout?.chart) chartSel.value = app.session.layout.chart;
    (editor ?? newEditor()).setImage(r);
    editor.setLayout(layout());
    remove.hidden = false;
    panel.dataset.state = 'decoded';
  }
  /// Step 2's own image in this panel (its second chart), with its preview when the worker has it.
  async function showFirst() {
    if (!(await ensureFirst())) return false;
    const img = app.derived.image;
    fileState.textContent = `the second chart in ${app.session['files.chart']?.name} — ${img.width}×${img.height}`;
    shown(img);
    try { const preview = await engine.call('preview', { slot: 'chart' }); if (preview) editor?.setImage({ ...img, preview }); } catch { /* drawn without it */ }
    return !!editor;
  }

  /// "Use both charts found": candidate c (a detection of step 2's layout in its own image) becomes
  /// the second chart; a second image file loaded before is dropped.
  async function useCandidate(c) {
    seq++;
    if (app.session['files.chart2']) {
      await app.save('files.chart2', undefined);
      try { await engine.call('forget', { slot: 'chart2' }); } catch { /* the worker may have been restarted */ }
    }
    input.value = '';
    await app.save('chart2', { sameImage: true, chart: app.session.layout?.chart, duplicates: dupSel.value, corners: Array.from(c.corners) });
    if (!(await showFirst())) return null;
    editor.setCorners(c.corners);
    note.textContent = `Second chart found in the same image (confidence ${c.confidence.toFixed(2)}). Drag the handles to correct them.`;
    return resample();
  }
  /// Step 2's own image or layout changed: its second chart, if that is the second chart, is gone.
  function firstChanged() {
    if (same()) forget();
  }

  /// Decodes the stored files again when the worker was restarted since.
  async function ensureDecoded() {
    const f = app.session['files.chart2'];
    if (!f || !(decodedGen === engine.generation || await decode(f))) return false;
    for (const slot of Object.keys(FRAME_SLOTS)) {
      const fr = app.session[`files.${slot}`];
      if (fr && frameGen[slot] !== engine.generation && !(await decodeFrames(slot, fr))) return false;
    }
    return true;
  }

  /// Decodes {name, list: [{name, bytes}]} into a frame slot; the worker calibrates 'chart2' with it
  /// (refused, e.g. FRAME_MISMATCH, next to its input: the slot keeps what it had).
  async function decodeFrames(slot, entry) {
    clearError(frameIns[slot]);
    const copies = entry.list.map((f) => new Uint8Array(f.bytes).slice().buffer);
    const msg = slot === 'dark2' ? { slot, bytesList: copies } : { slot, bytes: copies[0], flatMode: entry.mode };
    try {
      await engine.call('decode', msg, { transfer: copies });
      frameGen[slot] = engine.generation;
      frameStates[slot].textContent = entry.name;
      return true;
    } catch (e) {
      if (e.code !== 'CANCELLED') showError(frameIns[slot], e, entry.name);
      return false;
    }
  }
  async function setFrames(slot, files) {
    if (!files.length) return;
    clearError(frameIns[slot]);
    let list;
    try { list = await Promise.all(files.map(async (f) => ({ name: f.name, bytes: (await fileBytes(f)).buffer }))); } catch (e) {
      showError(frameIns[slot], e, files.map((f) => f.name).join(', '));
      return;
    }
    const entry = { name: list.map((f) => f.name).join(', '), list, ...(slot === 'flat2' ? { mode: app.session.flatMode ?? 'pixel' } : {}) };
    if (!(await ensureDecoded()) || !(await decodeFrames(slot, entry))) return;
    await app.save(`files.${slot}`, entry);
    await resample();
  }
  async function forgetFrame(slot, again = true) {
    await app.save(`files.${slot}`, undefined);
    frameIns[slot].value = frameStates[slot].textContent = '';
    clearError(frameIns[slot]);
    try { await engine.call('forget', { slot }); } catch { /* the worker may have been restarted */ }
    if (again) await resample();
  }

  /// The ReferenceChart (+ data_digest) of reference file f under step 1's illuminant and observer.
  const parseReference = (f) => {
    const s = app.derived.reference?.settings ?? {};
    return engine.call('parseReference', { text: f.text, fileName: f.name, illuminant: s.illuminant ?? 'D50', observer: s.observer ?? '1931' });
  };
  const showReference = (f, ref) => {
    app.derived.reference2 = ref;
    refState.textContent = `${f.name}: ${ref.ids.length} patches`;
    refClear.hidden = false;
  };
  /// Reads the stored reference file (if any) into app.derived.reference2 (its error next to its input).
  async function readReference() {
    const f = saved().referenceFile;
    clearError(refIn);
    delete app.derived.reference2;
    refState.textContent = '';
    refClear.hidden = !f;
    if (!f || same()) return;
    try { showReference(f, await parseReference(f)); } catch (e) { if (e.code !== 'CANCELLED') showError(refIn, e, f.name); }
  }
  /// A new reference file (null: back to the built-in chart's); one that does not read is refused
  /// next to its input and the previous one stays.
  async function setReference(file) {
    clearError(refIn);
    if (file) {
      try {
        const f = { name: file.name, text: await file.text() };
        const ref = await parseReference(f);
        await store({ referenceFile: f });
        showReference(f, ref);
      } catch (e) {
        if (e.code !== 'CANCELLED') showError(refIn, e, file.name);
        return;
      }
    } else {
      await store({ referenceFile: undefined });
      refIn.value = '';
      await readReference();
    }
    app.emit('sample2', app.derived.sample2);
  }
  app.on('reference', () => { if (saved().referenceFile) readReference().then(() => app.emit('sample2', app.derived.sample2)); });

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
    const corners = saved().corners, one = same();
    if (!corners || !(await (one ? ensureFirst() : ensureDecoded()))) return null;
    // The same image: sampled as step 2 samples it, after its light trap (its frames are the slot's).
    const t = one ? app.session.lightTrap : null;
    const lightTrap = t ? [t.x, t.y, t.x + t.w, t.y, t.x + t.w, t.y + t.h, t.x, t.y + t.h] : null;
    try {
      const s = await engine.call('sample', { slot: one ? 'chart' : 'chart2', layout: layout(), corners, sampleOptions: { area: area() }, lightTrap });
      if (n !== seq) return null;
      clearError(editor.el);
      s.corners = Array.from(corners);
      app.derived.sample2 = s;
      editor.setSample(s);
      tableBox.replaceChildren(patchTable(s));
      summary.textContent = `Second ${one ? 'chart' : 'image'}: ${s.ids.length} patches sampled; ${s.flags.filter((f) => f.length).length} flagged.`;
      panel.dataset.state = 'sampled';
      panel.dataset.frames = one ? '' : Object.keys(FRAME_SLOTS).filter((k) => app.session[`files.${k}`]).join(' ');
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
    for (const slot of Object.keys(FRAME_SLOTS)) if (app.session[`files.${slot}`]) await forgetFrame(slot, false);
    await app.save('files.chart2', undefined);
    await app.save('chart2', undefined);
    delete app.derived.sample2;
    delete app.derived.reference2;
    refIn.value = refState.textContent = '';
    refClear.hidden = true;
    clearError(refIn);
    input.value = '';
    fileState.textContent = summary.textContent = note.textContent = '';
    tableBox.replaceChildren();
    editorBox.replaceChildren();
    editor = null;
    remove.hidden = true;
    framesBox.hidden = true;
    chartSel.disabled = false;
    panel.dataset.state = 'empty';
    try { await engine.call('forget', { slot: 'chart2' }); } catch { /* the worker may have been restarted */ }
    app.emit('sample2', null);
  }

  /// A stored second image (a reload): decoded and sampled at its stored corners.
  async function restore() {
    if (!saved().chart) chartSel.value = firstChart();   // the session's layout is known by now
    if (same() && saved().corners) {
      if (await showFirst()) { editor.setCorners(saved().corners); await resample(); }
      return;
    }
    const f = app.session['files.chart2'];
    if (!f) return;
    for (const slot of Object.keys(FRAME_SLOTS)) if (app.session[`files.${slot}`]) frameStates[slot].textContent = app.session[`files.${slot}`].name;
    if (await ensureDecoded()) {
      await readReference();
      if (saved().corners) { editor.setCorners(saved().corners); await resample(); } else await detect();
    }
  }

  return { restore, resample, input, forget, useCandidate, firstChanged, get editor() { return editor; } };
}

/// The recipe of a fit on the chart image(s) of step 2: `recipe` itself with one image, or with
/// an `images` list — the first image's stages, then the second's (its chart's layout and
/// reference, step 1's illuminant and observer, its own dark frames and flat field; the second chart of the
/// first image: that image's file and stages, its own corners) — and `duplicates`.
/// `exclude(flags)`: whether the fit leaves a flagged patch out.
export async function withImages(app, recipe, exclude) {
  const s2 = app.derived.sample2, c2 = app.session.chart2;
  if (!s2 || !c2?.corners) return recipe;
  const first = app.session['files.chart'];
  const sha = (app.derived.chartDigest ??= { bytes: null, sha256: '' });
  if (sha.bytes !== first.bytes) Object.assign(sha, { bytes: first.bytes, sha256: await app.engine.call('digest', { bytes: first.bytes }) });
  const { reference, capture, sampling } = recipe;
  const excludeFlagged = sampling.exclude_flagged;
  const own = { corners: s2.corners, area: sampling.area,
    exclude: excludeFlagged ? [] : s2.ids.filter((id, i) => exclude(s2.flags[i])), exclude_flagged: excludeFlagged };
  return {
    ...recipe,
    images: [
      { name: first.name, sha256: sha.sha256, reference, capture, sampling },
      c2.sameImage
        ? { name: first.name, sha256: sha.sha256, reference, capture, sampling: { ...sampling, ...own } }
        : { name: app.session['files.chart2'].name, sha256: c2.sha256,
          reference: { chart: c2.referenceFile ? 'file' : c2.chart, data_digest: c2.referenceFile ? app.derived.reference2?.data_digest ?? '' : '',
            illuminant: reference.illuminant, observer: reference.observer }, ...framesOf(app),
          sampling: { layout: { chart: c2.chart }, ...own } },
    ],
    duplicates: c2.duplicates ?? 'once',
  };
}

/// The capture stage of the second image's own frames ({} without any: the entry has none).
function framesOf(app) {
  const dark = app.session['files.dark2'], flat = app.session['files.flat2'], radial = flat?.mode === 'radial';
  if (!dark && !flat) return {};
  return { capture: { dark_frames: dark?.list.length ?? 0, dark_mode: 'per_pixel', flat_field: !!flat && !radial, falloff: !!flat && radial } };
}

/// What the worker's fit pairs each image of `recipe.images` with: its sample (the engine's
/// ChartSample) and, for a reference file, the page's reference (the second chart of the first
/// image shares the first's).
export function chartsOf(app, recipe, sample, reference) {
  if (!recipe.images?.length) return undefined;
  const { layout, homography, patches } = app.derived.sample2;
  const { data_digest, ...own } = app.derived.reference2 ?? {};   // the second image's reference file, if any
  const second = app.session.chart2?.sameImage ? reference : (app.session.chart2?.referenceFile && app.derived.reference2 ? own : null);
  return [{ sample, reference }, { sample: { layout, homography, patches }, reference: second }];
}

/// What the second chart is called in the page's text: its file, or the first image's second chart.
export function secondName(app) {
  return app.session.chart2?.sameImage ? `${app.session['files.chart']?.name}: its second chart` : app.session['files.chart2']?.name;
}

/// The source files of a fit on `recipe` in its `images` order (a share link's `sources`).
export function sourceKeys(app, recipe) {
  if (!recipe.images?.length) return ['files.chart'];
  return ['files.chart', app.session.chart2?.sameImage ? 'files.chart' : 'files.chart2'];
}
