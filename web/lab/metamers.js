// The Lab's metamerism explorer (core/include/tristim/lab/metamerism.hpp): pairs of Munsell chips
// that match under one light and not under another, or a metamer of one chip constructed with a
// metameric black; for the CIE observer and, optionally, a camera of the 52. A table of pairs, a
// plot of both spectra of the chosen pair and its ΔE00 under each light, the CLI equivalent.
import { h, field, select, showError, clearError, numberValue, fmt } from '../lib/ui.js';
import { options } from '../lib/catalog.js';
import { labPanel } from './panel.js';
import { figure } from '../plots/common.js';
import { metamerPlot } from './plots.js';
import { fillChips } from './chips.js';
import { labOptionBoxes } from './options.js';

const q = (s) => (/^[\w.+/-]+$/.test(s) ? s : `"${s}"`);

/// The command line printing the same result.
export function metamersCommand(o, construct) {
  let s = `tristim lab metamers --illuminant ${o.illuminant} --second ${o.second} --observer ${o.observer}`;
  if (o.camera) s += ` --camera ${q(o.camera)}`;
  if (o.match !== 'observer') s += ` --match ${o.match}`;
  s += construct ? ` --construct ${q(construct)}` : ` --max-match ${o.max_match} --top ${o.top}`;
  return `${s} --json`;
}

export function metamersPanel(app) {
  const illuminants = options(app.catalog.illuminants);
  const cams = [{ value: '', label: '(none: the observer only)' }, ...options(app.catalog.cameras)];
  const ill1 = select(illuminants, 'D65'), ill2 = select(illuminants, 'A');
  const obsSel = select(options(app.catalog.observers), '1931');
  const camSel = select(cams, '');
  // Who the pair matches for: the engine's viewers (metamer_match_table), the default first.
  const matches = app.catalog.metamerMatches ?? [];
  const matchSel = select(matches.map((m) => ({ value: m.id, label: m.label })), matches[0]?.id);
  const boxes = labOptionBoxes(app);
  const maxIn = boxes.box('metamers.max_match', 'met-max'), topIn = boxes.box('metamers.top', 'met-top');
  const chipSel = select([{ value: '5R5/6', label: '5R5/6' }], '5R5/6');
  const searchBtn = h('button', { type: 'button', 'data-action': 'lab-met-search' }, 'Find pairs');
  const constructBtn = h('button', { type: 'button', 'data-action': 'lab-met-construct' }, 'Construct a metamer');
  const cli = h('pre', { class: 'cli', 'data-lab': 'met-cli' });
  const summary = h('p', { class: 'summary', 'data-lab': 'met-summary' });
  const tableBox = h('div', { class: 'table-scroll' });
  const plotBox = h('div', { class: 'plot-box', 'data-lab': 'met-plot' });
  for (const [el, name] of [[ill1, 'met-ill1'], [ill2, 'met-ill2'], [obsSel, 'met-observer'], [camSel, 'met-camera'],
    [matchSel, 'met-match'], [chipSel, 'met-chip']]) el.dataset.lab = name;

  const loadChips = () => fillChips(app, chipSel);

  function readOptions() {
    return { illuminant: ill1.value, second: ill2.value, observer: obsSel.value, camera: camSel.value, match: matchSel.value,
      max_match: numberValue(maxIn), top: numberValue(topIn) };
  }

  /// One pair: both spectra, and per viewer the ΔE00 under each light with a sentence.
  function showPair(r, p) {
    const lines = p.views.map((v) => h('li', {},
      `${v.viewer}: ΔE00 ${fmt(v.dE00_1, 2)} under ${r.illuminant}, ${fmt(v.dE00_2, 2)} under ${r.second}`));
    const m = p.views[r.match === 'camera' ? 1 : 0];
    plotBox.replaceChildren(
      figure(metamerPlot(r, p), { name: 'lab-metamers', caption: `${p.a} and ${p.b}` }),
      h('ul', { class: 'explain', 'data-lab': 'met-dE' }, ...lines),
      h('p', { class: 'explain' },
        `For ${m.viewer} the two surfaces look ${m.dE00_1 < 1 ? 'the same' : 'different'} under ${r.illuminant} `
        + `(ΔE00 ${fmt(m.dE00_1, 2)}) and ${m.dE00_2 < 1 ? 'still alike' : 'different'} under ${r.second} (ΔE00 ${fmt(m.dE00_2, 2)}). `
        + 'Three numbers per light summarise a whole spectrum: spectra that differ where the light is weak, or where the '
        + 'observer\'s curves cancel out, give the same three numbers (metamers). Change the light and the cancellation '
        + 'breaks. A camera whose curves are not a mix of the CMFs cancels elsewhere, so it can see a difference the eye '
        + 'does not, and the reverse.'
        + (r.camera ? ` The camera's XYZ: ${r.camera_matrix}.` : '')));
  }

  async function run(construct) {
    const btn = construct ? constructBtn : searchBtn;
    clearError(searchBtn);
    clearError(constructBtn);
    let o;
    try { o = readOptions(); } catch (e) { showError(e.input ?? btn, e, 'Metamers'); return null; }
    cli.textContent = metamersCommand(o, construct ? chipSel.value : '');
    btn.disabled = true;
    let r;
    try { r = await app.engine.call('labMetamers', { options: o, construct: construct ? chipSel.value : '' }); } catch (e) {
      showError(btn, e, 'Metamers');
      return null;
    } finally { btn.disabled = false; }
    summary.textContent = construct
      ? `${r.pairs[0].a} and its metamer: the chip plus a metameric black (a spectrum the ${r.match} integrates to zero under `
        + `${r.illuminant}), scaled by ${fmt(r.pairs[0].alpha, 4)}, the most that keeps it between 0 and 1.`
      : `${r.matching} pairs of Munsell chips match within ΔE00 `
        + `${r.max_match} for the ${r.match} under ${r.illuminant} (${r.compared} of ${r.all_pairs} pairs compared: only those `
        + `close in L*). The ${r.pairs.length} that differ most under ${r.second}:`;
    const heads = ['a', 'b', ...(r.pairs[0]?.views ?? []).flatMap((v) => [r.illuminant, r.second].map((l) => `${v.viewer}: ΔE00 ${l}`))];
    const body = r.pairs.map((p) => {
      const b = h('button', { type: 'button', class: 'link' }, p.a);
      b.addEventListener('click', () => showPair(r, p));
      return h('tr', {}, h('td', {}, b), h('td', {}, p.b),
        ...p.views.flatMap((v) => [h('td', { class: 'num' }, fmt(v.dE00_1, 2)), h('td', { class: 'num' }, fmt(v.dE00_2, 2))]));
    });
    tableBox.replaceChildren(h('table', { class: 'data', 'data-lab': 'met-pairs' },
      h('thead', {}, h('tr', {}, ...heads.map((t) => h('th', { scope: 'col' }, t)))), h('tbody', {}, ...body)));
    if (r.pairs.length) showPair(r, r.pairs[0]);
    else plotBox.replaceChildren();
    return r;
  }

  searchBtn.addEventListener('click', () => run(false));
  constructBtn.addEventListener('click', () => run(true));
  chipSel.addEventListener('focus', () => loadChips().catch((e) => showError(constructBtn, e, 'Munsell chips')));
  const panel = labPanel({ id: 'metamers', title: 'Metamerism explorer',
    explain:
      'Two surfaces are metamers when they match under one light and not under another. Search the 1269 Munsell matte '
      + 'chips for pairs that match under the first light and differ most under the second, or construct a metamer of a '
      + 'chip: add to its reflectance a metameric black (Wyszecki 1958), a spectrum the viewer does not see under the '
      + 'first light. With a camera, its numbers are shown too (and the pair can be made to match for the camera).',
    controls: [field('First light (match)', ill1), field('Second light', ill2), field('Observer', obsSel),
      field('Camera', camSel), field('Match for', matchSel),
      boxes.field(maxIn), boxes.field(topIn), field('Munsell chip', chipSel)],
    buttons: [searchBtn, constructBtn], cli }, summary, tableBox, plotBox);
  return { panel, run: (construct = false) => loadChips().then(() => run(construct)), loadChips };
}
