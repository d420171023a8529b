// The per-patch table of a sampling: id, mean camera RGB, std, pixel count, saturation, flags; the
// patches of a chart cut by the frame (the engine's `missing`) as rows "outside the frame".
import { h, fmt } from '../lib/ui.js';

/// stale: the corners in use were not found on this image (detection missed and they were left
/// from before), so no row is "ok": each is marked stale.
export function patchTable(s, { stale = false } = {}) {
  const n = s.ids.length;
  const rows = [];
  for (let i = 0; i < n; i++) {
    const f = stale ? [...s.flags[i], 'stale'] : s.flags[i];
    rows.push(h('tr', { class: f.includes('saturated') ? 'flagged saturated' : f.length ? 'flagged' : '', dataset: { id: s.ids[i] } },
      h('th', { scope: 'row' }, s.ids[i]),
      [0, 1, 2].map((k) => h('td', {}, fmt(s.RGB[3 * i + k], 1))),
      [0, 1, 2].map((k) => h('td', {}, s.std ? fmt(s.std[3 * i + k], 1) : '–')),
      h('td', {}, s.n ? String(s.n[i]) : '–'),
      h('td', {}, s.saturated_fraction ? `${fmt(100 * maxOf(s.saturated_fraction, i, s.saturated_fraction.length / n), 1)} %` : '–'),
      h('td', { class: 'flags' }, f.length ? f.join(', ') : 'ok')));
  }
  for (const id of s.missing ?? []) {
    rows.push(h('tr', { class: 'missing', dataset: { id } }, h('th', { scope: 'row' }, id),
      h('td', { colspan: 9, class: 'flags' }, 'outside the frame: not sampled, left out of the fit')));
  }
  return h('table', { class: 'patch-table' },
    h('caption', {}, 'Sampled camera RGB per patch (linear DN, black subtracted, no white balance; mean and σ over the central area). Flags: saturated (left out of fits), dark (near the noise floor), nonuniform (quadrant means differ by > 5 % beyond noise), stale (the corners were not found on this image); outside the frame (a chart cut by the image edge: the patch is not sampled).'),
    h('thead', {}, h('tr', {}, ['Patch', 'R', 'G', 'B', 'σR', 'σG', 'σB', 'pixels', 'saturated', 'flags'].map((t) => h('th', { scope: 'col' }, t)))),
    h('tbody', {}, rows));
}

function maxOf(a, i, stride) {
  let m = 0;
  for (let k = 0; k < stride; k++) m = Math.max(m, a[i * stride + k]);
  return m;
}
