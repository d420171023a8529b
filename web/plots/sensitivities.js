// Camera spectral sensitivities against wavelength: a chosen set (an uploaded CSV or a Jiang 2013
// estimate; solid) over a built-in camera's measured curves (dashed), R, G, B in their channel
// colours. Each set is scaled by one factor so that its largest value is 1, which keeps the
// ratios between its channels (what eq 7's A_R/A_G/A_B depend on). Pure function from arrays to SVG.
import { getPlot } from './common.js';
import { CHANNELS } from './oecf.js';

/// {wavelengths, values: [R, G, B]} -> rows {set, channel, nm, v}, the set scaled to max 1.
export function sensitivityRows(ssf, set) {
  let peak = 0;
  for (const v of ssf.values) for (const x of v) peak = Math.max(peak, x);
  const rows = [];
  ssf.values.forEach((v, c) => v.forEach((x, i) => rows.push({ set, channel: CHANNELS[c].id, nm: ssf.wavelengths[i], v: peak > 0 ? x / peak : 0 })));
  return rows;
}

/// shown, reference: {label, ssf} (reference may be null).
export function sensitivitiesPlot({ shown, reference }, { width = 720, height = 300, Plot = getPlot() } = {}) {
  const a = sensitivityRows(shown.ssf, shown.label), b = reference ? sensitivityRows(reference.ssf, reference.label) : [];
  const key = (d) => `${d.set} ${d.channel}`;
  return Plot.plot({
    width, height, marginLeft: 50, marginBottom: 40,
    x: { domain: [380, 780], label: 'wavelength (nm) →', grid: true },
    y: { domain: [0, 1.05], label: '↑ relative sensitivity (largest value of the set = 1)', grid: true },
    color: { domain: CHANNELS.map((c) => c.id), range: CHANNELS.map((c) => c.colour), legend: true, label: 'channel' },
    marks: [
      Plot.frame({ stroke: '#ccc' }),
      Plot.line(b, { x: 'nm', y: 'v', z: key, stroke: 'channel', strokeWidth: 1.5, strokeDasharray: '5,4' }),
      Plot.line(a, { x: 'nm', y: 'v', z: key, stroke: 'channel', strokeWidth: 2.2 }),
      Plot.tip(a, Plot.pointerX({ x: 'nm', y: 'v', stroke: 'channel', title: (d) => `${d.set}\n${d.channel} at ${d.nm} nm: ${d.v.toFixed(3)}` })),
    ],
  });
}
