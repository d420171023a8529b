// An exercise's set-up as a link: `#lab=<tab>&<name>=<value>…` (URLSearchParams encoding), so a
// teacher hands out the exact set-up. Every value is checked against the control it sets — a
// picker's options (the engine's catalog) or a number box's min/max — before anything changes;
// a bad link is a coded error (INVALID_ARGUMENT naming the parameter), shown as text.

import { h } from '../lib/ui.js';

const bad = (message) => Object.assign(new Error(message), { code: 'INVALID_ARGUMENT' });

/// The fragment for a tab's controls: '#lab=ex3&camera=Nikon_D850&chart=sg140'.
export function labFragment(tab, params = {}) {
  const p = new URLSearchParams({ lab: tab });
  for (const [k, el] of Object.entries(params)) p.set(k, String(el.value));
  return `#${p.toString()}`;
}

/// The link's tab and values, checked against `tabs` ({id: {name: control}}); null for a
/// fragment that is not a lab link. Throws INVALID_ARGUMENT for an unknown tab, parameter or value.
export function parseLabFragment(hash, tabs) {
  if (!hash.startsWith('#lab=')) return null;
  const p = new URLSearchParams(hash.slice(1));
  const tab = p.get('lab');
  if (!Object.hasOwn(tabs, tab)) throw bad(`lab link: no exercise '${tab}' (one of ${Object.keys(tabs).join(', ')})`);
  const params = tabs[tab], values = {};
  for (const [k, v] of p) {
    if (k === 'lab') continue;
    const el = Object.hasOwn(params, k) ? params[k] : null;
    if (!el) throw bad(`lab link: '${tab}' has no setting '${k}'`);
    if (el.tagName === 'SELECT') {
      if (![...el.options].some((o) => o.value === v)) throw bad(`lab link: '${v}' is not a choice of ${k}`);
    } else {
      const x = Number(v), lo = el.min === '' ? -Infinity : Number(el.min), hi = el.max === '' ? Infinity : Number(el.max);
      if (v.trim() === '' || !Number.isFinite(x) || x < lo || x > hi) throw bad(`lab link: ${k} must be a number in [${el.min || '-∞'}, ${el.max || '∞'}]`);
    }
    values[k] = v;
  }
  return { tab, values };
}

/// Sets the controls of a parsed link (values already checked).
export function applyLabValues(params, values) {
  for (const [k, v] of Object.entries(values)) {
    params[k].value = v;
    params[k].dispatchEvent(new Event('change'));
  }
}

/// Link boxes for the exercise tabs and the opening of a lab link. `exercises`: {tab: {panel,
/// params, run}}; `showTab(tab)` shows a tab. Returns the element where a bad link is reported
/// (text only) and openFromHash() (also run on every hashchange): sets the controls, shows the
/// tab and runs the exercise.
export function wireLabLinks(app, exercises, showTab) {
  const tabs = {};
  for (const [id, ex] of Object.entries(exercises)) {
    tabs[id] = ex.params;
    const out = h('input', { type: 'text', readonly: true, class: 'lab-link', 'data-lab-link': id, 'aria-label': 'Link to this set-up', hidden: true });
    const btn = h('button', { type: 'button', 'data-action': `lab-link-${id}` }, 'Link to this set-up');
    btn.addEventListener('click', () => {
      out.value = `${location.href.split('#')[0]}${labFragment(id, ex.params)}`;
      out.hidden = false;
      out.select();
      navigator.clipboard?.writeText(out.value).catch(() => {});
    });
    ex.panel.append(h('p', { class: 'hint' }, btn, ' ', out, ' (the same exercise with these settings, for a class)'));
  }
  const status = h('p', { class: 'field-error', role: 'alert', 'data-lab': 'link-error', hidden: true });
  async function openFromHash() {
    let link;
    try { link = parseLabFragment(location.hash, tabs); } catch (e) {
      status.textContent = `${e.message} (${e.code}): the link's set-up was not applied.`;
      status.hidden = false;
      app.goto('lab');
      return null;
    }
    if (!link) return null;
    status.hidden = true;
    applyLabValues(tabs[link.tab], link.values);
    app.goto('lab');
    showTab(link.tab);
    return exercises[link.tab].run();
  }
  window.addEventListener('hashchange', () => { if (location.hash.startsWith('#lab=')) openFromHash(); });
  return { status, openFromHash };
}
