// An extra chart image's own dark frames and flat field (Abed 2013 App. C steps 1-2, issue 48):
// decoded into the worker's 'dark<k>' / 'flat<k>' slots, which calibrate its 'chart<k>' (step 2's
// flat-field mode); stored in the session as 'files.dark<k>' / 'files.flat<k>'.
import { h, field, showError, clearError, fileBytes } from '../lib/ui.js';

/// The frames of chart image k: {el, slots, ensure(), names(), forgetAll(), capture()}.
/// ensureImage(): the image itself is decoded in this worker; resample(): samples it again.
export function extraFrames(app, k, { ensureImage, resample }) {
  const { engine } = app;
  const SLOTS = { [`dark${k}`]: 'Its dark frame(s)', [`flat${k}`]: 'Its flat field' };
  const isDark = (slot) => slot.startsWith('dark');
  const ins = {}, states = {}, gen = {};
  const el = h('div', { class: 'frames' });
  for (const [slot, label] of Object.entries(SLOTS)) {
    ins[slot] = h('input', { type: 'file', dataset: { slot }, multiple: isDark(slot) });
    states[slot] = h('span', { class: 'file-state' });
    el.append(h('div', { class: 'field-group' }, field(label, ins[slot], isDark(slot)
      ? 'Lens capped, same settings as this image; several files are averaged' : 'A uniform surface filling this image\'s frame'),
    states[slot], h('button', { type: 'button', 'aria-label': `Remove ${label.toLowerCase()}`, onclick: () => forget(slot) }, 'Remove')));
    ins[slot].addEventListener('change', () => set(slot, [...ins[slot].files]));
  }

  /// Decodes {name, list: [{name, bytes}]} into a frame slot; the worker calibrates the image with
  /// it (refused, e.g. FRAME_MISMATCH, next to its input: the slot keeps what it had).
  async function decode(slot, entry) {
    clearError(ins[slot]);
    const copies = entry.list.map((f) => new Uint8Array(f.bytes).slice().buffer);
    const msg = isDark(slot) ? { slot, bytesList: copies } : { slot, bytes: copies[0], flatMode: entry.mode };
    try {
      await engine.call('decode', msg, { transfer: copies });
      gen[slot] = engine.generation;
      states[slot].textContent = entry.name;
      return true;
    } catch (e) {
      if (e.code !== 'CANCELLED') showError(ins[slot], e, entry.name);
      return false;
    }
  }
  /// Decodes the stored frames again when the worker was restarted since.
  async function ensure() {
    for (const slot of Object.keys(SLOTS)) {
      const f = app.session[`files.${slot}`];
      if (f && gen[slot] !== engine.generation && !(await decode(slot, f))) return false;
    }
    return true;
  }
  async function set(slot, files) {
    if (!files.length) return;
    clearError(ins[slot]);
    let list;
    try { list = await Promise.all(files.map(async (f) => ({ name: f.name, bytes: (await fileBytes(f)).buffer }))); } catch (e) {
      showError(ins[slot], e, files.map((f) => f.name).join(', '));
      return;
    }
    const entry = { name: list.map((f) => f.name).join(', '), list, ...(isDark(slot) ? {} : { mode: app.session.flatMode ?? 'pixel' }) };
    if (!(await ensureImage()) || !(await decode(slot, entry))) return;
    await app.save(`files.${slot}`, entry);
    await resample();
  }
  async function forget(slot, again = true) {
    await app.save(`files.${slot}`, undefined);
    ins[slot].value = states[slot].textContent = '';
    clearError(ins[slot]);
    try { await engine.call('forget', { slot }); } catch { /* the worker may have been restarted */ }
    if (again) await resample();
  }
  return {
    el,
    slots: Object.keys(SLOTS),
    ensure,
    /// The stored frames' names shown (a reload, before they are decoded).
    names: () => { for (const slot of Object.keys(SLOTS)) if (app.session[`files.${slot}`]) states[slot].textContent = app.session[`files.${slot}`].name; },
    /// The slots that hold a frame (e.g. 'dark3 flat3').
    present: () => Object.keys(SLOTS).filter((s) => app.session[`files.${s}`]).join(' '),
    forgetAll: async () => { for (const slot of Object.keys(SLOTS)) if (app.session[`files.${slot}`]) await forget(slot, false); },
  };
}

/// The capture stage of chart image k's own frames ({} without any).
export function framesCapture(app, k) {
  const dark = app.session[`files.dark${k}`], flat = app.session[`files.flat${k}`], radial = flat?.mode === 'radial';
  if (!dark && !flat) return {};
  return { dark_frames: dark?.list.length ?? 0, dark_mode: 'per_pixel', flat_field: !!flat && !radial, falloff: !!flat && radial };
}
