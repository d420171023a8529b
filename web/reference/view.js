// Step 1: the reference — chart (built-in or uploaded CSV/CGATS), illuminant and observer; the
// patches as swatches with XYZ and Lab, and the CIE xy diagram. Emits 'reference'.
import { h, field, select, setOptions, showError, clearError, fmt, onFileText } from '../lib/ui.js';
import { options } from '../lib/catalog.js';
import { cssColours, xyFromXYZ, figure } from '../plots/common.js';
import { xyPlot } from '../plots/xy.js';

export const DEFAULT_SETTINGS = { chart: 'passport', illuminant: 'D50', observer: '1931', referenceFile: null };

export function mount(section, app) {
  const { engine } = app;
  const settings = (app.session.settings ??= { ...DEFAULT_SETTINGS });
  const charts = options(app.catalog.charts);
  const illuminants = options(app.catalog.illuminants);
  const observers = options(app.catalog.observers);

  const chartSel = select(charts, settings.chart);
  const illumSel = select(illuminants, settings.illuminant);
  const obsSel = select(observers, settings.observer);
  const fileInput = h('input', { type: 'file', accept: '.csv,.txt,.cie,.ti3,.cgats,.it8' });
  const fileState = h('p', { class: 'file-state' });
  const useBuiltin = h('button', { type: 'button', hidden: true }, 'Use the built-in chart instead');
  const swatches = h('div', { class: 'swatches', 'aria-label': 'Reference patches' });
  const plotBox = h('div', { class: 'plot-box' });
  const summary = h('p', { class: 'summary', 'aria-live': 'polite' });

  const controls = h('div', { class: 'controls' },
    field('Chart', chartSel, 'Reference data built into tristim'),
    field('Illuminant', illumSel, 'Reference XYZ are computed for this light'),
    field('Observer', obsSel),
    h('div', { class: 'field' }, field('Or upload a reference file (CSV or CGATS)', fileInput,
      'Per-patch XYZ or Lab, or spectral reflectances; the same ids as the chart layout'), fileState, useBuiltin));
  section.append(controls, summary, h('div', { class: 'ref-layout' }, swatches, plotBox));


  async function computeLocus() {
    const key = settings.observer;
    if (app.derived.locus?.observer === key) return app.derived.locus;
    try {
      const l = await engine.call('spectralLocus', { observer: key });
      app.derived.locus = { ...l, observer: key };
    } catch (e) { showError(obsSel, e, 'Spectral locus'); app.derived.locus = null; }
    return app.derived.locus;
  }

  /// Recomputes the reference from the settings; shows errors next to the control responsible.
  async function update() {
    const s = settings;
    let ref = null;
    const args = { illuminant: s.illuminant, observer: s.observer };
    if (s.referenceFile) {
      try {
        ref = await engine.call('parseReference', { text: s.referenceFile.text, fileName: s.referenceFile.name, ...args });
        ref.source = `file ${s.referenceFile.name}`;
        clearError(fileInput);
      } catch (e) {
        showError(fileInput, e, s.referenceFile.name);
        return e;
      }
    } else {
      try {
        ref = await engine.call('reference', { chart: s.chart, ...args });
        ref.source = `built-in chart ${chartSel.selectedOptions[0]?.textContent ?? s.chart}`;
        clearError(chartSel); clearError(illumSel);
      } catch (e) {
        showError(illumSel, e, 'Reference');
        return e;
      }
    }
    ref.settings = { ...s, referenceFile: s.referenceFile ? { name: s.referenceFile.name } : null };
    await computeLocus();
    app.derived.reference = ref;
    render(ref);
    app.mark('reference', 'done');
    app.emit('reference', ref);
    return ref;
  }

  const s0 = () => settings;
  function render(ref) {
    const n = ref.ids.length;
    const colours = cssColours(ref.sRGB);
    const xy = xyFromXYZ(ref.XYZ);
    summary.textContent = `${n} patches from the ${ref.source}, illuminant ${settings.illuminant}, `
      + `CIE ${settings.observer} observer; white X=${fmt(ref.white[0])} Y=${fmt(ref.white[1])} Z=${fmt(ref.white[2])}.`;
    // A built-in chart's patches laid out as on the chart: each at its cell of the chart's layout
    // (the engine's layout table); an uploaded file's in its own order, six to a row.
    const layout = s0().referenceFile ? null : app.catalog.layouts[settings.chart];
    const cells = new Map((layout?.patches ?? []).map((c) => [c.id, c]));
    const compact = n > 30;
    const pos = (id) => { const c = cells.get(id); return c ? { row: c.row + 1, col: c.column + 1 } : null; };
    swatches.className = `swatches${compact ? ' compact' : ''}`;
    swatches.style.gridTemplateColumns = `repeat(${layout?.columns ?? 6}, minmax(0, 1fr))`;
    swatches.replaceChildren(...ref.ids.map((id, i) => {
      const xyz = `XYZ ${fmt(ref.XYZ[3 * i])}, ${fmt(ref.XYZ[3 * i + 1])}, ${fmt(ref.XYZ[3 * i + 2])}`;
      const lab = `L*a*b* ${fmt(ref.Lab[3 * i], 1)}, ${fmt(ref.Lab[3 * i + 1], 1)}, ${fmt(ref.Lab[3 * i + 2], 1)}`;
      const p = pos(id);
      const label = ref.labels?.[i] ?? id;   // an uploaded file's own spelling ("A01"); data-id is the matching key
      return h('div', { class: 'swatch', dataset: { id }, title: `${label}: ${xyz}; ${lab}`, style: p ? { gridRow: p.row, gridColumn: p.col } : {} },
        h('div', { class: 'chip', style: { background: colours[i] }, 'aria-hidden': 'true' }),
        h('div', { class: 'swatch-text' }, h('strong', {}, label), compact ? null : [h('br'), xyz, h('br'), lab]));
    }));
    const points = ref.ids.map((id, i) => ({
      id, ...xy[i], fill: colours[i],
      title: `${id}\nx ${fmt(xy[i].x, 4)}  y ${fmt(xy[i].y, 4)}\nXYZ ${fmt(ref.XYZ[3 * i])} ${fmt(ref.XYZ[3 * i + 1])} ${fmt(ref.XYZ[3 * i + 2])}`,
    }));
    const [Xw, Yw, Zw] = ref.white;
    const white = Xw + Yw + Zw > 0 ? { x: Xw / (Xw + Yw + Zw), y: Yw / (Xw + Yw + Zw) } : null;
    const svg = xyPlot({ locus: app.derived.locus, points, white, observer: settings.observer });
    plotBox.replaceChildren(figure(svg, { name: 'reference-xy', caption: `Reference patches on the CIE ${settings.observer} xy diagram` }));
  }

  const persist = () => app.save('settings', { ...settings });
  chartSel.addEventListener('change', () => { settings.chart = chartSel.value; settings.referenceFile = null; syncFile(); persist(); update(); });
  illumSel.addEventListener('change', () => { settings.illuminant = illumSel.value; persist(); update(); });
  obsSel.addEventListener('change', () => { settings.observer = obsSel.value; persist(); update(); });
  onFileText(fileInput, async (text, f) => {
    const previous = settings.referenceFile;
    settings.referenceFile = { name: f.name, text };
    await update();
    if (fileInput.getAttribute('aria-invalid')) {   // keep the last good reference
      settings.referenceFile = previous;
    } else persist();
    syncFile();
  });
  useBuiltin.addEventListener('click', () => { settings.referenceFile = null; clearError(fileInput); fileInput.value = ''; syncFile(); persist(); update(); });
  function syncFile() {
    const f = settings.referenceFile;
    fileState.textContent = f ? `Using ${f.name}.` : '';
    useBuiltin.hidden = !f;
    chartSel.disabled = !!f;
  }
  syncFile();
  if (!charts.some((c) => c.value === settings.chart)) settings.chart = charts[0].value;
  if (!illuminants.some((c) => c.value === settings.illuminant)) {
    settings.illuminant = (illuminants.find((c) => c.value === 'D50') ?? illuminants[0]).value;
  }
  setOptions(chartSel, charts, settings.chart);
  setOptions(illumSel, illuminants, settings.illuminant);

  /// Uses {name, text} as the reference (as the file input does); returns the reference, or the
  /// Error (shown next to the file input) after going back to the previous reference.
  async function useFile(file) {
    const previous = settings.referenceFile;
    settings.referenceFile = file;
    const r = await update();
    if (r instanceof Error) { settings.referenceFile = previous; syncFile(); await update(); showError(fileInput, r, file.name); return r; }
    persist();
    syncFile();
    return r;
  }

  return { ready: update(), update, useFile, controls: { chartSel, illumSel, obsSel, fileInput } };
}
