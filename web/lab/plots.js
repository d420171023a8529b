// Lab plots, pure functions from arrays to SVG: a camera's spectral sensitivities (solid) beside
// the best-fit combination of the CIE 1931 colour-matching functions (dashed) — how far the camera
// is from the Luther condition; both on the camera's scale (its largest value = 1).
import { getPlot } from '../plots/common.js';
import { CHANNELS } from '../plots/oecf.js';

/// fit: the engine's LutherFit {wavelengths, camera: [R, G, B], fit: [R, G, B]} -> rows.
export function lutherRows(fit) {
  const rows = [];
  for (const [set, curves] of [['camera', fit.camera], ['best CMF combination', fit.fit]]) {
    curves.forEach((v, c) => v.forEach((x, i) => rows.push({ set, channel: CHANNELS[c].id, nm: fit.wavelengths[i], v: x })));
  }
  return rows;
}

export function lutherPlot(fit, { width = 720, height = 300, Plot = getPlot() } = {}) {
  const rows = lutherRows(fit);
  const cam = rows.filter((d) => d.set === 'camera'), cmf = rows.filter((d) => d.set !== 'camera');
  return Plot.plot({
    width, height, marginLeft: 50, marginBottom: 40,
    x: { domain: [380, 780], label: 'wavelength (nm) →', grid: true },
    y: { label: '↑ relative sensitivity (camera peak = 1)', grid: true },
    color: { domain: CHANNELS.map((c) => c.id), range: CHANNELS.map((c) => c.colour), legend: true, label: 'channel' },
    marks: [
      Plot.frame({ stroke: '#ccc' }),
      Plot.ruleY([0], { stroke: '#999' }),
      Plot.line(cmf, { x: 'nm', y: 'v', z: 'channel', stroke: 'channel', strokeWidth: 1.5, strokeDasharray: '5,4' }),
      Plot.line(cam, { x: 'nm', y: 'v', z: 'channel', stroke: 'channel', strokeWidth: 2.2 }),
      Plot.tip(cam, Plot.pointerX({ x: 'nm', y: 'v', stroke: 'channel', title: (d) => `camera ${d.channel} at ${d.nm} nm: ${d.v.toFixed(3)}` })),
    ],
  });
}

/// Exercise 1: the patch's reflectance (black) and the colour stimulus R·S under each illuminant.
export function stimulusPlot(e, { width = 720, height = 280, Plot = getPlot() } = {}) {
  const rows = [];
  e.illuminants.forEach((id, k) => e.stimulus[k].forEach((v, i) => rows.push({ set: `R·S under ${id}`, nm: e.wavelengths[i], v: v / 100 })));
  e.reflectance.forEach((v, i) => rows.push({ set: 'reflectance R', nm: e.wavelengths[i], v }));
  return Plot.plot({
    width, height, marginLeft: 50, marginBottom: 40,
    x: { label: 'wavelength (nm) →', grid: true },
    y: { label: '↑ R, and R·S with S(560 nm) = 1', grid: true },
    color: { legend: true },
    marks: [Plot.frame({ stroke: '#ccc' }), Plot.line(rows, { x: 'nm', y: 'v', z: 'set', stroke: 'set', strokeWidth: 2 })],
  });
}

/// Exercise 2: mean ΔE00 on the training patches, in leave-one-out and on the held-out Munsell
/// chips, per model, for one training chart (refused models left out).
export function overfitPlot(rows, training, { width = 720, height = 300, Plot = getPlot() } = {}) {
  const data = [];
  for (const r of rows.filter((x) => x.training === training && x.ok)) {
    for (const [k, v] of [['training', r.train_dE00], ['leave-one-out', r.loo_dE00], ['Munsell (held out)', r.test_dE00]]) {
      if (Number.isFinite(v)) data.push({ model: `${r.model} (${r.terms})`, kind: k, v });
    }
  }
  return Plot.plot({
    width, height, marginLeft: 50, marginBottom: 50,
    fx: { label: null, domain: [...new Set(data.map((d) => d.model))] },
    x: { axis: null, domain: ['training', 'leave-one-out', 'Munsell (held out)'] },
    y: { label: '↑ mean ΔE00', grid: true },
    color: { legend: true, domain: ['training', 'leave-one-out', 'Munsell (held out)'] },
    marks: [Plot.barY(data, { fx: 'model', x: 'kind', y: 'v', fill: 'kind' }), Plot.ruleY([0])],
  });
}

/// The metamerism explorer: both reflectances of a pair (the engine's MetamerPair) on its grid.
export function metamerPlot(result, pair, { width = 720, height = 280, Plot = getPlot() } = {}) {
  const rows = [];
  for (const [name, v] of [[pair.a, pair.reflectance_a], [pair.b, pair.reflectance_b]]) {
    v.forEach((x, i) => rows.push({ set: name, nm: result.wavelengths[i], v: x }));
  }
  return Plot.plot({
    width, height, marginLeft: 50, marginBottom: 40,
    x: { label: 'wavelength (nm) →', grid: true },
    y: { label: '↑ reflectance', domain: [0, 1], grid: true },
    color: { legend: true, domain: [pair.a, pair.b], range: ['#333', '#d95f02'] },
    marks: [Plot.frame({ stroke: '#ccc' }), Plot.line(rows, { x: 'nm', y: 'v', z: 'set', stroke: 'set', strokeWidth: 2 }),
      Plot.tip(rows, Plot.pointerX({ x: 'nm', y: 'v', stroke: 'set', title: (d) => `${d.set} at ${d.nm} nm: ${d.v.toFixed(3)}` }))],
  });
}
