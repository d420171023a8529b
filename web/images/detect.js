// Worker handler of step 2: automatic chart detection (issue 12) in the decoded chart image
// (state.raw.chart, its dark/flat applied). Reports the detector's stages as progress.
import { reply, coded } from '../lib/reply.js';
import { isChart } from './handlers.js';

const STAGES = { segment: 'finding flat patches', group: 'grouping patches into grids', orient: 'placing the chart', refine: 'refining the corners' };

export const handlers = {
  /// detect({layout, seed?, box?}) -> {candidates: [ChartCandidate + grid {layout, homography}]}, best
  /// first, for the chosen layout (a custom grid: its geometry); seed [x, y] or box [x0, y0, x1, y1]
  /// (image pixels): look there (DetectOptions). Throws CHART_NOT_FOUND, saying why, when there is none.
  /// `slot`: the image to search ('chart', or 'chart2', 'chart3', …: an extra chart image).
  detect: (T, { slot = 'chart', layout = { chart: 'passport' }, seed, box }, { state, progress }) => {
    if (!isChart(slot) || !state.raw?.[slot]) throw coded('no image decoded yet', 'NO_IMAGE');
    // A chart cut by the frame is found too (its `missing` patches lie outside the image): the
    // sampling (handlers.js) samples the patches inside, as `tristim sample` does.
    const options = { charts: [layout.chart], seed, box, cut_charts: true };
    if (layout.chart === 'custom') options.custom = layout;
    progress(0, 'finding the chart');
    const found = T.detectCharts(state.raw[slot], options, (stage, fraction) => progress(fraction, `finding the chart: ${STAGES[stage] ?? stage}`));
    const grid = T.chartLayout(layout);
    const candidates = found.map((c) => ({ ...c, corners: Array.from(c.corners), grid: { layout: grid, homography: T.homographyUnitSquare(c.corners) } }));
    return reply({ candidates });
  },
};
