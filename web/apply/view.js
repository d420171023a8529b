// Step 5: apply the selected profile to the whole RAW (the chart, or another RAW of a scene):
// the XYZ image rendered to sRGB, a false-colour map of Y with a named CVD-safe colour map and
// its legend, and X, Y, Z, x, y, L*a*b* under the pointer.
import { h, field, select, showError, clearError, progressBar, fmt, fileBytes } from '../lib/ui.js';
import { cameraOf } from '../fit/view.js';
import { CornerEditor } from '../images/corners.js';

const MAPS = {
  viridis: { label: 'viridis', interp: () => globalThis.d3.interpolateViridis },
  cividis: { label: 'cividis', interp: () => globalThis.d3.interpolateCividis },
};

export function mount(section, app) {
  const { engine } = app;
  const sourceSel = select([{ value: 'chart', label: 'The chart RAW (step 2)' }, { value: 'scene', label: 'Another RAW file…' }], 'chart');
  const sceneInput = h('input', { type: 'file' });
  const sceneField = field('Scene RAW', sceneInput, 'Decoded in the worker; the profile is applied to its linear camera RGB');
  sceneField.hidden = true;
  // The scene's own frames (Abed 2013 App. C step 8): what `tristim apply --dark --flat --light-trap` takes.
  const darkInput = h('input', { type: 'file', multiple: true, dataset: { frame: 'dark' } });
  const flatInput = h('input', { type: 'file', dataset: { frame: 'flat' } });
  // The flat field's modes as the engine lists them (per pixel, or a radial fall-off fitted to it).
  const flatModes = app.catalog.flatFieldModes.map((m, i) => {
    const r = h('input', { type: 'radio', name: 'apply-flat-mode', value: m.id, checked: i === 0, dataset: { flatMode: m.id } });
    r.id = `apply-flat-mode-${m.id}`;
    return h('div', { class: 'check', title: m.reference ?? '' }, r, h('label', { for: r.id }, m.label));
  });
  const flatMode = () => flatModes.map((d) => d.querySelector('input')).find((r) => r.checked)?.value ?? app.catalog.flatFieldModes[0]?.id;
  const trapInput = h('input', { type: 'text', placeholder: 'x1,y1,x2,y2,x3,y3,x4,y4', dataset: { frame: 'light-trap' } });
  // The light trap drawn on the scene: the corner editor of step 2 (its four handles, no chart grid),
  // in the same pixels as the typed field, which it keeps in sync both ways.
  const trapEditor = new CornerEditor({ onChange: (c) => trapFromEditor(c), grid: () => Promise.reject(new Error('no chart grid here')) });
  trapEditor.el.classList.add('trap-editor');
  trapEditor.svg.setAttribute('aria-label', 'Light trap corners on the scene');
  trapEditor.handles.forEach((g, i) => g.setAttribute('aria-label', `Light trap corner ${i + 1}`));
  const noTrapBtn = h('button', { type: 'button' }, 'No light trap');
  const trapDraw = h('div', { class: 'trap-draw', hidden: true },
    h('p', { class: 'hint' }, 'Or drag the four handles onto the light trap (arrow keys move a focused handle; Shift: 10 pixels). The field above follows; an empty field: no light trap.'),
    trapEditor.el, noTrapBtn);
  const framesNote = h('p', { class: 'summary frames-note', 'aria-live': 'polite' });
  const frames = h('fieldset', { class: 'scene-frames', hidden: true }, h('legend', {}, 'This image\'s own frames (Abed 2013 App. C step 8)'),
    h('p', { class: 'hint' }, 'Dark frames, a flat field and a light trap of this scene calibrate it before the profile, the same way step 2 calibrates the chart (tristim apply … --dark … --flat … --light-trap …).'),
    h('div', { class: 'controls' }, field('Dark frames (RAW, averaged)', darkInput), field('Flat field (RAW)', flatInput), h('fieldset', { class: 'flat-mode' }, h('legend', {}, 'Flat-field mode (--flat-mode)'), ...flatModes),
      field('Light trap corners (pixels of the decoded image)', trapInput, 'Four corners of a black light trap in the scene, typed as x,y pairs; its mean is the flare subtracted from every pixel')),
    trapDraw, framesNote);
  const mapSel = select(Object.entries(MAPS).map(([value, m]) => ({ value, label: m.label })), app.session.colourMap ?? 'viridis');
  const applyBtn = h('button', { type: 'button', class: 'primary' }, 'Apply the selected profile');
  const which = h('p', { class: 'summary', 'aria-live': 'polite' });
  const warning = h('p', { class: 'unavailable', role: 'status', hidden: true });
  const progress = progressBar('Applying');
  const srgbCanvas = h('canvas', { class: 'apply-img', 'aria-label': 'The XYZ image rendered to sRGB' });
  const yCanvas = h('canvas', { class: 'apply-img', 'aria-label': 'Luminance Y false-colour map' });
  const legend = h('div', { class: 'legend' });
  const readout = h('output', { class: 'readout', 'aria-live': 'polite' }, 'Move the pointer over an image (or focus it and use the arrow keys) to read X, Y, Z, x, y and L*a*b*.');
  const images = h('div', { class: 'apply-images', hidden: true },
    h('figure', {}, srgbCanvas, h('figcaption', {}, 'XYZ → sRGB (display; D65-adapted, clipped)')),
    h('figure', {}, yCanvas, h('figcaption', {}, 'Luminance Y (relative, white = 100)'), legend));
  section.append(h('div', { class: 'controls' }, field('Apply to', sourceSel), sceneField, field('Colour map for Y', mapSel, 'Perceptually uniform and readable with colour-vision deficiencies'), applyBtn),
    frames,
    which, warning, progress.el, readout, images);
  applyBtn._errorSlot = h('p', { class: 'field-error', role: 'alert', hidden: true, id: 'apply-error' });
  applyBtn.setAttribute('aria-describedby', 'apply-error');
  applyBtn.after(applyBtn._errorSlot);

  let sceneBytes = null;
  let sceneMeta = null;
  let sceneSize = null;      // {width, height} of the decoded scene (the light trap's pixels)
  let previewOf = null;      // the sceneBytes whose preview the trap editor shows
  let sceneGen = -1;
  let shown = null;
  sourceSel.addEventListener('change', () => { sceneField.hidden = frames.hidden = sourceSel.value !== 'scene'; app.save('applySource', sourceSel.value); });
  // Restore: the scene file kept in the session, the source choice, and (when the step is
  // visited) the last applied image.
  const savedScene = app.session['files.scene'];
  if (savedScene) {
    sceneBytes = { name: savedScene.name, bytes: new Uint8Array(savedScene.bytes) };
    sceneField.append(h('span', { class: 'file-state' }, `Kept from before: ${savedScene.name}`));
  }
  if (app.session.applySource === 'scene' && savedScene) { sourceSel.value = 'scene'; sceneField.hidden = frames.hidden = false; }
  let restoreApplied = !!app.session.applied;
  mapSel.addEventListener('change', () => { app.save('colourMap', mapSel.value); if (shown) run(); });
  let sceneLoading = null;   // reading + decoding a newly chosen scene file
  let afterApply = null;     // called when the next apply has ended
  sceneInput.addEventListener('change', () => {
    const f = sceneInput.files[0];
    if (!f) return;
    clearError(sceneInput);
    sceneLoading = (async () => {
      await scenePromise;
      sceneBytes = { name: f.name, bytes: await fileBytes(f) };
      sceneGen = -1;
      const ok = await decodeScene();
      // Kept for a reload once the apply that follows has drawn (or after 2 s, or at once when the
      // page is being left): writing 8 MB to IndexedDB takes the page and the browser a few
      // hundred ms of the cores the apply needs. save() reports its own errors.
      const kept = { name: sceneBytes.name, bytes: sceneBytes.bytes.buffer };
      if (ok) Promise.race([new Promise((r) => { afterApply = r; }), new Promise((r) => { setTimeout(r, 2000); }),
                            new Promise((r) => { addEventListener('pagehide', r, { once: true }); })])
        .then(() => app.save('files.scene', kept));
      return ok;
    })();
  });

  let scenePromise = null;
  /// Decodes the scene RAW once per worker generation (a cancelled fit restarts the worker).
  function decodeScene() {
    if (sceneGen === engine.generation) return Promise.resolve(true);
    scenePromise ??= (async () => {
      progress.start(`Decoding ${sceneBytes.name}…`);
      try {
        const copy = sceneBytes.bytes.slice();
        const d = await engine.call('decode', { slot: 'scene', bytes: copy.buffer }, { transfer: [copy.buffer] });
        sceneMeta = d.metadata;
        sceneSize = { width: d.width, height: d.height };
        sceneGen = engine.generation;
        if (previewOf !== sceneBytes) await showScene();
        return true;
      } catch (e) { showError(sceneInput, e, sceneBytes.name); return false; } finally { progress.done(); scenePromise = null; }
    })();
    return scenePromise;
  }

  /// The typed corners: 8 finite numbers, or null (empty or not 8 numbers).
  function typedTrap() {
    const v = trapInput.value.trim() ? trapInput.value.split(',').map((t) => Number(t.trim())) : [];
    return v.length === 8 && v.every(Number.isFinite) ? v : null;
  }
  /// The decoded scene's preview under the trap editor, its handles at the typed corners (or, with
  /// none typed, a small square near the top-left corner, dimmed until one is moved).
  async function showScene() {
    const bytes = sceneBytes;
    const preview = await engine.call('preview', { slot: 'scene' });
    if (bytes !== sceneBytes) return;
    previewOf = bytes;
    trapEditor.setImage({ ...sceneSize, preview });
    const typed = typedTrap();
    if (typed) trapEditor.setCorners(typed);
    else {
      const { width: w, height: hh } = sceneSize, x = Math.round(w / 8), y = Math.round(hh / 8), s = Math.round(Math.min(w, hh) / 12);
      trapEditor.setCorners([x, y, x + s, y, x + s, y + s, x, y + s]);
    }
    trapDraw.hidden = false;
    trapInUse();
  }
  function trapInUse() { trapEditor.svg.style.opacity = typedTrap() ? '' : '0.55'; }
  function trapFromEditor(c) {
    trapInput.value = Array.from(c).join(',');
    clearError(trapInput);
    trapInUse();
  }
  trapInput.addEventListener('input', () => {
    const typed = typedTrap();
    if (typed && trapEditor.width) trapEditor.setCorners(typed);
    trapInUse();
  });
  noTrapBtn.addEventListener('click', () => { trapInput.value = ''; clearError(trapInput); trapInUse(); });

  /// Sets the scene's own frames in the worker (each apply: the inputs as they are now).
  async function setFrames() {
    clearError(trapInput);
    let lightTrap = null;
    if (trapInput.value.trim()) {
      lightTrap = trapInput.value.split(',').map((t) => Number(t.trim()));
      if (lightTrap.length !== 8 || !lightTrap.every(Number.isFinite)) {
        showError(trapInput, Object.assign(new Error(`the light trap needs 8 numbers (x1,y1,…,x4,y4), got '${trapInput.value}'`), { code: 'INVALID_ARGUMENT' }), 'Light trap');
        return false;
      }
    }
    const darks = await Promise.all([...darkInput.files].map(async (f) => (await fileBytes(f)).buffer));
    const flat = flatInput.files[0] ? (await fileBytes(flatInput.files[0])).buffer : null;
    try {
      const set = await engine.call('sceneFrames', { darks, flat, flatMode: flatMode(), lightTrap }, { transfer: [...darks, ...(flat ? [flat] : [])] });
      framesNote.textContent = [set.dark ? `dark: ${set.dark.frames} frame(s) averaged` : null, set.flat ? `flat field (${flatMode()})` : null,
        set.lightTrap ? `light trap: flare R ${fmt(set.lightTrap.mean[0])}, G ${fmt(set.lightTrap.mean[1])}, B ${fmt(set.lightTrap.mean[2])} subtracted (${set.lightTrap.n} pixels)` : null]
        .filter(Boolean).join('; ') || 'No frames: the scene is used as decoded.';
      return true;
    } catch (e) {
      showError(e.code === 'INVALID_ARGUMENT' && lightTrap ? trapInput : applyBtn, e, 'Frames');
      return false;
    }
  }

  function selected() {
    const rs = app.session.results ?? [];
    return rs.find((r) => r.key === app.session.selected) ?? rs[0];
  }
  function describe() {
    const r = selected();
    which.textContent = r ? `Profile: ${r.label}.` : 'No profile yet: fit one in step 3 or import one in step 6.';
  }
  app.on('results', describe);
  app.on('step', (s) => {
    if (s !== 'apply') return;
    describe();
    if (restoreApplied && selected()) { restoreApplied = false; run(); }
  });

  function lut() {
    const f = MAPS[mapSel.value].interp();
    const out = new Uint8Array(256 * 3);
    for (let i = 0; i < 256; i++) {
      const c = globalThis.d3.rgb(f(i / 255));
      out[3 * i] = c.r; out[3 * i + 1] = c.g; out[3 * i + 2] = c.b;
    }
    return out;
  }

  /// Applies the selected profile; returns timing figures (for the bench script).
  async function run() {
    clearError(applyBtn);
    const r = selected();
    if (!r) { showError(applyBtn, Object.assign(new Error('no profile to apply: fit or import one first'), { code: 'NO_PROFILE' }), 'Apply'); return null; }
    const slot = sourceSel.value;
    if (slot === 'scene') {
      await sceneLoading;
      if (!sceneBytes) { showError(sceneInput, Object.assign(new Error('choose a RAW file first'), { code: 'NO_IMAGE' }), 'Apply'); return null; }
      if (!(await decodeScene())) return null;
      if (!(await setFrames())) return null;
    } else if (!(await app.views.images.ensureDecoded())) {
      showError(applyBtn, Object.assign(new Error('no chart RAW decoded (step 2)'), { code: 'NO_IMAGE' }), 'Apply'); return null;
    }
    progress.start('Applying the profile…');
    applyBtn.disabled = true;
    const t0 = performance.now();
    try {
      const L = lut();
      const white = r.white;
      const out = await engine.call('applyRender', { profile: r.fit.profile, slot, white, lut: L.buffer, maxSide: 1400 }, { transfer: [L.buffer], onProgress: progress.update });
      draw(srgbCanvas, out, out.srgb);
      draw(yCanvas, out, out.ymap);
      images.hidden = false;
      shown = out;
      legend.replaceChildren(yLegend(out.yMax));
      app.mark('apply', 'done');
      app.save('applied', true);
      const ms = performance.now() - t0;
      const imageCamera = cameraOf(slot === 'scene' ? sceneMeta : app.derived.image?.metadata);
      warning.hidden = !(r.camera && imageCamera && r.camera !== imageCamera) && slot !== 'scene';
      warning.textContent = r.camera && imageCamera && r.camera !== imageCamera
        ? `This profile was fitted for a ${r.camera}; this image comes from a ${imageCamera}. A profile belongs to one camera: these colours are not measurements.`
        : 'Y is relative to the chart photo: Y = 100 is a perfect white diffuser lit as the chart was, at the same exposure. Another exposure or light scales it.';
      which.textContent = `Profile: ${r.label}. Applied to ${out.fullWidth}×${out.fullHeight} pixels in ${fmt(out.msApply, 0)} ms (render ${fmt(out.msRender, 0)} ms; total ${fmt(ms, 0)} ms).`;
      return { ms, ...out };
    } catch (e) {
      if (e.code !== 'CANCELLED') showError(applyBtn, e, 'Apply');
      return null;
    } finally {
      progress.done(); applyBtn.disabled = false;
      setTimeout(() => { afterApply?.(); afterApply = null; });
    }
  }
  applyBtn.addEventListener('click', run);

  function draw(canvas, out, rgba) {
    canvas.width = out.width; canvas.height = out.height;
    canvas.getContext('2d').putImageData(new ImageData(new Uint8ClampedArray(rgba.buffer), out.width, out.height), 0, 0);
  }

  function yLegend(yMax) {
    const name = MAPS[mapSel.value].label;
    const leg = globalThis.Plot.legend({ color: { type: 'linear', interpolate: MAPS[mapSel.value].interp(), domain: [0, yMax], label: `Y (relative, white = 100) — colour map: ${name}` }, width: 360 });
    return h('div', { class: 'legend-box', dataset: { colourMap: name } }, leg,
      h('small', { class: 'hint' }, `Colour map: ${name} (perceptually uniform, readable with colour-vision deficiencies). Values above ${fmt(yMax, 1)} (99th percentile) are shown at the top colour.`));
  }

  let pending = false;
  const cursor = { x: 0, y: 0 };
  async function read(x, y) {
    if (!shown || pending) return;
    pending = true;
    try {
      const p = await engine.call('pixel', { x, y });
      if (p) readout.textContent = `pixel (${Math.floor(x)}, ${Math.floor(y)}): X ${fmt(p.XYZ[0])}  Y ${fmt(p.XYZ[1])}  Z ${fmt(p.XYZ[2])}  ·  x ${fmt(p.xy[0], 4)}  y ${fmt(p.xy[1], 4)}  ·  L* ${fmt(p.Lab[0], 1)}  a* ${fmt(p.Lab[1], 1)}  b* ${fmt(p.Lab[2], 1)}`;
    } catch { /* worker restarted: ignore */ } finally { pending = false; }
  }
  for (const c of [srgbCanvas, yCanvas]) {
    c.tabIndex = 0;
    c.title = 'Pointer, or arrow keys when focused (Shift: 10 pixels), to read X, Y, Z, x, y and L*a*b*';
    c.addEventListener('pointermove', (e) => {
      if (!shown) return;
      const rect = c.getBoundingClientRect();
      cursor.x = ((e.clientX - rect.left) / rect.width) * shown.width * shown.factor;
      cursor.y = ((e.clientY - rect.top) / rect.height) * shown.height * shown.factor;
      read(cursor.x, cursor.y);
    });
    c.addEventListener('keydown', (e) => {
      const step = (e.shiftKey ? 10 : 1) * (shown?.factor ?? 1);
      const d = { ArrowLeft: [-step, 0], ArrowRight: [step, 0], ArrowUp: [0, -step], ArrowDown: [0, step] }[e.key];
      if (!d || !shown) return;
      e.preventDefault();
      cursor.x = Math.min(Math.max(0, cursor.x + d[0]), shown.fullWidth - 1);
      cursor.y = Math.min(Math.max(0, cursor.y + d[1]), shown.fullHeight - 1);
      read(cursor.x, cursor.y);
    });
    c.addEventListener('focus', () => { if (shown && !cursor.x && !cursor.y) { cursor.x = shown.fullWidth / 2; cursor.y = shown.fullHeight / 2; read(cursor.x, cursor.y); } });
  }
  describe();
  return { run, sourceSel, sceneInput, applyBtn, darkInput, flatInput, trapInput, trapEditor };
}
