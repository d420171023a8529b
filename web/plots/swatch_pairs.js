// Swatch pairs: the reference colour as the square's background and the estimate as a centred
// disc (Guarnera et al. 2018, figs 1d and 13). Display sRGB, clipped; a difference you can see.
import { getPlot } from './common.js';
import { patchTitle } from '../lib/perpatch.js';

export function swatchLayout(rows, cols = 6) {
  return rows.map((r, k) => ({ ...r, col: k % cols, rowN: Math.floor(k / cols) }));
}

export function swatchPairsPlot(rows, { cols = 6, cell = 70, Plot = getPlot() } = {}) {
  const c = Math.min(cols, rows.length) || 1;
  const data = swatchLayout(rows, c);
  const nRows = Math.ceil(rows.length / c);
  return Plot.plot({
    width: c * cell + 20, height: nRows * cell + 20, margin: 10,
    x: { domain: [0, c], axis: null }, y: { domain: [nRows, 0], axis: null },
    marks: [
      Plot.rect(data, { x1: (d) => d.col + 0.04, x2: (d) => d.col + 0.96, y1: (d) => d.rowN + 0.04, y2: (d) => d.rowN + 0.96, fill: 'fill', title: patchTitle }),
      Plot.dot(data, { x: (d) => d.col + 0.5, y: (d) => d.rowN + 0.5, r: cell * 0.22, fill: 'fillEst', title: patchTitle, tip: true }),
      Plot.text(data, { x: (d) => d.col + 0.08, y: (d) => d.rowN + 0.1, text: 'id', textAnchor: 'start', fontSize: 9, fill: (d) => (d.L > 55 ? '#000' : '#fff') }),
    ],
  });
}
