// One extra chart image of step 2 (issue 48, docs/multi-image.md): chart image k (k = 2, 3, …) —
// another photograph decoded into the worker's slot 'chart<k>'; its layout (a built-in chart, or a
// custom grid from the engine's layout option table, layout_inputs.js); its corners found by
// detection or dragged by hand; its own dark frames and flat field (extra_frames.js), light trap
// (light_trap.js) and reference (extra_reference.js); sampled as step 2's image is.
// Session: 'chart<k>' {chart, layout, corners, sha256, lightTrap, referenceFile, sameImage} and
// 'files.chart<k>'; the sample is app.derived['sample<k>'].
// Chart image 2 may instead be the second chart detection found in step 2's own image
// (useCandidate: `sameImage`, sampled in that image's slot with its frames and light trap).
import { h, field, select, showError, clearError, fileBytes, progressBar } from '../lib/ui.js';
import { CornerEditor } from './corners.js';
import { patchTable } from './patch_table.js';
import { customGrid, layoutName } from './layout_inputs.js';
import { lightTrapBox } from './light_trap.js';
import { extraFrames } from './extra_frames.js';
import { extraReference } from './extra_reference.js';

/// Chart image k's panel: {el, k, restore, resample, useCandidate, empty, dispose, editor}.
/// ensureFirst(): step 2's own image is decoded in this worker; changed(): this image's sample or
/// reference changed; remove(k): the user removed it; more: controls shown beside its chart picker.
export function mountPanel(app, k, { ensureFirst, changed, remove, more = [] }) {
  const { engine } = app;
  const slot = `chart${k}`, sampleKey = `sample${k}`;
  const saved = () => app.session[slot] ?? {};
  const store = (patch) => app.save(slot, { ...saved(), ...patch });
  const same = () => !!saved().sameImage;
  const layouts = Object.keys(app.catalog.layouts);
  // By default the first image's chart (another shot of it), else the engine's first chart.
  const firstChart = () => (app.session.layout?.chart !== 'custom' && layouts.includes(app.session.layout?.chart) ? app.session.layout.chart : layouts.find((id) => id !== 'custom'));
  const input = h('input', { type: 'file', dataset: { slot } });
  const fileState = h('span', { class: 'file-state' });
  const chartSel = select(layouts.map((value) => ({ value, label: layoutName(app, value) })), saved().chart ?? firstChart());
  chartSel.dataset.role = `${slot}-chart`;
  const grid = customGrid(app, saved().layout ?? {});
  const removeBtn = h('button', { type: 'button', hidden: true, class: 'remove-image', onclick: () => remove(k) }, 'Remove this image');
  const progress = progressBar(`Decoding chart image ${k}`);
  let editor = null;   // made at the first decode
  const editorBox = h('div', { class: 'second-editor' });
  const trap = lightTrapBox({ engine: app.engine, editor: () => editor, stored: () => saved().lightTrap, save: async (r) => { await store({ lightTrap: r }); await resample(); } });
  const frames = extraFrames(app, k, { ensureImage: () => ensureDecoded(), resample: () => resample() });
  const ref = extraReference(app, k, { saved, store, same, changed: () => changed() });
  const ownBox = h('div', { class: 'controls second-frames', hidden: true }, frames.el, ref.el, trap.el);
  const note = h('p', { class: 'detect-text', 'aria-live': 'polite' });
  const summary = h('p', { class: 'summary', 'aria-live': 'polite' });
  const tableBox = h('div', { class: 'table-box' });
  const el = h('fieldset', { class: 'second-chart', dataset: { state: 'empty', slot } },
    h('legend', {}, k === 2 ? 'Add another chart image (optional): the fit trains on every chart\'s patches' : `Chart image ${k}`),
    h('div', { class: 'controls' }, h('div', { class: 'field-group' },
      field(k === 2 ? 'Second chart image' : `Chart image ${k}`, input, 'Another photograph: the same chart elsewhere in the frame, or another chart (RAW, TIFF, PNG or JPEG)'), fileState, removeBtn),
    field('Its chart (layout and reference)', chartSel, 'The reference is this chart under the illuminant and observer of step 1, unless a reference file is given below (a custom grid needs one)'),
    grid.el, ...more), ownBox,
    progress.el, h('div', { class: 'images-layout' }, h('div', {}, editorBox, note), h('div', {}, summary, tableBox)));
  grid.el.hidden = chartSel.value !== 'custom';

  /// The engine's LayoutOptions of this image (the first image's when it is that image's second chart).
  const layout = () => (same() ? app.session.layout : grid.read(chartSel.value));
  const area = () => app.session.sampleOptions?.area ?? 0.5;
  let decodedGen = -1, seq = 0, timer = null;

  async function setFile(file) {
    clearError(input);
    let bytes;
    try { bytes = await fileBytes(file); } catch (e) { showError(input, e, file.name); return; }
    if (same()) await store({ sameImage: undefined, corners: undefined });   // a file replaces the first image's second chart
    if (!(await decode({ name: file.name, bytes }))) return;
    await app.save(`files.${slot}`, { name: file.name, bytes: bytes.buffer });
    await store({ chart: chartSel.value, corners: undefined, sameImage: undefined, sha256: await engine.call('digest', { bytes }) });
    await detect();
  }
  input.addEventListener('change', () => { if (input.files[0]) setFile(input.files[0]); });

  async function decode(file) {
    progress.start(`Decoding ${file.name}…`);
    try {
      const r = await engine.call('decode', { slot, bytes: new Uint8Array(file.bytes).slice().buffer });
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
    ownBox.hidden = same();   // the second chart of step 2's image has that image's frames and trap
    if (same() && app.session.layout?.chart) chartSel.value = app.session.layout.chart;
    grid.el.hidden = same() || chartSel.value !== 'custom';
    if (!editor) {
      editor = new CornerEditor({ onChange: (c, final) => { note.textContent = 'Corners placed by hand.'; return cornersChanged(c, final); }, grid: (L, corners) => engine.call('grid', { layout: L, corners }), clipId: `image-clip-${k}` });
      editorBox.replaceChildren(editor.el);
    }
    editor.setImage(r);
    try { editor.setLayout(layout()); } catch { /* a custom box that cannot be read: shown at its change */ }
    trap.show();
    removeBtn.hidden = false;
    el.dataset.state = 'decoded';
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
  /// this chart; an image file loaded here before is dropped.
  async function useCandidate(c) {
    seq++;
    if (app.session[`files.${slot}`]) {
      await frames.forgetAll();
      await app.save(`files.${slot}`, undefined);
      try { await engine.call('forget', { slot }); } catch { /* the worker may have been restarted */ }
    }
    input.value = '';
    ref.clear();
    await app.save(slot, { sameImage: true, chart: app.session.layout?.chart, corners: Array.from(c.corners) });
    if (!(await showFirst())) return null;
    editor.setCorners(c.corners);
    note.textContent = `Second chart found in the same image (confidence ${c.confidence.toFixed(2)}). Drag the handles to correct them.`;
    return resample();
  }

  /// Decodes the stored files again when the worker was restarted since.
  async function ensureDecoded() {
    const f = app.session[`files.${slot}`];
    if (!f || !(decodedGen === engine.generation || await decode(f))) return false;
    return frames.ensure();
  }

  /// Looks for the chosen chart; takes its corners, or leaves the handles for the user to drag.
  async function detect() {
    note.textContent = 'Looking for the chart…';
    try {
      const { candidates } = await engine.call('detect', { slot, layout: layout() });
      if (!editor) return;   // removed meanwhile
      const c = candidates[0];
      editor.setCorners(c.corners);
      note.textContent = `Corners found automatically (confidence ${c.confidence.toFixed(2)}). Drag the handles to correct them.`;
    } catch (e) {
      if (e.code === 'CANCELLED' || !editor) return;
      if (e.input) { showError(e.input, e, 'Layout'); return; }
      editor.reset();   // (its onChange says 'by hand': the reason follows)
      note.textContent = `No ${chartSel.selectedOptions[0]?.textContent ?? 'chart'} found (${e.message}): drag the four corners onto the chart's outer patch corners (A1 first).`;
      return;
    }
    await cornersChanged(editor.corners, true);
  }
  function cornersChanged(c, final) {
    clearTimeout(timer);
    return new Promise((resolve) => {
      timer = setTimeout(async () => { await store({ corners: Array.from(c) }); resolve(resample()); }, final ? 0 : 120);
    });
  }

  /// Samples this image at its corners: app.derived['sample<k>'], then changed().
  async function resample() {
    const n = ++seq;
    const corners = saved().corners, one = same();
    if (!corners || !(await (one ? ensureFirst() : ensureDecoded()))) return null;
    // The same image: sampled as step 2 samples it, after its light trap (its frames are the slot's).
    const t = one ? app.session.lightTrap : null;
    const lightTrap = one ? (t ? [t.x, t.y, t.x + t.w, t.y, t.x + t.w, t.y + t.h, t.x, t.y + t.h] : null) : trap.corners();
    try {
      const s = await engine.call('sample', { slot: one ? 'chart' : slot, layout: layout(), corners, sampleOptions: { area: area() }, lightTrap });
      if (n !== seq) return null;
      clearError(editor.el);
      if (!one) trap.showResult(s, lightTrap);
      if (s.lightTrap) s.lightTrapCorners = lightTrap;
      s.corners = Array.from(corners);
      app.derived[sampleKey] = s;
      editor.setSample(s);
      tableBox.replaceChildren(patchTable(s));
      summary.textContent = `Chart ${one ? '2 (in step 2\'s image)' : `image ${k}`}: ${s.ids.length} patches sampled; ${s.flags.filter((f) => f.length).length} flagged`
        + `${s.missing?.length ? `; ${s.missing.length} outside the frame (${s.missing.join(', ')})` : ''}.`;
      el.dataset.state = 'sampled';
      el.dataset.frames = one ? '' : frames.present();
      el.dataset.trap = s.lightTrap ? 'subtracted' : '';
      changed();
      return s;
    } catch (e) {
      if (n !== seq || e.code === 'CANCELLED') return null;
      if (e.input) { showError(e.input, e, 'Layout'); return null; }
      showError(editor.el, e, `Chart image ${k} corners`);
      editor.setSample(null, e.code);
      return null;
    }
  }

  /// A new layout (again: look for the chart anew, as for another built-in chart).
  async function layoutChanged(again) {
    for (const b of grid.boxes) clearError(b);
    grid.el.hidden = chartSel.value !== 'custom';
    let L;
    try { L = layout(); } catch (e) { showError(e.input, e, 'Layout'); return; }
    editor?.setLayout(L);
    await store({ chart: chartSel.value, layout: chartSel.value === 'custom' ? L : undefined });
    if (app.session[`files.${slot}`]) await (again || !saved().corners ? detect() : resample());
  }
  chartSel.addEventListener('change', () => layoutChanged(chartSel.value !== 'custom'));
  for (const b of grid.boxes) b.addEventListener('change', () => layoutChanged(false));

  /// A stored image (a reload): decoded and sampled at its stored corners.
  async function restore() {
    if (!saved().chart) chartSel.value = firstChart();   // the session's layout is known by now
    grid.el.hidden = chartSel.value !== 'custom';
    if (same() && saved().corners) {
      if (await showFirst()) { editor.setCorners(saved().corners); await resample(); }
      return;
    }
    if (!app.session[`files.${slot}`]) return;
    frames.names();
    if (await ensureDecoded()) {
      await ref.read();
      if (saved().corners) { editor.setCorners(saved().corners); await resample(); } else await detect();
    }
  }

  /// The panel is removed: its worker slots freed, its derived data dropped (the session's entries
  /// are the caller's).
  async function dispose() {
    seq++;
    ref.dispose();
    delete app.derived[sampleKey];
    delete app.derived[`reference${k}`];
    for (const s of [slot, ...frames.slots]) { try { await engine.call('forget', { slot: s }); } catch { /* the worker may have been restarted */ } }
    el.remove();
  }

  return { el, k, restore, resample, useCandidate, dispose, empty: () => el.dataset.state === 'empty', get editor() { return editor; } };
}
