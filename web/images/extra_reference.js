// An extra chart image's reference (issue 48): its chart's built-in data, or a file of the user's
// (CSV/CGATS, as step 1 takes it) read under step 1's illuminant and observer into
// app.derived['reference<k>']; the recipe's entry then has a "file" reference (its data_digest),
// and `tristim fit --recipe` takes its --xyz. A custom grid has no built-in data: it needs one.
import { h, field, showError, clearError } from '../lib/ui.js';

/// The reference box of chart image k: {el, read(), clear(), dispose()}. saved(): the panel's session entry;
/// store(patch): updates it; same(): the image is step 2's own (its reference is step 1's);
/// changed(): the reference in use changed.
export function extraReference(app, k, { saved, store, same, changed }) {
  const { engine } = app;
  const key = `reference${k}`;
  const input = h('input', { type: 'file', accept: '.csv,.txt,.cgats,.ti3,.it8', dataset: { role: `chart${k}-reference` } });
  const state = h('span', { class: 'file-state' });
  const builtIn = h('button', { type: 'button', hidden: true, onclick: () => set(null) }, 'Use the built-in reference');
  const el = h('div', { class: 'field-group' }, field('Its reference file (optional; needed for a custom grid)', input,
    'Measured colours of this chart (CSV or CGATS: XYZ, L*a*b* or spectra), in place of the built-in ones'), state, builtIn);
  input.addEventListener('change', () => { if (input.files[0]) set(input.files[0]); });

  /// The ReferenceChart (+ data_digest) of reference file f under step 1's illuminant and observer.
  const parse = (f) => {
    const s = app.derived.reference?.settings ?? {};
    return engine.call('parseReference', { text: f.text, fileName: f.name, illuminant: s.illuminant ?? 'D50', observer: s.observer ?? '1931' });
  };
  const show = (f, ref) => {
    app.derived[key] = ref;
    state.textContent = `${f.name}: ${ref.ids.length} patches`;
    builtIn.hidden = false;
  };
  /// Reads the stored reference file (if any) into app.derived[key] (its error next to its input).
  async function read() {
    const f = saved().referenceFile;
    clearError(input);
    delete app.derived[key];
    state.textContent = '';
    builtIn.hidden = !f;
    if (!f || same()) return;
    try { show(f, await parse(f)); } catch (e) { if (e.code !== 'CANCELLED') showError(input, e, f.name); }
  }
  /// A new reference file (null: back to the built-in chart's); one that does not read is refused
  /// next to its input and the previous one stays.
  async function set(file) {
    clearError(input);
    if (file) {
      try {
        const f = { name: file.name, text: await file.text() };
        const ref = await parse(f);
        await store({ referenceFile: f });
        show(f, ref);
      } catch (e) {
        if (e.code !== 'CANCELLED') showError(input, e, file.name);
        return;
      }
    } else {
      await store({ referenceFile: undefined });
      input.value = '';
      await read();
    }
    changed();
  }
  let gone = false;   // the panel was removed (the page's bus keeps its listeners)
  app.on('reference', () => { if (!gone && saved().referenceFile) read().then(changed); });
  /// The panel is gone or empty: no reference file.
  function clear() {
    delete app.derived[key];
    input.value = state.textContent = '';
    builtIn.hidden = true;
    clearError(input);
  }
  return { el, read, clear, dispose: () => { gone = true; } };
}
