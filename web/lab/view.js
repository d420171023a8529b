// The Lab mode (issue 45): a colorimetry lab without cameras, spectrometers or a light booth.
// (1) Render a chart photograph from measured spectra — one of the 52 cameras, a chart, an
// illuminant, exposure, shot + read noise, fall-off and flare — as a real DNG the engine writes,
// shown with its truth (camera RGB per patch), downloadable, and handed to the normal journey
// (Images step) with one click. (2) Camera quality as a colorimeter: the ISO 17321-1 SMI and the
// Vora–Trussell μ-factor of the 52 cameras, ranked, and one camera's curves beside the best-fit
// combination of the CIE colour-matching functions. Every panel names its CLI equivalent.
import { h, field, select, showError, clearError, numberValue, fmt, download } from '../lib/ui.js';
import { options } from '../lib/catalog.js';
import { labPanel } from './panel.js';
import { figure } from '../plots/common.js';
import { lutherPlot } from './plots.js';
import { spectraPanel, overfitPanel } from './exercises.js';
import { shenPanel, table4Panel, guarneraPanel } from './exercises_papers.js';
import { wireLabLinks } from './exercises_link.js';
import { metamersPanel } from './metamers.js';
import { fillChips } from './chips.js';
import { labOptionBoxes } from './options.js';

/// Sets a picker of another step as a person would (its change handler runs) when it offers `value`.
function choose(sel, value) {
  if (!sel || ![...sel.options].some((o) => o.value === value) || sel.value === value) return;
  sel.value = value;
  sel.dispatchEvent(new Event('change'));
}

const q = (s) => (/^[\w.+-]+$/.test(s) ? s : `"${s}"`);

/// One extra choice a picker shows for what the person gave instead of its list (an uploaded file,
/// a selection of chips): `show(value, text)` adds and selects it, `clear()` removes it and returns
/// to the listed choice shown before; picking a listed choice removes it too.
function extraChoice(sel) {
  const opt = document.createElement('option');
  opt.dataset.lab = 'extra';
  let before = sel.value;
  sel.addEventListener('change', () => { if (sel.value !== opt.value) opt.remove(); });
  return {
    show(value, text) {
      if (!opt.isConnected) { before = sel.value; sel.append(opt); }
      opt.value = value;
      opt.textContent = text;
      sel.value = value;
    },
    clear() { if (opt.isConnected) { opt.remove(); sel.value = before; } },
  };
}

/// The command line that renders the same file; `kind`: its row of the engine's file kinds.
export function renderCommand(o, kind) {
  const chart = o.reflectances ? `--reflectances ${q(o.reflectances)}` : `--chart ${q(o.chart)}`;
  let s = `tristim lab render --camera ${q(o.camera)} ${chart} --illuminant ${q(o.illuminant)} --exposure ${o.exposure}`;
  if (o.shot_gain > 0 || o.read_noise > 0) s += ` --noise ${o.shot_gain},${o.read_noise} --seed ${o.seed}`;
  if (o.falloff > 0) s += ` --falloff ${o.falloff}`;
  if (o.flare > 0) s += ` --flare ${o.flare}`;
  if (kind.through_oecf) s += ` --oecf ${o.oecf}`;
  return `${s} --out chart.${kind.extension}`;
}

export function mount(section, app) {
  const { engine } = app;
  const saved = app.session.lab ?? {};
  const cameras = options(app.catalog.cameras);
  const illuminants = options(app.catalog.illuminants);

  // The charts the renderer draws (lab_chart_ids), named by the chart catalog; the files it writes
  // (lab_file_kinds: id, label, extension, media type), DNG first.
  const charts = (app.catalog.labCharts ?? []).map((id) => ({ value: id, label: app.catalog.charts.find((c) => c.id === id)?.name ?? id }));
  const kinds = app.catalog.labFileKinds ?? [];
  const formatOf = (id) => kinds.find((k) => k.id === id) ?? kinds[0];

  // ---- (1) render
  const camSel = select(cameras, saved.camera ?? 'Canon_EOS_5D_Mark_II');
  const chartSel = select(charts, saved.chart ?? charts[0]?.value);
  const illumSel = select(illuminants, saved.illuminant ?? 'D65');
  const formatSel = select(kinds.map((k) => ({ value: k.id, label: k.label })), kinds[0]?.id);
  const oecfSel = select([{ value: 'linear', label: 'linear' }], 'linear');
  const spdIn = h('input', { type: 'file', accept: '.csv,.txt', 'data-lab': 'spd', 'aria-label': 'Illuminant SPD (CSV)' });
  formatSel.dataset.lab = 'format';
  oecfSel.dataset.lab = 'oecf';
  const reflIn = h('input', { type: 'file', accept: '.csv,.txt,.cgats,.cie', 'data-lab': 'reflectances', 'aria-label': 'Reflectances (CSV)' });
  const chipsSel = h('select', { multiple: true, size: 6, 'data-lab': 'munsell-chips' });
  const illumChoice = extraChoice(illumSel), chartChoice = extraChoice(chartSel);
  let spd = null;   // an uploaded SPD {name, text}: the illuminant instead of the picker's
  let refl = null;  // uploaded reflectances {name, text}: the chart instead of the picker's
  spdIn.addEventListener('change', async () => {
    const f = spdIn.files[0];
    spd = f ? { name: f.name, text: await f.text() } : null;
    if (spd) illumChoice.show(`uploaded:${spd.name}`, `uploaded: ${spd.name}`); else illumChoice.clear();
  });
  illumSel.addEventListener('change', () => { spd = null; spdIn.value = ''; });
  // A chart of one's own: chips of the engine's Munsell set, or uploaded reflectances, drawn as a grid.
  const loadChips = () => fillChips(app, chipsSel)
    .catch((e) => showError(chipsSel, e, 'Munsell chips'));
  chipsSel.addEventListener('focus', loadChips);
  chipsSel.addEventListener('change', () => {
    const ids = [...chipsSel.selectedOptions].map((o) => o.value);
    refl = null;
    reflIn.value = '';
    if (ids.length) chartChoice.show(`munsell:${ids.join(',')}`, `Munsell: ${ids.length} chips`); else chartChoice.clear();
  });
  const clearChips = () => { for (const o of [...chipsSel.selectedOptions]) o.selected = false; };
  reflIn.addEventListener('change', async () => {
    const f = reflIn.files[0];
    refl = f ? { name: f.name, text: await f.text() } : null;
    clearChips();
    if (refl) chartChoice.show(`uploaded:${refl.name}`, `uploaded: ${refl.name}`); else chartChoice.clear();
  });
  chartSel.addEventListener('change', () => {
    if (chartSel.value.startsWith('munsell:')) return;
    refl = null;
    reflIn.value = '';
    clearChips();
  });
  engine.call('labOecfs', {}).then((ids) => {   // the engine's OECF ids
    oecfSel.replaceChildren(...ids.map((id) => h('option', { value: id }, id)));
    oecfSel.value = ids.includes('sRGB') ? 'sRGB' : ids[0];
  }).catch((e) => showError(oecfSel, e, 'OECFs'));
  // The render's number boxes: rows render.<option> of the engine's lab option table.
  const boxes = labOptionBoxes(app);
  const inputs = Object.fromEntries(['exposure', 'shot_gain', 'read_noise', 'falloff', 'flare', 'seed']
    .map((k) => [k, boxes.box(`render.${k}`, k, saved[k])]));
  const renderBtn = h('button', { type: 'button', 'data-action': 'lab-render' }, 'Render the chart');
  const renderCli = h('pre', { class: 'cli', 'data-lab': 'render-cli' });
  const renderOut = h('div', { class: 'lab-out', 'aria-live': 'polite' });
  let last = null;

  function readOptions() {
    const o = { camera: camSel.value, chart: refl ? refl.name : chartSel.value, illuminant: spd ? spd.name : illumSel.value,
      format: formatSel.value, oecf: formatOf(formatSel.value).through_oecf ? oecfSel.value : 'linear' };
    if (refl) o.reflectances = refl.name;
    for (const [k, el] of Object.entries(inputs)) o[k] = numberValue(el);
    return o;
  }

  async function render() {
    clearError(renderBtn);
    for (const el of Object.values(inputs)) clearError(el);
    let o;
    try { o = readOptions(); } catch (e) { showError(e.input ?? renderBtn, e, 'Lab'); return null; }
    app.save('lab', { ...o });
    renderCli.textContent = renderCommand(o, formatOf(o.format));
    renderBtn.disabled = true;
    renderOut.replaceChildren(h('p', {}, 'Rendering in the engine…'));
    try {
      const { format, reflectances, ...options } = o;
      last = await engine.call('labRender', { options, format, spd, refl: reflectances ? refl : null });
    } catch (e) {
      renderOut.replaceChildren();
      showError(renderBtn, e, 'Render');
      return null;
    } finally { renderBtn.disabled = false; }
    app.derived.labTruth = last.truth;   // for the curious (and the browser test)
    show(last);
    return last;
  }

  function show({ dng, truth, format }) {
    const f = formatOf(format);
    const name = `lab-${truth.layout ? 'grid' : truth.chart}-${truth.camera.replace(/[^\w.-]+/g, '_')}-${truth.illuminant.replace(/[^\w.-]+/g, '_')}.${f.extension}`;
    const openBtn = h('button', { type: 'button', 'data-action': 'lab-open' }, 'Open in the journey (Images step)');
    const saveBtn = h('button', { type: 'button', 'data-action': 'lab-download' }, `Download the ${f.extension.toUpperCase()}`);
    const truthBtn = h('button', { type: 'button', 'data-action': 'lab-truth' }, 'Download the truth (JSON)');
    openBtn.addEventListener('click', () => openInJourney(name));
    saveBtn.addEventListener('click', () => download(name, dng, f.media_type));
    truthBtn.addEventListener('click', () => download(name.replace(/\.\w+$/, '.json'), JSON.stringify(truth, null, 1), 'application/json'));
    const stored = truth.patches[0]?.stored !== undefined;
    const rows = truth.patches.map((p) => h('tr', {},
      h('th', { scope: 'row', title: p.cell ?? '' }, p.board ? `${p.id} (board)` : p.id), ...p.rgb.map((v) => h('td', { class: 'num' }, String(v))),
      ...p.XYZ.map((v) => h('td', { class: 'num' }, fmt(v, 2))),
      ...(stored ? p.stored.map((v) => h('td', { class: 'num' }, String(v))) : [])));
    const what = !f.through_oecf
      ? `A ${truth.sensor_width} × ${truth.sensor_height} ${truth.cfa} DNG (${(dng.length / 1e6).toFixed(1)} MB, black ${truth.black}, white ${truth.white_level}): `
      : `A ${truth.width} × ${truth.height} RGB ${f.id === 'jpeg' ? `JPEG (quality ${truth.jpeg_quality}, 8 bits` : 'TIFF (16 bits'}, `
        + `${(dng.length / 1e6).toFixed(2)} MB) through the OECF ${truth.oecf}; the stored columns are its encoded values (full scale ${truth.full_scale})`
        + `${f.id === 'jpeg' ? ' before compression' : ''}: `;
    renderOut.replaceChildren(
      h('p', { class: 'summary', 'data-lab': 'summary' }, what
        + `the white diffuser's G at ${fmt(truth.white[1], 0)} DN. The table is the truth: the camera RGB (DN above black) that sampling the patches `
        + 'recovers exactly when noise and fall-off are off, and the reference XYZ of the same patches.'
        + (truth.layout ? ` A chart of your own is drawn as a ${truth.layout.rows} × ${truth.layout.columns} grid that detection does not `
          + `know: sample it with tristim sample <file> ${truth.sample_args} (cells R1C1… in the patches\' order; cells past the last `
          + 'patch show the board and are in the table by their cell).' : '')),
      h('p', { class: 'actions' }, openBtn, ' ', saveBtn, ' ', truthBtn),
      h('div', { class: 'table-scroll' }, h('table', { class: 'data', 'data-lab': 'truth' },
        h('thead', {}, h('tr', {}, ...['patch', 'R', 'G', 'B', 'X', 'Y', 'Z', ...(stored ? ['stored R', 'stored G', 'stored B'] : [])]
          .map((t) => h('th', { scope: 'col' }, t)))),
        h('tbody', {}, ...rows))));
  }

  /// The rendered DNG through the normal journey: the reference and the layout follow the chart
  /// and illuminant it was rendered with, then the Images step decodes, detects and samples it.
  /// A generated grid (Munsell chips, uploaded reflectances) is no chart detection knows: the
  /// reference is the truth's XYZ per cell (R1C1…: the rendered reflectances under the render's
  /// illuminant, CIE 1931 2°), the layout goes into the Images step's custom-grid boxes (rows ×
  /// columns, no gap) and the corners are the render's, so the journey samples it with no hand work.
  async function openInJourney(name) {
    if (!last) return;
    const { truth } = last;
    const file = new File([last.dng], name, { type: formatOf(last.format).media_type });
    const ref = app.views.reference;
    choose(ref?.controls?.illumSel, truth.illuminant);
    const images = document.getElementById('step-images');
    const layoutSel = images.querySelector('select[data-role="layout"]');
    if (!truth.layout) {
      choose(ref?.controls?.chartSel, truth.chart);
      choose(layoutSel, truth.chart);
      app.goto('images', { focus: true });
      await app.views.images.setFile('chart', file);
      return;
    }
    const { rows, columns } = truth.layout;
    const board = truth.patches.filter((p) => p.board).map((p) => p.cell);
    await ref.useFile({ name: name.replace(/\.\w+$/, '-reference.csv'), text: last.reference });   // the engine's CSV
    for (const [k, v] of [['rows', rows], ['columns', columns], ['gap', 0]]) images.querySelector(`input[data-layout="${k}"]`).value = v;
    layoutSel.value = 'custom';
    layoutSel.dispatchEvent(new Event('change'));
    app.goto('images', { focus: true });
    await app.views.images.setFile('chart', file, { corners: truth.corners,
      note: `Layout and corners from the render: a custom ${rows} × ${columns} grid, no gap, corners ${truth.corners.join(', ')} `
        + `(tristim sample ${truth.sample_args}); the reference (step 1) is the render's XYZ of each cell.`
        + (board.length ? ` Cell${board.length > 1 ? 's' : ''} ${board.join(', ')} hold${board.length > 1 ? '' : 's'} no chip: `
          + 'the chart\'s board, in the reference and the fit like any patch.' : '') });
  }

  renderBtn.addEventListener('click', render);
  const renderPanel = labPanel({ id: 'render', title: 'Render a chart photograph',
    explain:
      'The chart\'s measured reflectances, lit by the illuminant, seen through the camera\'s measured spectral sensitivities '
      + '(u = Σ SSF · S · R, the virtual camera), drawn head-on into a 14-bit Bayer sensor and written as a real DNG — or, '
      + 'through an OECF (x = DN / saturation; sRGB, or x^(1/γ)), as a 16-bit TIFF or an 8-bit JPEG. The illuminant: a built-in '
      + 'one, or your own SPD (CSV: wavelength, value). '
      + 'Exposure: the white diffuser\'s G as a fraction of saturation. Noise: variance = gain · DN + read². '
      + 'Fall-off: 1 − a·r² (r = 1 at the corners). Flare: a veil of that fraction of the white.',
    controls: [
      field('Camera', camSel, 'One of the 52 cameras with measured sensitivities'),
      field('Chart', chartSel), field('Illuminant', illumSel), field('or an SPD (CSV)', spdIn),
      field('or Munsell chips', chipsSel, 'The engine\'s 1269 matte chips: Ctrl/Shift-click several; drawn as a grid'),
      field('or reflectances (CSV)', reflIn, 'Spectra of your own (id, then one column per wavelength); drawn as a grid'),
      field('File', formatSel), field('OECF (TIFF, JPEG)', oecfSel),
      ...Object.values(inputs).map(boxes.field)],
    buttons: [renderBtn], cli: renderCli }, renderOut);

  // ---- (2) camera quality
  const qIllum = select(illuminants, 'D65');
  const qCam = select(cameras, saved.camera ?? 'Canon_EOS_5D_Mark_II');
  const rankBtn = h('button', { type: 'button', 'data-action': 'lab-rank' }, 'Rank the 52 cameras');
  const plotBtn = h('button', { type: 'button', 'data-action': 'lab-luther' }, 'Plot against the CMFs');
  const rankBox = h('div', { class: 'table-scroll' });
  const plotBox = h('div', { class: 'plot-box', 'data-lab': 'luther' });
  const qCli = h('pre', { class: 'cli' });
  const setCli = () => { qCli.textContent = `tristim lab smi --illuminant ${qIllum.value} --json\ntristim lab smi --camera ${q(qCam.value)} --illuminant ${qIllum.value} --json`; };
  setCli();

  async function rank() {
    clearError(rankBtn);
    rankBtn.disabled = true;
    rankBox.replaceChildren(h('p', {}, 'Computing the SMI and μ of every camera…'));
    let rows;
    try { rows = await engine.call('labRanking', { illuminant: qIllum.value }); } catch (e) {
      rankBox.replaceChildren();
      showError(rankBtn, e, 'Ranking');
      return null;
    } finally { rankBtn.disabled = false; }
    const body = rows.map((r, i) => {
      const b = h('button', { type: 'button', class: 'link' }, r.camera);
      b.addEventListener('click', () => { qCam.value = r.camera; setCli(); plot(); });
      return h('tr', {}, h('td', { class: 'num' }, String(i + 1)), h('td', {}, b), h('td', { class: 'num' }, fmt(r.smi, 1)),
        h('td', { class: 'num' }, fmt(r.mu_factor, 4)), h('td', { class: 'num' }, fmt(r.mean_dE, 2)));
    });
    rankBox.replaceChildren(h('table', { class: 'data', 'data-lab': 'ranking' },
      h('thead', {}, h('tr', {}, ...['#', 'camera', 'SMI', 'μ', 'mean ΔE*ab'].map((t) => h('th', { scope: 'col' }, t)))),
      h('tbody', {}, ...body)));
    return rows;
  }

  async function plot() {
    clearError(plotBtn);
    let r;
    try { r = await engine.call('labCamera', { camera: qCam.value, illuminant: qIllum.value }); } catch (e) { showError(plotBtn, e, 'Plot'); return null; }
    const { quality, fit } = r;
    plotBox.replaceChildren(
      figure(lutherPlot(fit), { name: `luther-${quality.camera}`, caption: `${quality.camera}: SMI ${fmt(quality.smi, 1)}, μ ${fmt(quality.mu_factor, 4)} under ${qIllum.value}` }),
      h('p', { class: 'explain' },
        'Solid: the camera\'s measured sensitivities. Dashed: for each channel, the combination of x̄, ȳ, z̄ closest to it '
        + '(least squares, weighted by the illuminant). Where they part, two surfaces can match for the camera and not for us '
        + '(or the reverse): no 3×3 matrix can undo that, which is what the SMI scores on the 18 colours of the ColorChecker.'));
    return r;
  }

  rankBtn.addEventListener('click', rank);
  plotBtn.addEventListener('click', plot);
  qIllum.addEventListener('change', setCli);
  qCam.addEventListener('change', setCli);
  const qualityPanel = labPanel({ id: 'quality', title: 'Camera quality as a colorimeter',
    explain:
      'A camera measures colour exactly only if its sensitivities are a linear combination of the colour-matching functions '
      + '(the Luther condition). ISO 17321-1\'s sensitivity metamerism index scores the gap: SMI = 100 − 5.5 × the mean ΔE*ab of '
      + 'ColorChecker patches 1–18 after the best 3×3 matrix (100 = perfect). Vora & Trussell\'s μ-factor measures it in the '
      + 'spectral domain: 1 when the camera\'s curves span the same space as the CMFs.',
    controls: [field('Illuminant', qIllum), field('Camera', qCam)], buttons: [rankBtn, plotBtn], cli: qCli }, plotBox, rankBox);

  // Tabs: one panel shown at a time.
  const ex1 = spectraPanel(app), ex2 = overfitPanel(app), met = metamersPanel(app);
  const ex3 = shenPanel(app), ex4 = table4Panel(app), ex5 = guarneraPanel(app);
  const panels = [['render', 'Virtual camera', renderPanel], ['quality', 'Camera quality', qualityPanel],
    ['metamers', 'Metamerism', met.panel],
    ['ex1', 'Exercise 1: spectra to colour', ex1.panel], ['ex2', 'Exercise 2: why a 3×3 is not enough', ex2.panel],
    ['ex3', 'Exercise 3: Shen 2008', ex3.panel], ['ex4', 'Exercise 4: Abed 2013', ex4.panel], ['ex5', 'Exercise 5: Guarnera 2018', ex5.panel]];
  const tabs = h('div', { class: 'lab-tabs', role: 'tablist' });
  const showTab = (id) => {
    for (const [k, , p] of panels) p.hidden = k !== id;
    for (const b of tabs.children) b.setAttribute('aria-selected', String(b.dataset.tab === id));
    if (id === 'metamers') met.loadChips().catch(() => {});  // the chip picker from the engine's list
  };
  for (const [k, label] of panels) {
    const b = h('button', { type: 'button', role: 'tab', 'data-tab': k }, label);
    b.addEventListener('click', () => showTab(k));
    tabs.append(b);
  }
  const links = wireLabLinks(app, { ex1, ex2, ex3, ex4, ex5 }, showTab);   // #lab=… set-up links
  section.append(links.status, tabs, ...panels.map(([, , p]) => p));
  showTab('render');
  return { render, openInJourney, rank, plot, showTab, exercise1: ex1.run, exercise2: ex2.run, metamers: met.run,
    exercise3: ex3.run, exercise4: ex4.run, exercise5: ex5.run, openFromHash: links.openFromHash };
}
