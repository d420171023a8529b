// Small DOM helpers shared by the views. No framework: elements are built with h().

/// h('div', {class: 'x', onclick: fn}, child, 'text', ...) -> HTMLElement
export function h(tag, attrs = {}, ...children) {
  const el = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs ?? {})) {
    if (v == null || v === false) continue;
    if (k.startsWith('on') && typeof v === 'function') el.addEventListener(k.slice(2), v);
    else if (k === 'class') el.className = v;
    else if (k === 'dataset') Object.assign(el.dataset, v);
    else if (k === 'style' && typeof v === 'object') Object.assign(el.style, v);
    else if (v === true) el.setAttribute(k, '');
    else el.setAttribute(k, v);
  }
  append(el, children);
  return el;
}

function append(el, children) {
  for (const c of children.flat(Infinity)) {
    if (c == null || c === false) continue;
    el.append(c instanceof Node ? c : String(c));
  }
}

let uid = 0;
export const nextId = (prefix) => `${prefix}-${++uid}`;

/// A labelled control: <label for=id>text</label> control, plus an error slot right after it.
export function field(labelText, control, hint) {
  control.id ||= nextId('f');
  const err = errorSlot(control);
  return h('div', { class: 'field' }, h('label', { for: control.id }, labelText), control,
    hint ? h('small', { class: 'hint' }, hint) : null, err);
}

/// The number in an <input type=number>, or `empty` when the box is empty (no `empty`: the box
/// needs a value). When the browser could not read what was typed ('1e', '--', '2,5' where the
/// decimal mark is a point: validity.badInput), type=number reports '' as its value — which
/// `Number(x.value) || 0` read as "empty" without a word. That, and an empty box that needs a value,
/// throw INVALID_ARGUMENT carrying the input, to be shown next to it.
export function numberValue(input, empty) {
  const name = input.getAttribute('aria-label') || input.labels?.[0]?.textContent?.trim() || 'this box';
  const bad = (why) => Object.assign(new Error(`${name}: ${why}`), { code: 'INVALID_ARGUMENT', input });
  if (input.validity?.badInput) throw bad('what was typed is not a number');
  const text = String(input.value).trim();
  if (text === '') {
    if (empty === undefined) throw bad('needs a number');
    return empty;
  }
  const v = Number(text);
  if (!Number.isFinite(v)) throw bad(`'${text}' is not a number`);
  return v;
}

/// An element where errors about `control` appear (aria-describedby links them).
export function errorSlot(control) {
  const err = h('p', { class: 'field-error', role: 'alert', hidden: true });
  err.id = `${control.id || nextId('c')}-error`;
  control.setAttribute('aria-describedby', err.id);
  control._errorSlot = err;
  return err;
}

/// Shows `error` (with its code) next to `control`; the rest of the page keeps working.
export function showError(control, error, context = '') {
  const slot = control?._errorSlot;
  // The engine's errors carry a string code. A browser DOMException has a legacy numeric one (a
  // file moved or deleted after it was chosen: NotFoundError, 8; unreadable: NotReadableError):
  // named instead, as a file the page could not read.
  const unreadable = typeof DOMException !== 'undefined' && error instanceof DOMException;
  const code = unreadable ? 'FILE_UNREADABLE' : typeof error?.code === 'string' ? error.code : 'ERROR';
  const message = unreadable ? `the file could not be read (${error.name}: moved, deleted or changed since it was chosen?)`
    : String(error?.message ?? error);
  const text = `${context && !message.includes(context) ? context + ': ' : ''}${message} (${code})`;
  if (!slot) { console.warn(text); return; }
  slot.textContent = text;
  slot.dataset.code = code;
  slot.hidden = false;
  control.setAttribute('aria-invalid', 'true');
  // A refused file is not kept in its input (the message names it; the file in use is the one
  // the control's status line names), so the input never shows a file that was not loaded.
  if (control.type === 'file') control.value = '';
}

export function clearError(control) {
  const slot = control?._errorSlot;
  if (slot) { slot.hidden = true; slot.textContent = ''; delete slot.dataset.code; }
  control?.removeAttribute('aria-invalid');
}

/// A <select> from [{value, label}] (or strings).
export function select(options, value) {
  const s = h('select');
  setOptions(s, options, value);
  return s;
}
export function setOptions(s, options, value) {
  s.replaceChildren(...options.map((o) => {
    const v = typeof o === 'string' ? o : o.value;
    const l = typeof o === 'string' ? o : o.label;
    return h('option', { value: v, selected: v === value }, l);
  }));
  if (value != null && options.some((o) => (typeof o === 'string' ? o : o.value) === value)) s.value = value;
}

/// A progress bar with a label, updated by progress messages {fraction, stage}.
export function progressBar(label) {
  const bar = h('progress', { max: 1, value: 0, 'aria-label': label });
  const text = h('span', { class: 'progress-text' }, '');
  const el = h('div', { class: 'progress', hidden: true }, bar, text);
  return {
    el,
    start(stage = label) { el.hidden = false; bar.removeAttribute('value'); text.textContent = stage; },
    update({ fraction, stage }) {
      if (Number.isFinite(fraction)) bar.value = fraction; else bar.removeAttribute('value');
      if (stage) text.textContent = stage;
    },
    done() { el.hidden = true; },
  };
}

export function download(name, data, type) {
  const blob = data instanceof Blob ? data : new Blob([data], { type });
  const url = URL.createObjectURL(blob);
  const a = h('a', { href: url, download: name });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

export const fmt = (x, d = 2) => (Number.isFinite(x) ? x.toFixed(d) : '–');

/// Reads a File as bytes (Uint8Array) or text.
export const fileBytes = async (file) => new Uint8Array(await file.arrayBuffer());

/// The text of a chosen file, or null after showing why it could not be read (moved or deleted
/// since it was chosen: FILE_UNREADABLE) next to its input.
export async function readText(input, file) {
  try { return await file.text(); } catch (e) { showError(input, e, file.name); return null; }
}

/// On each file chosen in `input`: its error cleared, its text read (readText), then
/// `use(text, file)`.
export function onFileText(input, use) {
  input.addEventListener('change', async () => {
    const f = input.files[0];
    if (!f) return;
    clearError(input);
    const text = await readText(input, f);
    if (text != null) await use(text, f);
  });
}
