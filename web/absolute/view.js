// The Absolute mode (Guarnera, Bianco & Schettini 2018): a bracketed series of RAWs and the
// training stimuli -> an absolute profile (eq 8 per channel across every exposure, the colour
// matrix) -> X, Y, Z in cd/m² for every pixel. Shows the fitted OECFs per channel and exposure
// (fig 5), the luminance map with a cd/m² colour bar (linear or log), the map of the exposure
// that served each pixel, a pointer read-out and the engine's report on a test scene (the section
// 4.1 figures with the eq 16 white, the per-point and per-region rows: what `tristim absolute
// evaluate` prints). "Example" makes the whole input with the engine's virtual bracket camera.
import { h, field, select, setOptions, showError, clearError, numberValue, progressBar, fmt, fileBytes, download } from '../lib/ui.js';
import { figure } from '../plots/common.js';
import { oecfPlot } from '../plots/oecf.js';
import { NO_VALUE_RGB } from './render.js';
import { mountSensitivities } from './sensitivities.js';
import { optionInput, optionLabel } from './option_input.js';

const MAPS = {
  viridis: { label: 'viridis', interp: () => globalThis.d3.interpolateViridis },
  cividis: { label: 'cividis', interp: () => globalThis.d3.interpolateCividis },
};
// One colour per exposure, shortest first: Okabe & Ito's palette (distinct with colour-vision
// deficiencies), then grey steps beyond eight exposures.
const EXPOSURE_COLOURS = ['#0072B2', '#56B4E9', '#009E73', '#F0E442', '#E69F00', '#D55E00', '#CC79A7', '#000000'];
const exposureColour = (i) => EXPOSURE_COLOURS[i] ?? `hsl(0, 0%, ${20 + ((i * 9) % 60)}%)`;
const rgbOf = (css) => { const c = globalThis.d3.rgb(css); return [c.r, c.g, c.b]; };
const pct = (x, d = 2) => (Number.isFinite(x) ? `${(100 * x).toFixed(d)} %` : '–');
const num = (x) => (Number.isFinite(x) ? (Math.abs(x) >= 100 ? x.toFixed(1) : Math.abs(x) >= 1 ? x.toFixed(2) : x.toPrecision(3)) : '–');

// A shutter time as cameras show it: 1/250 below half a second when 1/t is (nearly) a whole
// number, otherwise the number itself.
function shutterText(t) {
  const inv = 1 / t;
  return t < 0.5 && Math.abs(inv - Math.round(inv)) <= 1e-3 * inv ? `1/${Math.round(inv)}` : String(t);
}
/// A text box for an exposure setting of one frame, showing `value` (from the file's metadata or
/// typed before; empty when unknown). Its exact value is kept: text left as shown reads back as
/// that value, not as the rounded text ("1/60" for 0.0166667 s).
function settingInput(value, format, label) {
  const shown = value > 0 ? format(value) : '';
  const i = h('input', { type: 'text', inputmode: 'decimal', value: shown, 'aria-label': label, class: 'num', size: 8 });
  i._exact = { text: shown, value: value > 0 ? value : 0 };
  return i;
}
/// What a setting box holds: its kept value when left as shown, 0 when empty (then the file's
/// metadata is used), else the typed number or fraction ("1/250", "0.004", "2.5"). Anything
/// else throws INVALID_ARGUMENT (shown next to the series) instead of being dropped silently.
function settingValue(input) {
  const text = input.value.trim();
  if (input._exact && text === input._exact.text) return input._exact.value;
  if (text === '') return 0;
  const frac = /^([0-9]*\.?[0-9]+)\s*\/\s*([0-9]*\.?[0-9]+)$/.exec(text);
  const v = frac ? Number(frac[1]) / Number(frac[2]) : /^[0-9]*\.?[0-9]+(e[+-]?[0-9]+)?$/i.test(text) ? Number(text) : NaN;
  if (!(v > 0) || !Number.isFinite(v))
    throw Object.assign(new Error(`${input.getAttribute('aria-label')}: '${text}' is not a positive number (e.g. 0.004, 1/250, 8, 100)`), { code: 'INVALID_ARGUMENT', typed: true });
  return v;
}

export function mount(section, app) {
  const { engine } = app;
  const intro = h('p', { class: 'summary' },
    'A camera as a tele-colorimeter: absolute X, Y, Z in cd/m² for every pixel from a bracketed series of RAW exposures, ',
    'after Guarnera, Bianco & Schettini (2018). The inverse OECF of each channel (eq 8) is fitted to equal-tristimulus training stimuli ',
    'of known luminance across every exposure (scaled by t/N²·ISO), the colour matrix (eqs 11–15) to chromatic ones; each pixel takes ',
    'its value from the exposures where it is reliable.');

  // ---- inputs ----
  const seriesInput = h('input', { type: 'file', multiple: true, 'data-role': 'abs-series' });
  const seriesTable = h('div', { class: 'abs-series' });
  const stimuliInput = h('input', { type: 'file', accept: '.csv,.txt,text/csv', 'data-role': 'abs-stimuli' });
  const stimuliInfo = h('span', { class: 'file-state', 'data-role': 'abs-stimuli-info' });
  const testInput = h('input', { type: 'file', accept: '.csv,.txt,text/csv', 'data-role': 'abs-test' });
  const testInfo = h('span', { class: 'file-state', 'data-role': 'abs-test-info' });
  // The white of the test figures (section 4.1): the engine's rules (eq 16, E), or a stimulus of the scene.
  const WHITE_AUTO = (app.catalog?.absoluteWhiteRules ?? []).map((r) => ({ value: r.id, label: r.label }));
  const whiteSel = select(WHITE_AUTO, '');
  whiteSel.dataset.role = 'abs-white';
  // The recipe's numbers from the engine's rows (listAbsoluteOptions: absolute_option_table — label,
  // unit, bounds, default): the zone parameter w of section 3.1, the noise floor and saturation of eq (7).
  const spec = Object.fromEntries((app.catalog?.absoluteOptions ?? []).map((o) => [o.name, o]));
  const wInput = optionInput('absolute', spec.w, { 'data-role': 'abs-w' });
  const capInput = h('input', { type: 'file', multiple: true, 'data-role': 'abs-lenscap' });
  const capInfo = h('span', { class: 'file-state' });
  const flatInput = h('input', { type: 'file', 'data-role': 'abs-flat' });
  const flatInfo = h('span', { class: 'file-state' });
  const noiseInput = optionInput('absolute', spec.noise_floor, { 'data-role': 'abs-noise' });
  const satInput = optionInput('absolute', spec.saturation, { 'data-role': 'abs-saturation' });
  // Sensitivities for eq (7)'s areas, in the order of the engine's table (listAbsoluteSensitivities:
  // absolute_sensitivity_table — the recipe's sensitivities.choice ids): 'none' itself, 'given' as
  // this session's sets (an uploaded CSV or an estimate, '@upload' / '@estimate': held by the worker,
  // see sensitivities.js), 'camera' as the built-in cameras (their ids).
  const ssfRows = app.catalog?.absoluteSensitivities ?? [];
  const NONE = 'none';
  const builtIn = (app.catalog?.cameras ?? []).map((c) => ({ value: c.id, label: c.name }));
  const givenSets = {};
  const expand = {
    none: (r) => [{ value: r.id, label: r.label }],
    given: () => Object.entries(givenSets).map(([k, label]) => ({ value: `@${k}`, label })),
    camera: () => builtIn,
  };
  const cameraOptions = () => ssfRows.flatMap((r) => expand[r.id]?.(r) ?? []);
  /// The table's row a picker value stands for.
  const ssfRowOf = (value) => ssfRows.find((r) => r.id === (value.startsWith('@') ? 'given' : value === NONE ? NONE : 'camera'));
  const cameraSel = select(cameraOptions(), NONE);
  cameraSel.dataset.role = 'abs-camera';
  const ssf = mountSensitivities(app, { onChoice: (which, label) => { givenSets[which] = label; setOptions(cameraSel, cameraOptions(), `@${which}`); cameraSel._showHint?.(); } });
  // The colour matrix: the Guarnera2018 family of the engine's model table; a row's id is
  // Guarnera2018-<transform> and the recipe names the transform.
  const transforms = (app.catalog?.models ?? []).filter((m) => m.family === 'Guarnera2018')
    .map((m) => ({ value: m.id.slice(m.family.length + 1), label: `${m.label} — ${m.reference}` }));
  const transformSel = select(transforms, 'T1');
  // The engine's tables (listFusionModes, listExampleLights, listExampleTrainings), default first.
  const choices = (list) => list.map((r) => ({ value: r.id, label: r.label }));
  const fusionModes = app.catalog?.fusionModes ?? [];
  const fusionSel = select(choices(fusionModes), fusionModes[0]?.id);
  const exampleBtn = h('button', { type: 'button', 'data-role': 'abs-example' }, 'Example (virtual camera)');
  // The example's scene light and colour training; a training row names the colour matrix that
  // meets Table 4 with it (T2R for the reflective patches), which choosing it selects.
  const exLights = app.catalog?.exampleLights ?? [], exTrainings = app.catalog?.exampleTrainings ?? [];
  const exLightSel = select(choices(exLights), exLights[0]?.id);
  exLightSel.dataset.role = 'abs-example-light';
  const exTrainingSel = select(choices(exTrainings), exTrainings[0]?.id);
  exTrainingSel.dataset.role = 'abs-example-training';
  exTrainingSel.addEventListener('change', () => {
    const want = exTrainings.find((t) => t.id === exTrainingSel.value)?.transform;
    if (want && transforms.some((t) => t.value === want)) transformSel.value = want;
  });
  const fitBtn = h('button', { type: 'button', class: 'primary', 'data-role': 'abs-fit' }, 'Fit and measure the series');
  // A picker of engine rows whose hint is the chosen row's `about` (the engine's words, kept current).
  const aboutField = (label, sel, rows) => {
    const f = field(label, sel, ' ');
    const hint = f.querySelector('small.hint');
    const show = () => { hint.textContent = rows.find((r) => r.id === sel.value)?.about ?? ''; };
    sel.addEventListener('change', show);
    show();
    return f;
  };
  // The sensitivities' field: its hint is the chosen row's label and citation (the engine's words).
  const ssfField = () => {
    const f = field('Sensitivities for A_R, A_G, A_B', cameraSel, ' ');
    const hint = f.querySelector('small.hint');
    const show = () => { const r = ssfRowOf(cameraSel.value); hint.textContent = r ? `${r.label} — ${r.reference}` : ''; };
    cameraSel.addEventListener('change', show);
    cameraSel._showHint = show;
    show();
    return f;
  };
  // Two grid columns for a field whose choices are long (the chosen text stays readable).
  const wide = (el) => { el.classList.add('abs-wide'); return el; };
  const progress = progressBar('Absolute');

  section.append(intro,
    h('div', { class: 'abs-inputs' },
      h('div', { class: 'abs-series-box' }, field('Bracketed series (RAW files of one scene)', seriesInput, 'Same camera and size; exposure time, f-number and ISO from each file (or typed in the table)'), seriesTable),
      h('div', {}, field('Training stimuli (CSV)', stimuliInput, 'Per patch: id, set (luminance|colour), exposure_s, f_number, iso, R, G, B (black-subtracted DN), falloff, X, Y, Z (cd/m²); or a region: file (a RAW of the series), x, y, w, h instead of R, G, B'), stimuliInfo),
      h('div', {}, field('Test scene (CSV, optional)', testInput, 'The same columns: stimuli of the scene with their measured X, Y, Z; region rows are measured on the fused maps'), testInfo),
      field('White of the test figures', whiteSel, 'CIELAB white of ΔE94/ΔE00 (Guarnera 2018 section 4.1)'),
      h('div', {}, field('Lens-cap frames (RAW, optional)', capInput, 'Averaged: the noise floor n of eq (7)'), capInfo),
      h('div', {}, field('Flat field (RAW, optional)', flatInput, 'Evenly lit: the radial fall-off f(r) of eq (7)'), flatInfo),
      ...[noiseInput, satInput, wInput].map((i) => { const o = spec[i.dataset.absoluteOption]; return field(optionLabel(o), i, o.description); }),
      ssfField(),
      h('div', { class: 'abs-ssf-box' }, ssf.el),
      wide(field('Colour matrix', transformSel)),
      wide(field('Exposure fusion', fusionSel)),
      aboutField('Example: light on the chart', exLightSel, exLights),
      wide(aboutField('Example: colour training', exTrainingSel, exTrainings)),
      h('div', { class: 'buttons' }, exampleBtn, fitBtn)),
    progress.el);
  fitBtn._errorSlot = h('p', { class: 'field-error', role: 'alert', hidden: true, id: 'abs-fit-error' });
  fitBtn.setAttribute('aria-describedby', 'abs-fit-error');
  fitBtn.parentElement.after(fitBtn._errorSlot);
  exampleBtn._errorSlot = fitBtn._errorSlot;

  // ---- results ----
  const fitSummary = h('div', { class: 'abs-fit-summary', 'data-role': 'abs-fit-summary', 'aria-live': 'polite' });
  const oecfBox = h('div', { class: 'abs-oecf' });
  const mapSel = select(Object.entries(MAPS).map(([value, m]) => ({ value, label: m.label })), app.session.colourMap ?? 'viridis');
  const logBox = h('input', { type: 'checkbox', checked: true, 'data-role': 'abs-log' });
  const lumCanvas = h('canvas', { class: 'apply-img abs-map', 'data-role': 'abs-luminance', 'aria-label': 'Luminance Y in cd/m² (false colour)' });
  const srcCanvas = h('canvas', { class: 'apply-img abs-map', 'data-role': 'abs-source', 'aria-label': 'The exposure that served each pixel' });
  // Cell labels over both maps (the measured cells, when they are known: the example's).
  const SVG = 'http://www.w3.org/2000/svg';
  const labelLayer = (role) => { const g = document.createElementNS(SVG, 'svg'); g.setAttribute('class', 'abs-labels'); g.dataset.role = role; g.setAttribute('aria-hidden', 'true'); return g; };
  const lumLabels = labelLayer('abs-luminance-labels'), srcLabels = labelLayer('abs-source-labels');
  const labelsBox = h('input', { type: 'checkbox', checked: true, 'data-role': 'abs-labels' });
  const lumLegend = h('div', { class: 'legend', 'data-role': 'abs-colourbar' });
  const srcLegend = h('div', { class: 'legend abs-source-legend', 'data-role': 'abs-source-legend' });
  const readout = h('output', { class: 'readout', 'data-role': 'abs-readout', 'aria-live': 'polite' }, 'Move the pointer over a map (or focus it and use the arrow keys) to read X, Y, Z in cd/m² and the exposure that served the pixel.');
  const mapSummary = h('p', { class: 'summary', 'data-role': 'abs-map-summary' });
  // Downloads: the absolute profile (what `tristim absolute apply` takes) and the X, Y, Z map.
  const fileBase = () => `${st.fit?.report.fit.model || 'camera'}-absolute`.replace(/[^\w.-]+/g, '_');
  const profileBtn = h('button', { type: 'button', 'data-role': 'abs-download-profile' }, 'Download the absolute profile (JSON)');
  profileBtn.addEventListener('click', () => { if (st.fit) download(`${fileBase()}.json`, st.fit.profile, 'application/json'); });
  // The recipe (`tristim absolute fit --recipe` reproduces the profile from it and the files it names)
  // and the report (what `tristim absolute evaluate --json` prints).
  const recipeBtn = h('button', { type: 'button', 'data-role': 'abs-download-recipe' }, 'Download the absolute recipe (JSON)');
  recipeBtn.addEventListener('click', () => { if (st.fit) download(`${fileBase()}-recipe.json`, st.fit.recipeJson, 'application/json'); });
  const reportBtn = h('button', { type: 'button', 'data-role': 'abs-download-report' }, 'Download the report (JSON)');
  reportBtn.addEventListener('click', () => { if (st.report) download(`${fileBase()}-report.json`, `${JSON.stringify(st.report, null, 2)}\n`, 'application/json'); });
  const tiffBtn = h('button', { type: 'button', 'data-role': 'abs-download-xyz' }, 'Download X, Y, Z in cd/m² (32-bit float TIFF)');
  tiffBtn._errorSlot = h('p', { class: 'field-error', role: 'alert', hidden: true });
  tiffBtn.addEventListener('click', async () => {
    clearError(tiffBtn);
    try {
      const { bytes } = await engine.call('absMapTiff', {});
      download(`${fileBase()}-XYZ.tiff`, bytes, 'image/tiff');
    } catch (e) { showError(tiffBtn, e, 'Download'); }
  });
  const maps = h('div', { class: 'abs-maps', hidden: true },
    h('div', { class: 'controls' }, field('Colour map', mapSel, 'Perceptually uniform, readable with colour-vision deficiencies'),
      h('label', { class: 'check' }, logBox, ' log scale'), h('label', { class: 'check' }, labelsBox, ' cell labels'), h('div', { class: 'buttons' }, tiffBtn, tiffBtn._errorSlot)),
    mapSummary, readout,
    h('div', { class: 'apply-images' },
      h('figure', {}, h('div', { class: 'abs-map-wrap' }, lumCanvas, lumLabels), h('figcaption', {}, 'Luminance Y (cd/m²)'), lumLegend),
      h('figure', {}, h('div', { class: 'abs-map-wrap' }, srcCanvas, srcLabels), h('figcaption', {}, 'Dominant exposure per pixel (largest reliability × t/N²)'), srcLegend)));
  const figuresBox = h('div', { class: 'abs-figures', 'data-role': 'abs-figures' });
  section.append(fitSummary, oecfBox, maps, figuresBox);

  // ---- state (page side: what was loaded, for the messages and the read-out) ----
  const st = { frames: [], exposures: null, fit: null, shown: null, regions: null, report: null, testFromExample: false };

  function seriesRows(frames) {
    st.frames = frames;
    const inputs = frames.map((f) => {
      const [te, ne, isoe] = f.exposure ?? [f.exposure_s, f.f_number, f.iso];  // the engine's [t, N, ISO]
      const t = settingInput(te, shutterText, `exposure time of ${f.name} (s)`);
      const n = settingInput(ne, String, `f-number of ${f.name}`);
      const iso = settingInput(isoe, String, `ISO of ${f.name}`);
      for (const i of [t, n, iso]) i.addEventListener('change', retypeExposures);
      return { t, n, iso, f };
    });
    st.inputs = inputs;
    seriesTable.replaceChildren(frames.length ? h('table', { class: 'patch-table' },
      h('thead', {}, h('tr', {}, h('th', {}, '#'), h('th', {}, 'file'), h('th', {}, 'camera'), h('th', {}, 'size'), h('th', {}, 't (s)'), h('th', {}, 'N'), h('th', {}, 'ISO'))),
      h('tbody', {}, inputs.map(({ t, n, iso, f }, i) => h('tr', { dataset: { frame: i } },
        h('td', {}, h('span', { class: 'abs-swatch', style: { background: exposureColour(i) } }), ` ${i + 1}`), h('td', {}, f.name), h('td', {}, `${f.make} ${f.model}`),
        h('td', {}, `${f.width}×${f.height}`), h('td', {}, t), h('td', {}, n), h('td', {}, iso))))) : '');
  }
  function typedExposures() {
    return (st.inputs ?? []).map(({ t, n, iso }) => [settingValue(t), settingValue(n), settingValue(iso)]);
  }
  async function retypeExposures() {
    clearError(seriesInput);
    try {
      const r = await engine.call('absExposures', { exposures: typedExposures() });
      st.frames = r.frames;
    } catch (e) { showError(seriesInput, e, 'Series'); }
  }

  async function readFiles(input) {
    return Promise.all([...input.files].map(async (f) => ({ name: f.name, bytes: (await fileBytes(f)).buffer })));
  }

  seriesInput.addEventListener('change', async () => {
    if (!seriesInput.files.length) return;
    clearError(seriesInput);
    if (st.testFromExample) {  // the example's test scene names the example's frames
      st.regions = null; st.testFromExample = false; testInfo.textContent = '';
      setOptions(whiteSel, WHITE_AUTO, '');
      await engine.call('absClearTest', {}).catch(() => {});
    }
    progress.start('Decoding the series…');
    try {
      const files = await readFiles(seriesInput);
      const r = await engine.call('absSeries', { files }, { transfer: files.map((f) => f.bytes), onProgress: progress.update });
      seriesRows(r.frames);
      if (r.frames[0]) ssf.cameraHint(r.frames[0].make, r.frames[0].model);
      if (r.missing) showError(seriesInput, Object.assign(new Error(`${r.missing.message}: type it in the table`), { code: r.missing.code }), 'Series');
    } catch (e) { seriesRows([]); showError(seriesInput, e, 'Series'); } finally { progress.done(); }
  });

  /// Reads a stimuli CSV in the worker: the training stimuli, or (kind 'test') a test scene.
  async function loadStimuli(text, name, kind = 'training') {
    const [input, info] = kind === 'test' ? [testInput, testInfo] : [stimuliInput, stimuliInfo];
    clearError(input);
    try {
      const r = await engine.call('absStimuli', { text, name, kind });
      const regions = r.regionRows ? `, ${r.regionRows} of them regions of ${r.files.join(', ')}` : '';
      info.textContent = `${name}: ${r.count} stimuli (${r.luminance} luminance, ${r.colour} colour${regions})${kind === 'test' ? '.' : ` over ${r.exposures} exposures.`}`;
      if (kind === 'test') {
        st.regions = r.regions;
        setOptions(whiteSel, [...WHITE_AUTO, ...r.colourIds.map((id) => ({ value: id, label: `${id} (eq 16)` }))], whiteSel.value);
      }
      return r;
    } catch (e) { info.textContent = ''; showError(input, e, name); return null; }
  }
  stimuliInput.addEventListener('change', async () => {
    const f = stimuliInput.files[0];
    if (f) await loadStimuli(await f.text(), f.name);
  });
  testInput.addEventListener('change', async () => {
    const f = testInput.files[0];
    st.testFromExample = false;
    if (f) await loadStimuli(await f.text(), f.name, 'test');
  });

  async function loadCalibration(input, kind, info) {
    clearError(input);
    progress.start(kind === 'flat' ? 'Decoding the flat field…' : 'Decoding the lens-cap frames…');
    try {
      const files = await readFiles(input);
      const r = await engine.call('absCalibration', { kind, files }, { transfer: files.map((f) => f.bytes), onProgress: progress.update });
      info.textContent = r.frames.length ? `${r.frames.length} frame${r.frames.length > 1 ? 's' : ''}: ${r.frames[0].make} ${r.frames[0].model}, ${r.frames[0].width}×${r.frames[0].height}` : '';
    } catch (e) { info.textContent = ''; showError(input, e, kind === 'flat' ? 'Flat field' : 'Lens cap'); } finally { progress.done(); }
  }
  capInput.addEventListener('change', () => loadCalibration(capInput, 'lensCap', capInfo));
  flatInput.addEventListener('change', () => loadCalibration(flatInput, 'flat', flatInfo));

  /// Where an error of the fit or the application belongs.
  function errorTarget(e, stage) {
    if (e.input) return e.input;   // a number box that could not be read
    const m = e.message ?? '';
    if (stage === 'apply' && /stimulus|white patch|test scene/.test(m)) return testInput;
    if (['NON_MONOTONIC', 'TOO_FEW_PATCHES', 'NEGATIVE_VALUE', 'EMPTY_FILE', 'NO_STIMULI', 'MISSING_COLUMN'].includes(e.code)) return stimuliInput;
    if (/zone parameter/.test(m)) return wInput;
    if (/lens-cap/.test(m)) return capInput;
    if (/flat/.test(m)) return flatInput;
    if (['FRAME_MISMATCH', 'MISSING_METADATA', 'NO_IMAGE', 'LIMIT_EXCEEDED'].includes(e.code) || e.typed) return seriesInput;
    if (e.code === 'NO_USABLE_DATA') return stage === 'apply' ? seriesInput : stimuliInput;
    if (/stimulus/.test(m)) return stimuliInput;
    return fitBtn;
  }

  function lut() {
    const f = MAPS[mapSel.value].interp();
    const out = new Uint8Array(256 * 3);
    for (let i = 0; i < 256; i++) { const c = globalThis.d3.rgb(f(i / 255)); out[3 * i] = c.r; out[3 * i + 1] = c.g; out[3 * i + 2] = c.b; }
    return out;
  }
  function renderOptions() {
    const L = lut();
    return { lut: L.buffer, log: logBox.checked, maxSide: 900, sourceColours: st.frames.map((_, i) => rgbOf(exposureColour(i))) };
  }

  /// Fits the profile and applies it to the series. Returns {fit, apply} or null.
  async function run() {
    for (const c of [fitBtn, seriesInput, stimuliInput, testInput, capInput, flatInput, noiseInput, satInput, wInput]) clearError(c);
    fitBtn.disabled = exampleBtn.disabled = true;
    let stage = 'fit';
    try {
      progress.start('Fitting the absolute profile…');
      const kind = ssfRowOf(cameraSel.value)?.id;
      const options = { camera: kind === 'camera' ? cameraSel.value : '', sensitivities: kind === 'given' ? cameraSel.value.slice(1) : '', transform: transformSel.value, fusion: fusionSel.value,
        noise_floor: numberValue(noiseInput, 0), saturation: numberValue(satInput, 0), w: numberValue(wInput) };
      const fit = await engine.call('absFit', { options }, { onProgress: progress.update });
      st.fit = fit;
      st.report = fit.report;
      showFit(fit);
      showFigures(fit.report);
      if (!st.frames.length) { maps.hidden = true; return { fit }; }
      stage = 'apply';
      progress.start('Measuring the series…');
      const out = await engine.call('absApply', { mode: fusionSel.value, exposures: typedExposures(), white: whiteSel.value, render: renderOptions() }, { onProgress: progress.update });
      st.report = out.report;
      showMaps(out);
      showFigures(out.report);
      app.mark('absolute', 'done');
      return { fit, apply: out };
    } catch (e) {
      if (e.code !== 'CANCELLED') showError(errorTarget(e, stage), e, stage === 'fit' ? 'Fit' : 'Measure');
      if (stage === 'fit') { fitSummary.replaceChildren(); oecfBox.replaceChildren(); figuresBox.replaceChildren(); }
      maps.hidden = true;
      return null;
    } finally { progress.done(); fitBtn.disabled = exampleBtn.disabled = false; }
  }
  fitBtn.addEventListener('click', run);

  async function example() {
    for (const c of [fitBtn, seriesInput, stimuliInput, testInput, capInput, flatInput]) clearError(c);
    progress.start('Generating the example with the virtual camera…');
    fitBtn.disabled = exampleBtn.disabled = true;
    let ex;
    try {
      ex = await engine.call('absExample', { options: { illuminant: exLightSel.value, colour_training: exTrainingSel.value } }, { onProgress: progress.update });
    } catch (e) { showError(exampleBtn, e, 'Example'); return null; } finally { progress.done(); fitBtn.disabled = exampleBtn.disabled = false; }
    for (const i of [seriesInput, stimuliInput, testInput, capInput, flatInput]) i.value = '';
    seriesRows(ex.frames);
    capInfo.textContent = `${ex.lensCap.length} virtual lens-cap frames`;
    flatInfo.textContent = 'virtual flat field (equal-tristimulus light, 450 cd/m²)';
    for (const i of [noiseInput, satInput, wInput]) i.value = String(spec[i.dataset.absoluteOption].default_number);
    setOptions(cameraSel, cameraOptions(), ex.camera || NONE);
    cameraSel._showHint();
    if (!(await loadStimuli(ex.stimuliCsv, 'example-stimuli.csv'))) return null;
    if (!(await loadStimuli(ex.testCsv, 'example-test.csv', 'test'))) return null;
    st.testFromExample = true;
    whiteSel.value = ex.whiteId;
    testInfo.textContent += ` The scene's cells: a ColorChecker under ${exLightSel.value} (white patch ${ex.whiteId}) and 12 equal-tristimulus cells from 0.3 to 3000 cd/m², with their true X, Y, Z.`;
    return run();
  }
  exampleBtn.addEventListener('click', example);

  // ---- fit summary and OECF plot ----
  function showFit({ report, panels }) {
    const fit = report.fit, t = report.training;
    const ch = ['R', 'G', 'B'];
    const rows = fit.channels.map((c, i) => h('tr', {}, h('th', {}, ch[i]), h('td', {}, c.k1.toExponential(3)), h('td', {}, c.k2.toExponential(4)), h('td', { 'data-col': `k3-${ch[i]}` }, c.k3.toFixed(4)),
      h('td', {}, String(c.samples)), h('td', {}, pct(c.rms_relative)), h('td', {}, c.r_squared.toFixed(5)),
      h('td', {}, num(fit.noise_floor[i])), h('td', {}, `${num(fit.saturation[i])}${fit.saturation_measured[i] ? ` (measured; ${pct(fit.saturation_fraction[i], 1)} of the metadata's ${num(fit.saturation_reported[i])})` : ' (metadata)'}`),
      h('td', {}, (fit.areas[1] / fit.areas[i]).toFixed(4))));
    const recip = fit.reciprocity_ok
      ? h('p', { class: 'ok', 'data-role': 'abs-reciprocity' }, `Reciprocity holds: every exposure's own curve is parallel to the common one (scale within 2 %, k3 within 0.03).`)
      : h('p', { class: 'unavailable', 'data-role': 'abs-reciprocity' }, `Reciprocity fails: ${fit.reciprocity_message}. The common curve is used as fitted; values from these exposures are biased.`);
    fitSummary.replaceChildren(
      h('h3', {}, 'Fitted profile'),
      h('p', {}, `${fit.make} ${fit.model}: ${t.luminance_stimuli} luminance and ${t.colour_stimuli} colour stimuli used${t.saturated_stimuli ? `, ${t.saturated_stimuli} left out (a channel saturated)` : ''}. `,
        `Fall-off f(r): ${fit.falloff ? `p1 ${fit.falloff.p1.toFixed(4)}, p2 ${fit.falloff.p2.toFixed(4)} (from the flat field)` : 'none (f = 1)'}. Channel areas: ${fit.areas_source}. Zones: w = ${num(fit.w)}. `,
        `Colour matrix ${fit.transform}: ${fit.colour_message || 'fitted by pattern search (eqs 11–12)'}.`),
      h('table', { class: 'metrics abs-channels' },
        h('thead', {}, h('tr', {}, ['channel', 'k1', 'k2', 'k3', 'stimuli', 'RMS rel. error', 'R²', 'n (DN)', 'S (DN)', 'A_G/A_c'].map((t) => h('th', {}, t)))),
        h('tbody', {}, rows)),
      recip, h('div', { class: 'buttons' }, profileBtn, recipeBtn));
    oecfBox.replaceChildren(figure(oecfPlot(panels), { name: 'absolute-oecf', caption: "Fitted OECFs per channel and exposure (Guarnera 2018 fig 5): normalised R′, G′, B′ (eq 7) of the luminance training stimuli against Y; solid: the common eq (8) curve at each exposure's t/N², dashed: the exposure's own fit (reciprocity check); log axes" }));
  }

  // ---- maps ----
  function draw(canvas, r) {
    canvas.width = r.width; canvas.height = r.height;
    canvas.getContext('2d').putImageData(new ImageData(new Uint8ClampedArray(r.rgba.buffer), r.width, r.height), 0, 0);
  }
  function colourBar(range, log) {
    const name = MAPS[mapSel.value].label;
    const leg = globalThis.Plot.legend({ color: { type: log ? 'log' : 'linear', interpolate: MAPS[mapSel.value].interp(), domain: range, label: 'luminance Y (cd/m²)' }, width: 520, height: 52, ticks: log ? 5 : 6, tickFormat: log ? ',~g' : ',~g' });
    return h('div', { class: 'legend-box', dataset: { colourMap: name, low: range[0], high: range[1], scale: log ? 'log' : 'linear' } }, leg,
      h('small', { class: 'hint' }, `${log ? 'Log' : 'Linear'} scale from ${num(range[0])} to ${num(range[1])} cd/m² (1st to 99th percentile${log ? '' : ' from 0'}); values beyond are drawn at the end colours. `,
        h('span', { class: 'abs-swatch', style: { background: `rgb(${NO_VALUE_RGB.join(',')})`, border: '1px solid #999' } }), ' saturated in every exposure (no value).'));
  }
  function sourceLegend(summary) {
    return [h('ul', { class: 'abs-legend-list' }, summary.labels.map((l, i) => h('li', {}, h('span', { class: 'abs-swatch', style: { background: exposureColour(i) } }), ` ${l}: ${pct(summary.dominant_pixels[i] / (summary.width * summary.height), 1)} of the pixels`)),
      h('li', {}, h('span', { class: 'abs-swatch', style: { background: `rgb(${NO_VALUE_RGB.join(',')})`, border: '1px solid #999' } }), ' none (no reliable value)'))];
  }
  /// The known cells (id, x, y, w, h in image pixels) outlined and named over a map.
  function drawLabels(svg, regions, width, height) {
    svg.setAttribute('viewBox', `0 0 ${width} ${height}`);
    svg.setAttribute('preserveAspectRatio', 'none');
    svg.replaceChildren();
    svg.style.display = regions?.length && labelsBox.checked ? '' : 'none';
    for (const r of regions ?? []) {
      const rect = document.createElementNS(SVG, 'rect');
      for (const [k, v] of Object.entries({ x: r.x + 0.5, y: r.y + 0.5, width: r.w - 1, height: r.h - 1, fill: 'none', stroke: 'rgba(255,255,255,0.55)', 'stroke-width': 0.6 })) rect.setAttribute(k, v);
      const t = document.createElementNS(SVG, 'text');
      // small, in the cell's top-left corner: the colour of the cell's centre stays visible
      const size = Math.max(3, Math.min(0.2 * r.h, (1.1 * r.w) / Math.max(2, r.id.length)));
      for (const [k, v] of Object.entries({ x: r.x + 0.08 * r.w, y: r.y + 0.06 * r.h, 'font-size': size, 'text-anchor': 'start', 'dominant-baseline': 'hanging',
        fill: '#fff', stroke: '#000', 'stroke-width': size / 6, 'paint-order': 'stroke', 'font-family': 'system-ui, sans-serif', 'font-weight': 600 })) t.setAttribute(k, v);
      t.textContent = r.id;
      svg.append(rect, t);
    }
  }
  function showLabels() {
    const s = st.shown?.summary;
    if (!s) return;
    for (const svg of [lumLabels, srcLabels]) drawLabels(svg, st.regions, s.width, s.height);
  }
  labelsBox.addEventListener('change', showLabels);
  function showMaps(out) {
    st.shown = { ...out, summary: out.report.maps };
    showLabels();
    draw(lumCanvas, out.luminance);
    draw(srcCanvas, out.source);
    lumLegend.replaceChildren(colourBar(out.luminance.range, out.luminance.log));
    const s = out.report.maps;
    srcLegend.replaceChildren(...sourceLegend(s));
    mapSummary.textContent = `${s.width}×${s.height} pixels from ${s.labels.length} exposure${s.labels.length > 1 ? 's' : ''} (${(app.catalog?.fusionModes ?? []).find((m) => m.id === s.mode)?.label ?? s.mode}) in ${fmt(out.ms, 0)} ms. `
      + `Y from ${num(s.Y.min)} to ${num(s.Y.max)} cd/m² (median ${num(s.Y.median)}); ${s.saturated_pixels} pixels saturated in every exposure, ${s.unreliable_pixels} without a reliable value.`;
    maps.hidden = false;
  }
  async function rerender() {
    app.save('colourMap', mapSel.value);
    if (!st.shown) return;
    try {
      const r = await engine.call('absRender', { render: renderOptions() });
      st.shown = { ...st.shown, ...r };
      draw(lumCanvas, r.luminance);
      draw(srcCanvas, r.source);
      lumLegend.replaceChildren(colourBar(r.luminance.range, r.luminance.log));
    } catch (e) { showError(fitBtn, e, 'Render'); }
  }
  mapSel.addEventListener('change', rerender);
  logBox.addEventListener('change', rerender);

  // ---- figures (section 4.1): the engine's report, as `tristim absolute evaluate` prints it ----
  const f2 = (x) => (Number.isFinite(x) ? x.toFixed(2) : '–');
  function showFigures(report) {
    const t = report.training, test = report.test;
    const cols = [];
    if (t) cols.push(['training', `Training stimuli (${t.evaluated})`, t.figures, `white: E at ${num(t.figures.white[1])} cd/m²`]);
    const white = test ? (test.white_rule === 'eq16' ? `white per eq (16): ${test.white_id} at ${num(test.max_luminance)} cd/m²` : `white: E at ${num(test.max_luminance)} cd/m²`) : '';
    for (const g of test?.figures ?? [])
      cols.push([g.group, `${g.group === 'all' ? 'Test scene' : g.label} (${g.count}${g.group === 'all' ? ', measured vs true' : ''})`, g.metrics, g.group === 'all' ? white : 'the same white']);
    const row = (label, f) => h('tr', {}, h('th', {}, label), cols.map(([group, , m]) => h('td', { 'data-group': group }, f(m))));
    const s3 = (x) => `${f2(x.mean)} / ${f2(x.median)} / ${f2(x.max)}`;
    const rows = test ? [...test.points, ...test.regions] : [];
    const xyz = (v) => v.map(num).join(' / ');
    const table = rows.length ? h('details', { class: 'abs-rows', 'data-role': 'abs-rows' },
      h('summary', {}, `Per-stimulus rows (${test.points.length} per patch, ${test.regions.length} regions)`),
      h('table', { class: 'metrics' },
        h('thead', {}, h('tr', {}, ['id', 'set', 'estimated X / Y / Z (cd/m²)', 'reference X / Y / Z (cd/m²)', 'relative Y error', 'from'].map((x) => h('th', {}, x)))),
        h('tbody', {}, rows.map((r) => h('tr', { dataset: { id: r.id } }, h('th', {}, r.id), h('td', {}, r.set), h('td', {}, xyz(r.estimated)), h('td', {}, xyz(r.reference)),
          h('td', { 'data-col': 'row-relY' }, pct(r.relative_Y_error)),
          h('td', {}, r.file ? `${r.file} (${r.region[0]}, ${r.region[1]}) ${r.region[2]}×${r.region[3]}: ${r.source_label || 'no exposure'}` : r.saturated ? 'per patch (saturated: left out)' : 'per patch')))))) : null;
    figuresBox.replaceChildren(h('h3', {}, 'Figures (Guarnera 2018 section 4.1)'),
      h('table', { class: 'metrics abs-figures-table' },
        h('thead', {}, h('tr', {}, h('th', {}, ''), cols.map(([group, l]) => h('th', { 'data-group': group }, l)))),
        h('tbody', {},
          row('ΔE94 mean / median / max', (m) => s3(m.metrics.dE94)),
          row('ΔE00 mean / median / max', (m) => s3(m.metrics.dE00)),
          row('NRMSE X / Y / Z', (m) => m.metrics.NRMSE.map((v) => pct(v)).join(' / ')),
          row('relative Y error (mean |ΔY|/Y)', (m) => h('span', { 'data-col': 'relY' }, pct(m.relative_Y_error))),
          row('median |ΔX| / |ΔY| / |ΔZ| (cd/m²)', (m) => m.median_absolute_error.map(num).join(' / ')),
          row('CIELAB white', (m) => `${m.white.map(num).join(', ')} cd/m²`))),
      h('small', { class: 'hint' }, cols.map(([, l, , w]) => `${l}: ${w}.`).join(' '), ' NRMSE: RMS error over the range of the reference channel.'),
      table, h('div', { class: 'buttons' }, reportBtn));
  }

  // ---- pointer read-out ----
  let pending = false;
  const cursor = { x: 0, y: 0 };
  async function read(x, y) {
    if (!st.shown || pending) return;
    pending = true;
    try {
      const r = await engine.call('absReadout', { x, y, window: 5 });
      if (!r) return;
      const s = r.XYZ[0] + r.XYZ[1] + r.XYZ[2];
      const parts = [`pixel (${r.x}, ${r.y}), mean of ${r.n} pixels: X ${num(r.XYZ[0])}  Y ${num(r.XYZ[1])}  Z ${num(r.XYZ[2])} cd/m²`,
        s > 0 ? `x ${(r.XYZ[0] / s).toFixed(4)} y ${(r.XYZ[1] / s).toFixed(4)}` : null,
        r.source >= 0 ? `source exposure ${r.source_label}${r.contributors.length > 1 ? ` (${r.contributors.length} exposures contributed)` : ''}` : 'no exposure served this pixel'];
      if (r.region) parts.push(`known stimulus ${r.region.id}: X ${num(r.region.XYZ[0])}  Y ${num(r.region.XYZ[1])}  Z ${num(r.region.XYZ[2])} cd/m² (Y ${r.XYZ[1] >= r.region.XYZ[1] ? '+' : ''}${pct((r.XYZ[1] - r.region.XYZ[1]) / r.region.XYZ[1], 2)})`);
      readout.textContent = parts.filter(Boolean).join('  ·  ');
      Object.assign(readout.dataset, { x: r.x, y: r.y, X: r.XYZ[0], Y: r.XYZ[1], Z: r.XYZ[2], source: r.source, region: r.region?.id ?? '' });
    } catch { /* worker restarted: ignore */ } finally { pending = false; }
  }
  for (const c of [lumCanvas, srcCanvas]) {
    c.tabIndex = 0;
    c.title = 'Pointer, or arrow keys when focused (Shift: 10 pixels), to read X, Y, Z in cd/m²';
    c.addEventListener('pointermove', (e) => {
      if (!st.shown) return;
      const rect = c.getBoundingClientRect(), s = st.shown.summary;
      cursor.x = ((e.clientX - rect.left) / rect.width) * s.width;
      cursor.y = ((e.clientY - rect.top) / rect.height) * s.height;
      read(cursor.x, cursor.y);
    });
    c.addEventListener('keydown', (e) => {
      const d = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1] }[e.key];
      if (!d || !st.shown) return;
      e.preventDefault();
      const k = (e.shiftKey ? 10 : 1) * st.shown.luminance.factor, s = st.shown.summary;
      cursor.x = Math.min(Math.max(0, cursor.x + d[0] * k), s.width - 1);
      cursor.y = Math.min(Math.max(0, cursor.y + d[1] * k), s.height - 1);
      read(cursor.x, cursor.y);
    });
  }

  // A cancelled job restarts the worker: what it held is gone.
  engine.addEventListener('restart', () => {
    st.shown = null; maps.hidden = true;
    for (const k of Object.keys(givenSets)) delete givenSets[k];
    setOptions(cameraSel, cameraOptions(), cameraSel.value.startsWith('@') ? NONE : cameraSel.value);
    cameraSel._showHint();
    ssf.forget();
  });
  return { run, example, read, seriesInput, stimuliInput, fitBtn, exampleBtn, sensitivities: ssf };
}
