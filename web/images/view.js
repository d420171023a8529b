// Step 2: the chart image — camera RAW, or TIFF/PNG/JPEG read as stored (its encoding shown, with
// a pointer to the linearisation step) — plus optional dark frame and flat field, decoded in the worker; the
// preview with four draggable corner handles and the patch grid; the per-patch table with flags,
// re-sampled as the corners move; automatic chart detection (a new image takes the detected
// corners; an image that already has corners gets the detected chart as a proposal to use or
// ignore; "Detect again"). Emits 'sample'.
import { h, field, select, showError, clearError, errorSlot, numberValue, progressBar, fmt, fileBytes } from '../lib/ui.js';
import { customGrid, optionInput, labelOf, layoutName } from './layout_inputs.js';
import { lightTrapBox } from './light_trap.js';
import { CornerEditor } from './corners.js';
import { patchTable } from './patch_table.js';
import { fetchExample } from './example.js';
import { mountSecond } from './second.js';

const SLOTS = {
  chart: { label: 'Chart image', hint: 'A photograph of the chart, evenly lit: camera RAW (DNG, CR2, NEF, ARW, …), or an 8/16-bit TIFF, 8/16-bit PNG or JPEG (read as stored: then choose a linearisation, step 2b)' },
  dark: { label: 'Dark frame(s) (optional)', hint: 'Same camera and settings, lens capped; several files are averaged (Abed et al. 2013, App. C step 1)' },
  flat: { label: 'Flat field (optional)', hint: 'A uniform white/grey surface filling the frame (App. C step 2)' },
};

export function mount(section, app) {
  const { engine } = app;
  const inputs = {};
  const names = {};
  const decodedGen = {};     // slot -> engine generation in which it was decoded
  const progress = progressBar('Decoding');
  const drop = h('div', { class: 'drop-zone', tabindex: -1 }, 'Drop a RAW, TIFF, PNG or JPEG file here, or choose one below.');
  const fileRow = h('div', { class: 'controls file-row' });
  for (const [slot, s] of Object.entries(SLOTS)) {
    inputs[slot] = h('input', { type: 'file', dataset: { slot }, multiple: slot === 'dark' });
    names[slot] = h('span', { class: 'file-state' });
    const clear = slot === 'chart' ? null : h('button', { type: 'button', 'aria-label': `Remove the ${s.label.replace(/ \(optional\)/, '').toLowerCase()}`, onclick: () => forget(slot) }, 'Remove');
    fileRow.append(h('div', { class: 'field-group' }, field(s.label, inputs[slot], s.hint), names[slot], clear));
    inputs[slot].addEventListener('change', () => {
      const fs = [...inputs[slot].files];
      if (slot === 'dark' && fs.length > 1) setFiles(slot, fs);
      else if (fs[0]) setFile(slot, fs[0]);
    });
  }
  // The engine's flat-field modes (MethodInfo rows: the citation is the option's title).
  const flatMode = select(app.catalog.flatFieldModes.map((m) => ({ value: m.id, label: m.label })), app.session.flatMode ?? 'pixel');
  for (const o of flatMode.options) o.title = app.catalog.flatFieldModes.find((m) => m.id === o.value)?.reference ?? '';
  flatMode.addEventListener('change', async () => {
    await app.save('flatMode', flatMode.value);
    const f = app.session['files.flat'];
    if (f && await decode('flat', f)) await resample();
  });
  // The layouts the engine has (chart_layout ids), named after the built-in charts.
  const chartName = (id) => layoutName(app, id);
  const layoutSel = select(Object.keys(app.catalog.layouts).map((value) => ({ value, label: chartName(value) })), app.session.layout?.chart ?? 'passport');
  layoutSel.dataset.role = 'layout';
  // The custom grid's and the sampled area's inputs from the engine's table (layout_inputs.js);
  // the session's values over the defaults.
  const grid = customGrid(app, app.session.layout ?? {});
  const customBox = grid.el;
  const areaSpec = app.catalog.layoutOptions.find((o) => o.name === 'area');
  const areaIn = optionInput(app, 'area', app.session.sampleOptions?.area, { 'data-role': 'sample-area' });
  const meta = h('p', { class: 'meta', 'aria-live': 'polite' });
  // A TIFF/PNG/JPEG: its non-linear encoding and what to do about it (the linearisation step).
  const encodingNote = h('p', { class: 'warning encoding-note', role: 'status', hidden: true });
  const editor = new CornerEditor({ onChange: (c, final) => cornersChanged(c, final), grid: (layout, corners) => engine.call('grid', { layout, corners }) });
  const cornerErr = h('p', { class: 'field-error', role: 'alert', hidden: true, id: 'corners-error' });
  editor.el.setAttribute('aria-describedby', 'corners-error');
  editor.el._errorSlot = cornerErr;
  const resetCorners = h('button', { type: 'button', onclick: () => { editor.reset(); } }, 'Reset corners');
  // Automatic detection: what was found, and the buttons to use it or look again.
  const detectText = h('p', { class: 'detect-text', 'aria-live': 'polite' });
  const acceptBtn = h('button', { type: 'button', class: 'primary', hidden: true, onclick: () => useDetected() }, 'Use the detected corners');
  const againBtn = h('button', { type: 'button', class: 'detect-again', disabled: true, onclick: () => detect() }, 'Detect again');
  // Two charts of the layout in this image (issue 48): the second becomes the second chart (second.js).
  let found = [];   // the last detection's candidates
  const bothBtn = h('button', { type: 'button', class: 'use-both', hidden: true, onclick: () => useBoth() }, 'Use both charts found');
  const detectErr = errorSlot(againBtn);
  const detectProgress = progressBar('Finding the chart');
  const detectPanel = h('div', { class: 'detect-panel', dataset: { state: 'idle' } }, detectText, acceptBtn, bothBtn, againBtn, detectProgress.el);
  let detection = null;  // {candidate, state: 'proposal' | 'in-use' | 'adjusted'}
  let unconfirmed = false;  // detection missed and the corners are still the ones from before: the table is stale
  // Light trap (Abed 2013 App. C step 1): its flare is subtracted before sampling (light_trap.js).
  const trap = lightTrapBox({ engine: app.engine, editor: () => editor, stored: () => app.session.lightTrap,
    save: async (r) => { await app.save('lightTrap', r); resample(); } });
  const tableBox = h('div', { class: 'table-box' });
  const sampleSummary = h('p', { class: 'summary', 'aria-live': 'polite' });

  fileRow.append(field('Flat-field correction', flatMode));
  section.append(
    fileRow, drop, progress.el, meta, encodingNote,
    h('div', { class: 'controls' }, field('Chart layout', layoutSel), customBox,
      field(labelOf(areaSpec), areaIn, areaSpec.description), resetCorners),
    h('div', { class: 'controls' }, trap.el),
    h('p', { class: 'hint' }, 'Drag the four corner handles onto the chart\'s outer patch corners (A1 top-left). '
      + 'With the keyboard: Tab to a handle, arrow keys move it 1 pixel (Shift: 10).'),
    h('div', { class: 'images-layout' }, h('div', {}, editor.el, cornerErr, detectPanel, detectErr), h('div', {}, sampleSummary, tableBox)));
  // "Add chart image" (issue 48): the fit trains on every chart image's patches (second.js).
  const second = mountSecond(section, app, { ensureFirst: () => ensureDecoded() });

  // Drag and drop onto the zone (or anywhere on this step) sets the chart RAW.
  for (const ev of ['dragover', 'dragenter']) section.addEventListener(ev, (e) => { e.preventDefault(); drop.classList.add('over'); });
  section.addEventListener('dragleave', () => drop.classList.remove('over'));
  section.addEventListener('drop', (e) => {
    e.preventDefault(); drop.classList.remove('over');
    const f = e.dataTransfer?.files?.[0];
    if (f) setFile('chart', f);
  });

  /// The engine's LayoutOptions for the chosen layout. A custom box that cannot be read (a typo;
  /// rows or columns left empty) throws INVALID_ARGUMENT carrying the box; gap and margins empty: 0.
  function layoutOptions() {
    return grid.read(layoutSel.value);
  }
  const sampleOptions = () => ({ area: numberValue(areaIn) });
  const layoutBoxes = [...grid.boxes, areaIn];
  function syncLayout(layout = layoutOptions()) {
    customBox.hidden = layoutSel.value !== 'custom';
    editor.setLayout(layout);
  }
  // A box that cannot be read shows why next to it; the grid, the sampling and the session keep
  // the last layout that could.
  function layoutChanged() {
    for (const c of layoutBoxes) clearError(c);
    let layout, sampling;
    try { layout = layoutOptions(); sampling = sampleOptions(); } catch (e) { customBox.hidden = layoutSel.value !== 'custom'; showError(e.input, e, 'Layout'); return; }
    syncLayout(layout);
    editor.setSample(null);
    if (detection) setDetection(null, 'idle', 'The layout changed: press “Detect again” to look for it.');
    app.save('layout', layout);
    app.save('sampleOptions', sampling);
    second.firstChanged();
    resample();
  }
  for (const el of [layoutSel, ...layoutBoxes]) el.addEventListener('change', layoutChanged);
  // A typo typed into an empty box, or cleared, gives no change event (its value is '' before and
  // after): the boxes are read again on leaving it.
  for (const el of layoutBoxes) el.addEventListener('blur', () => { if (el.hasAttribute('aria-invalid') || el.validity.badInput) layoutChanged(); });

  /// given: {corners, note} when the caller knows where the chart is (the Lab's own render): those
  /// corners are used as they are, with no detection, and the note says where they came from.
  async function setFile(slot, file, given = null) {
    clearError(inputs[slot]);
    let bytes;
    try { bytes = await fileBytes(file); } catch (e) { showError(inputs[slot], e, file.name); return; }
    const before = app.derived.image;
    const ok = await decode(slot, { name: file.name, bytes });
    if (ok) {
      await app.save(`files.${slot}`, { name: file.name, bytes: bytes.buffer });
      if (slot === 'chart') { await app.save('example', undefined); second.firstChanged(); }
      // A new chart image of another size gets fresh corners; same size keeps them (same set-up).
      const img = app.derived.image;
      const fresh = slot === 'chart' && !(before && img.width === before.width && img.height === before.height && app.session.corners);
      if (slot === 'chart' && given?.corners) {
        clearTimeout(timer);
        editor.setCorners(given.corners);
        await app.save('corners', Array.from(given.corners));
        setDetection(null, 'idle', given.note ?? '');
        await resample();
        return;
      }
      if (fresh) {
        await app.save('corners', undefined);
        editor.reset();
      }
      // Same size: the corners stay and the detection is only a proposal, so the table (and a fit
      // started from it) does not wait for it; new corners wait for the detection's.
      if (slot === 'chart' && fresh) await detect({ apply: true });
      await resample();
      if (slot === 'chart' && !fresh) detect();
    }
  }

  /// Several dark frames: decoded together and averaged by the engine.
  async function setFiles(slot, files) {
    clearError(inputs[slot]);
    let list;
    try { list = await Promise.all(files.map(async (f) => ({ name: f.name, bytes: (await fileBytes(f)).buffer }))); } catch (e) {
      showError(inputs[slot], e, files.map((f) => f.name).join(', '));
      return;
    }
    const entry = { name: list.map((f) => f.name).join(', '), list };
    if (await decode(slot, entry)) {
      await app.save(`files.${slot}`, entry);
      await resample();
    }
  }

  async function forget(slot) {
    await app.save(`files.${slot}`, undefined);
    names[slot].textContent = '';
    inputs[slot].value = '';
    clearError(inputs[slot]);
    try { await engine.call('forget', { slot }); } catch { /* the worker may have been restarted */ }
    await resample();
  }

  /// Decodes {name, bytes} into the worker's slot; shows progress and errors next to the input.
  /// The chart's preview is asked for after the decode, once the requests that follow the decode
  /// at once (the sampling) are queued: the table and the fit do not wait for the picture.
  let early = null;   // the example's decode, started by main.js before this view was mounted
  let previewSeq = 0;
  let previewAfter = null;   // restore(): a new session's preview waits for the first screen's compare
  let storeAfter = null;     // restore(): the example's RAW is written to storage after the first screen
  async function decode(slot, file) {
    progress.start(`Decoding ${file.name}…`);
    const started = slot === 'chart' && early?.bytes === file.bytes && early.generation === engine.generation ? early.decoding : null;
    const t0 = started ? early.t0 : performance.now();
    if (slot === 'chart') early = null;
    try {
      let r;
      if (started) r = await started;
      else {
        // The page keeps its own bytes: the worker gets copies (transferred).
        const copies = (file.list ?? [file]).map((f) => new Uint8Array(f.bytes).slice().buffer);
        const msg = file.list ? { slot, bytesList: copies } : { slot, bytes: copies[0] };
        if (slot === 'flat') msg.flatMode = flatMode.value;
        if (slot === 'chart') msg.previewSide = 0;
        r = await engine.call('decode', msg, { transfer: copies, onProgress: progress.update });
      }
      decodedGen[slot] = engine.generation;
      names[slot].textContent = `${file.name} — ${r.width}×${r.height} (decoded in ${((performance.now() - t0) / 1000).toFixed(2)} s)`
        + calibrationText(slot, r.calibration);
      if (slot === 'chart') {
        app.derived.image = r;
        againBtn.disabled = detectPanel.dataset.state === 'running';
        const m = r.metadata ?? {};
        const bits = [m.make, m.model, m.lens, m.iso && `ISO ${m.iso}`, m.shutter_s && `${fmtShutter(m.shutter_s)} s`,
          m.f_number && `f/${m.f_number}`, m.cfa_pattern && `${m.layout ?? ''} ${m.cfa_pattern}`, m.bits && `${m.bits} bit`, m.timestamp_iso].filter(Boolean);
        if (m.encoding === 'stored') {
          meta.textContent = `${[m.make, m.model, m.timestamp_iso].filter(Boolean).join(' · ')}${m.make || m.model ? ' — ' : ''}`
            + `${m.format.toUpperCase()}, ${m.bits}-bit ${m.layout === 'monochrome' ? 'grey' : 'RGB'}, ${r.width}×${r.height}, values as stored (0–${m.white_level}).`
            + ' The preview shows the stored values as they are.';
        } else {
          meta.textContent = `${bits.join(' · ')} — measurement image ${r.width}×${r.height} (half resolution, linear, no white balance).`
            + ' The preview below uses the camera matrix and sRGB gamma for display only.';
        }
        encodingNote.hidden = m.encoding !== 'stored';
        encodingNote.textContent = m.encoding === 'stored' ? encodingText(m) : '';
        // Same size as the image on screen: keep the handles where they are (they may have moved
        // since the last save); otherwise take the session's corners, or reset.
        const sameSize = editor.width === r.width && editor.height === r.height;
        editor.setImage(r);
        if (!app.session.corners) editor.reset();
        else if (!sameSize) editor.setCorners(app.session.corners);
        const seq = ++previewSeq, gen = engine.generation;
        const after = previewAfter ?? new Promise((r) => { setTimeout(r); });
        after.then(() => engine.call('preview', { slot: 'chart' })).then((preview) => {
          if (seq === previewSeq && gen === engine.generation && preview) editor.setImage({ ...r, preview });
        }, () => { /* the worker was restarted: the next decode asks again */ });
      }
      return true;
    } catch (e) {
      if (e.code !== 'CANCELLED') showError(inputs[slot], e, file.name);
      if (slot === 'chart' && !app.derived.image) meta.textContent = '';
      return false;
    } finally {
      progress.done();
    }
  }
  function calibrationText(slot, c) {
    const d = c?.dark, f = c?.flat;
    if (slot === 'dark' && d) return `; dark: ${d.frames} frame(s), mean ${d.mean.map((v) => fmt(v, 1)).join(' / ')} DN, noise ${d.noise.map((v) => fmt(v, 1)).join(' / ')} DN`;
    if (slot === 'flat' && f) return f.mode === 'radial' ? `; radial fall-off p1 ${fmt(f.p1, 4)}, p2 ${fmt(f.p2, 4)}, p3 ${fmt(f.p3, 4)}, rms residual ${fmt(f.rms_residual, 4)}` : `; flat field (${f.mode}) applied`;
    return '';
  }
  /// What a stored (non-linear) image means for the fit.
  function encodingText(m) {
    const declared = m.declared_colour ? ` The file declares ${m.declared_colour.split(';').join(', ')} — reported, not applied.` : '';
    return `Not linear: a ${m.format.toUpperCase()} holds display-encoded values (full scale ${m.white_level}), not values proportional to light.`
      + `${declared} Choose a linearisation in step 2b (gamma or sRGB if the encoding is known; Shen2008 or a grey-based curve to recover it from the chart) before fitting.`
      + (m.bits === 8 ? ' With 8 bits, patches at 0 or 255 are clipped and left out of the linearisation.' : '');
  }
  const fmtShutter = (t) => (t > 0 && t < 1 ? `1/${Math.round(1 / t)}` : `${t}`);

  /// Re-sends stored bytes when the worker was restarted (cancelled fit) since their decode.
  let ensuring = null;   // one re-decode at a time, shared by every caller
  function ensureDecoded() {
    ensuring ??= (async () => {
      for (const slot of Object.keys(SLOTS)) {
        const f = app.session[`files.${slot}`];
        if (f && decodedGen[slot] !== engine.generation) await decode(slot, f);
      }
      return decodedGen.chart === engine.generation;
    })().finally(() => { ensuring = null; });
    return ensuring;
  }

  // ---- automatic detection (worker handler: images/detect.js)
  const TURN = { 0: 'upright', 90: 'turned 90° clockwise', 180: 'upside down', 270: 'turned 90° anticlockwise' };
  const describe = (c) => `${chartName(c.chart)}, confidence ${fmt(c.confidence)}, `
    + (c.orientation_resolved ? TURN[c.orientation] ?? `${c.orientation}°` : 'orientation unknown (check that handle 1 is on A1)');
  const sameCorners = (a, b) => a.length === 8 && Array.from(a).every((v, i) => Math.abs(v - b[i]) < 1e-6);

  /// Shows the detection state: the panel's text and buttons, the proposal on the editor.
  function setDetection(candidate, state, text) {
    detection = candidate ? { candidate, state } : null;
    detectPanel.dataset.state = state;
    if (candidate) detectPanel.dataset.confidence = candidate.confidence.toFixed(3); else delete detectPanel.dataset.confidence;
    acceptBtn.hidden = state !== 'proposal';
    againBtn.disabled = state === 'running' || !app.derived.image;
    editor.setDetected(state === 'adjusted' ? null : candidate, { proposal: state === 'proposal' });
    detectText.textContent = text ?? {
      proposal: `Detected: ${candidate && describe(candidate)} — drawn dashed over the image. Use its corners, or keep yours.`,
      'in-use': `Corners found automatically: ${candidate && describe(candidate)}. Drag the handles to correct them.`,
      adjusted: `Corners found automatically (confidence ${candidate && fmt(candidate.confidence)}), then adjusted by hand.`,
      running: 'Looking for the chart…',
    }[state] ?? '';
  }

  /// Looks for the chosen layout in the chart image. apply: take the corners found (a new image);
  /// otherwise they are shown as a proposal unless they are the corners in use. When nothing is
  /// found the corners stay where they were, the detector's reason is shown, and a click near the
  /// chart (a seed point) or a rough box dragged around it runs detection again there (help).
  let detectSeq = 0;
  async function detect({ apply = false, help = null } = {}) {
    const seq = ++detectSeq;
    clearError(againBtn);
    setDetection(null, 'running');
    bothBtn.hidden = true;
    if (!(await ensureDecoded())) {
      if (seq === detectSeq) setDetection(null, 'idle');
      return null;
    }
    detectProgress.start('Finding the chart…');
    try {
      const { candidates } = await engine.call('detect', { layout: layoutOptions(), ...help }, { onProgress: detectProgress.update });
      if (seq !== detectSeq) return null;
      editor.askWhereTheChartIs(null);
      found = candidates;
      bothBtn.hidden = candidates.length < 2 || !!app.session.chart2?.sameImage;   // not while in use
      bothBtn.textContent = `Use both charts found (${candidates.length} in this image)`;
      const c = candidates[0];
      if (apply || sameCorners(editor.corners, c.corners)) useDetected(c);
      else setDetection(c, 'proposal');
      return c;
    } catch (e) {
      if (seq !== detectSeq || e.code === 'CANCELLED') return null;
      if (e.input) { setDetection(null, 'idle', 'A layout box could not be read: see the message next to it.'); showError(e.input, e, 'Layout'); return null; }
      const missed = e.code === 'CHART_NOT_FOUND';
      setDetection(null, 'none', missed
        ? `No ${chartName(layoutSel.value)} found ${help ? 'there' : 'in this image'}: ${e.message}. The corners were left where they were: `
          + 'click near the chart on the image, or drag a rough box around it, to look there again — or drag the corners onto it.'
        : 'Chart detection failed; the corners were left where they were.');
      if (missed) editor.askWhereTheChartIs((where) => detect({ apply: true, help: where }));
      if (missed) { unconfirmed = true; if (app.derived.sample) renderTable(app.derived.sample); }
      showError(againBtn, e, 'Chart detection');
      return null;
    } finally {
      if (seq === detectSeq) {
        detectProgress.done();
        detectPanel.dataset.runs = Number(detectPanel.dataset.runs ?? 0) + 1;   // finished detections (for tests)
      }
    }
  }
  /// Takes the detected corners (the proposal's, or c's).
  function useDetected(c = detection?.candidate) {
    if (!c) return;
    editor.setCorners(c.corners);
    setDetection(c, 'in-use');
    cornersChanged(editor.corners, true);
  }

  /// Step 2's chart on a candidate (the one in use, or the best), the next one as the second chart.
  async function useBoth() {
    const at = (c) => sameCorners(editor.corners, c.corners);
    if (!found.some(at)) useDetected(found[0]);
    const other = found.find((c) => !at(c));
    if (other && await second.useCandidate(other)) bothBtn.hidden = true;
  }

  let sampleSeq = 0;
  let timer = null;
  function cornersChanged(c, final) {
    unconfirmed = false;
    if (detection?.state === 'in-use' && !sameCorners(c, detection.candidate.corners)) setDetection(detection.candidate, 'adjusted');
    clearTimeout(timer);
    timer = setTimeout(() => { app.save('corners', Array.from(c)); resample(); }, final ? 0 : 120);
  }

  async function resample() {
    const seq = ++sampleSeq;
    if (!app.session['files.chart']) return null;
    if (!(await ensureDecoded())) {
      console.warn(`resample ${seq}: the chart image is not decoded in this worker`);
      return null;
    }
    const corners = Array.from(editor.corners);   // a copy: handles move while the worker samples
    try {
      const lightTrap = trap.corners();
      const s = await engine.call('sample', { layout: layoutOptions(), corners: Array.from(corners), sampleOptions: sampleOptions(), lightTrap });
      if (seq !== sampleSeq) return null;
      clearError(editor.el);
      trap.showResult(s, lightTrap);
      if (s.lightTrap) s.lightTrapCorners = lightTrap;
      s.corners = Array.from(corners);
      // Handles may have moved while the worker sampled: sample again until the table matches.
      if (editor.corners.some((v, i) => v !== corners[i])) setTimeout(resample, 0);
      app.derived.sample = s;
      editor.setSample(s);
      renderTable(s);
      app.mark('images', 'done');
      app.emit('sample', s);
      return s;
    } catch (e) {
      if (seq !== sampleSeq || e.code === 'CANCELLED') return null;
      if (e.input) { showError(e.input, e, 'Layout'); return null; }   // a layout box: shown at its change
      showError(editor.el, e, 'Corners');
      editor.setSample(null, e.code);
      if (app.derived.sample) {
        tableBox.classList.add('stale');
        sampleSummary.textContent = 'These corners were refused; the table shows the last good sampling.';
      }
      return null;
    }
  }

  function renderTable(s) {
    tableBox.classList.toggle('stale', unconfirmed);
    const flagged = s.flags.filter((f) => f.length).length;
    sampleSummary.textContent = unconfirmed
      ? 'No chart found in this image: the table shows the patches under the corners left from before, which may not lie on the chart.'
      : `${s.ids.length} patches sampled; ${flagged} flagged${s.missing?.length ? `; ${s.missing.length} outside the frame (${s.missing.join(', ')}): the fit uses the others` : ''}.`;
    tableBox.replaceChildren(patchTable(s, { stale: unconfirmed }));
  }

  /// Restores the session's files and corners (or the example on a first visit). The chart's own
  /// detection (a proposal) starts once `detectAfter` settles (the page passes the end of the first
  /// screen's compare, so the detection does not compete with it), at once without it; the preview
  /// once `previewAfter` settles (default: detectAfter), the example's write to storage once
  /// `storeAfter` settles (default: previewAfter).
  /// example: main.js's early fetch and decode of the example (images/example.js), for a new session.
  async function restore(fresh, { detectAfter = null, previewAfter: previewWait = detectAfter, storeAfter: storeWait = previewWait, example = null } = {}) {
    const L = app.session.layout;
    if (L) {
      layoutSel.value = L.chart;
      grid.set(L);
      // A session saved before the layout crossed as its JSON (margin_left …): saved in the new form.
      if ('margin_left' in L) app.save('layout', layoutOptions());
    }
    syncLayout();
    previewAfter = previewWait;
    storeAfter = storeWait;
    const saving = fresh ? await loadExample(example) : null;
    for (const slot of Object.keys(SLOTS)) {
      const f = app.session[`files.${slot}`];
      if (f && slot !== 'chart') names[slot].textContent = `${f.name}`;
    }
    if (app.session['files.chart']) {
      if (await ensureDecoded()) {
        await resample();
        // a proposal (or the corners' own detection); runs in the worker's queue
        if (detectAfter) detectAfter.then(() => detect()); else detect();
      }
    }
    previewAfter = storeAfter = null;
    await saving;
    await second.restore();
  }

  /// Loads the example into the session; resolves once it is in the session, with a promise of its
  /// settings being written to this browser's storage (its RAW is written after the first screen).
  async function loadExample(example) {
    try {
      const { cfg, bytes, decoding, t0, generation } = await (example ?? fetchExample());
      if (decoding) early = { bytes, decoding, t0, generation };
      const layout = cfg.layout ?? { chart: cfg.chart ?? 'passport' };
      layoutSel.value = layout.chart;
      if (cfg.area) areaIn.value = cfg.area;
      syncLayout();
      // The RAW is written to IndexedDB once the first screen is shown (restore's storeAfter),
      // or in a task of its own: the write takes the page and the browser a few hundred ms of
      // the cores the sampling and the first fit need. save() reports its own errors.
      app.session['files.chart'] = { name: cfg.file, bytes };
      Promise.resolve(storeAfter ?? new Promise((r) => { setTimeout(r); }))
        .then(() => { if (app.session['files.chart']?.bytes === bytes) app.save('files.chart', app.session['files.chart']); });
      return Promise.all([app.save('layout', layout), app.save('corners', cfg.corners), app.save('example', cfg.note ?? true)]);
    } catch (e) {
      showError(inputs.chart, e, 'Example chart');
      return null;
    }
  }

  engine.addEventListener('restart', () => { /* decodedGen is now stale; ensureDecoded() re-sends */ });
  syncLayout();

  return { restore, resample, ensureDecoded, setFile, detect, editor, inputs, second };
}
