// The Results swatches of a fit on several charts (issue 48, web/lib/perpatch.js): a "k:A1" row of
// the first image's chart takes the step 1 reference's colour; a row of another chart (here a
// ColorChecker SG beside a ColorChecker) is not in that reference and takes the colour of its own
// reference XYZ (the fit's display sRGB, `refSRGB`), not grey. Pure functions, no browser.
import test from 'node:test';
import assert from 'node:assert/strict';
import { perPatch } from '../../web/lib/perpatch.js';

const chart = (id) => ({ reference: { chart: id } });

test('several charts: every swatch has a colour, the k-th chart\'s whatever the chart', () => {
  const ids = ['1:A1', '1:B1', '2:A1', '2:N10'];
  const n = ids.length, nan = new Float64Array(n).fill(NaN);
  const result = {
    ids, xyz: new Float64Array(3 * n).fill(0.2), white: [0.96, 1, 0.82],
    recipe: { images: [chart('cc24'), chart('sg140')] },
    fit: {
      evaluation: { fit: { fitted: new Float64Array(3 * n).fill(0.2) }, training: { patches: { dE00: nan, dL: nan, dC: nan, dH: nan } } },
      display: { refLab: new Float64Array(3 * n), estLab: new Float64Array(3 * n), estSRGB: new Float64Array(3 * n).fill(0.5),
        refSRGB: Float64Array.from([0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]) },
    },
  };
  // Step 1's reference: the first image's chart (cc24), A1 white and B1 black.
  const reference = { ids: ['A1', 'B1'], sRGB: Float64Array.from([1, 1, 1, 0, 0, 0]) };
  const fills = perPatch(result, reference).rows.map((r) => r.fill);
  assert.notEqual(fills[0], fills[1], 'chart 1 from the reference');
  assert.ok(!fills.includes('#999'), `no grey swatch: ${fills}`);
  assert.notEqual(fills[2], fills[0], '2:A1 is the SG\'s A1 (red here), not the ColorChecker\'s');
  assert.notEqual(fills[3], fills[2], '2:N10 its own colour');
  // Without the fit's reference colours (an older result) another chart's rows stay grey.
  delete result.fit.display.refSRGB;
  assert.deepEqual(perPatch(result, reference).rows.map((r) => r.fill).slice(2), ['#999', '#999']);
});
