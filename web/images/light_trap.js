// The light-trap box of a chart image (Abed, Berns & Masaoka 2013, App. C step 1): a black cavity in
// the scene, marked like a patch; its mean after the dark frame is the flare subtracted per channel
// before sampling (the worker's `sample` with `lightTrap`). Step 2's chart image and every extra
// chart image (second.js) have one. Its four boxes (left x, top y, width, height in pixels) take
// their labels, units, bounds and steps from the engine's rows for the image's size
// (light_trap_option_table, the worker's `lightTrapOptions`); the engine refuses a trap past the
// image's edge (CORNERS_OUTSIDE, shown here).
import { h, showError, clearError, errorSlot, numberValue, fmt } from '../lib/ui.js';

/// A light-trap box. engine: the page's engine; editor(): the image's CornerEditor (or null);
/// stored(): the saved rectangle {x, y, w, h} (or undefined); save(r): stores a rectangle
/// (undefined: no trap) and samples again. Returns {el, corners(), showResult(sample, corners), show(r)}.
export function lightTrapBox({ engine, editor, stored, save }) {
  const trapOn = h('input', { type: 'checkbox', checked: !!stored() });
  // One box per row of the engine's table (x, y, width, height: the rectangle's members).
  const trapIns = ['x', 'y', 'width', 'height'].map((k) => h('input', { type: 'number', 'aria-label': `Light trap ${k}`, dataset: { trap: k } }));
  const trapLabels = trapIns.map((i) => h('span', {}, i.dataset.trap));
  const trapMark = h('button', { type: 'button' }, 'Mark it on the image');
  const trapState = h('p', { class: 'light-trap-state', 'aria-live': 'polite' });
  const trapErr = errorSlot(trapOn);
  const el = h('fieldset', { class: 'light-trap' },
    h('legend', {}, 'Light trap — flare (Abed et al. 2013, App. C)'),
    h('label', {}, trapOn, ' Subtract an in-scene light trap'),
    ...trapIns.map((i, k) => h('label', {}, trapLabels[k], ' ', i)),
    trapMark, trapState, trapErr);
  // The rows for the image shown (asked again when its size changes).
  let rowsFor = '';
  function bound() {
    const ed = editor();
    if (!engine || !ed?.width) return;
    const size = `${ed.width}x${ed.height}`;
    if (size === rowsFor) return;
    rowsFor = size;
    engine.call('lightTrapOptions', { width: ed.width, height: ed.height }).then((rows) => {
      if (rowsFor !== size) return;
      for (const o of rows) {
        const k = trapIns.findIndex((i) => i.dataset.trap === o.name);
        if (k < 0) continue;
        const label = o.unit ? `${o.label} (${o.unit})` : o.label;
        Object.assign(trapIns[k], { min: o.min ?? '', max: o.max ?? '', step: o.step || 1, title: o.description });  // null: unbounded
        trapIns[k].dataset.lightTrapOption = o.name;
        trapIns[k].setAttribute('aria-label', label);
        trapLabels[k].textContent = label.replace(/^Light trap /, '');
      }
    }, (e) => { rowsFor = ''; showError(trapOn, e, 'Light trap'); });
  }
  const rect = () => {
    if (!trapOn.checked) return null;
    const [x, y, w, hh] = trapIns.map((i) => Number(i.value));
    return [x, y, w, hh].every(Number.isFinite) && w > 0 && hh > 0 ? { x, y, w, h: hh } : null;
  };
  const cornersOf = (r) => (r ? [r.x, r.y, r.x + r.w, r.y, r.x + r.w, r.y + r.h, r.x, r.y + r.h] : null);
  /// Shows rectangle r (when given) in the boxes and on the image.
  function show(r) {
    bound();
    if (r) [r.x, r.y, r.w, r.h].forEach((v, i) => { trapIns[i].value = v; });
    for (const i of [...trapIns, trapMark]) i.disabled = !trapOn.checked;
    editor()?.setLightTrap(trapOn.checked ? rect() : null);
  }
  function changed() {
    const r = rect();
    editor()?.setLightTrap(r);
    return save(trapOn.checked ? (r ?? stored() ?? null) : undefined);
  }
  trapOn.addEventListener('change', () => {
    const ed = editor();
    if (trapOn.checked && !rect() && ed?.width) {
      // A first guess to move: a small square at the image's top-left quarter.
      const side = Math.round(Math.min(ed.width, ed.height) / 12);
      show({ x: Math.round(ed.width / 8), y: Math.round(ed.height / 8), w: side, h: side });
    }
    show();
    if (!trapOn.checked) { clearError(trapOn); trapState.textContent = ''; }
    changed();
  });
  for (const i of trapIns) i.addEventListener('change', () => {
    clearError(trapOn);
    // A typo in a box (type=number then reads '') would move the trap to 0 without a word.
    try { for (const b of trapIns) numberValue(b, 0); } catch (e) { showError(trapOn, e, 'Light trap'); return; }
    show(); changed();
  });
  trapMark.addEventListener('click', () => {
    trapState.textContent = 'Drag a rectangle over the light trap on the image.';
    editor()?.markLightTrap((r) => { if (r.w >= 1 && r.h >= 1) { show(r); changed(); } else trapState.textContent = ''; });
  });
  show(stored());

  /// What the light trap gave: the flare subtracted, or the reason it was not used (next to it).
  function showResult(s, corners) {
    clearError(trapOn);
    bound();
    if (!corners) { trapState.textContent = trapOn.checked ? 'Mark the trap (a rectangle of positive size).' : ''; return; }
    if (s.lightTrapError) {
      showError(trapOn, s.lightTrapError, 'Light trap');
      trapState.textContent = 'Not subtracted: the chart is sampled without a light trap.';
      return;
    }
    const t = s.lightTrap;
    trapState.textContent = `Flare subtracted from every pixel: R ${fmt(t.mean[0], 1)}, G ${fmt(t.mean[1], 1)}, B ${fmt(t.mean[2], 1)} DN `
      + `(mean of ${t.n} pixels after the dark frame; σ ${t.std.map((v) => fmt(v, 1)).join(' / ')})${t.flags.length ? ` — ${t.flags.join(', ')}` : ''}.`;
  }
  /// Back to no trap (a removed image).
  function reset() {
    trapOn.checked = false;
    for (const i of trapIns) i.value = '';
    clearError(trapOn);
    trapState.textContent = '';
    show();
  }
  return { el, corners: () => cornersOf(rect()), showResult, show, reset };
}
