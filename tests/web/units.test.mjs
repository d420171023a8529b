// Node unit tests of the page's pure functions (the excluded ids, plot data, display, forms). The .cube and
// ICC readers are the engine's: tests/wasm/formats.test.mjs.
// (Chart layouts, the corner homography and crossed corners are the engine's: tests/wasm.)
import test from 'node:test';
import assert from 'node:assert/strict';
import { excludedBy } from '../../web/lib/pairs.js';
import { deSegments } from '../../web/plots/de_bars.js';
import { xyFromXYZ, cssColours } from '../../web/plots/common.js';
import { locusData } from '../../web/plots/xy.js';
import { xyzScatterData } from '../../web/plots/xyz_scatter.js';
import { renderXYZ } from '../../web/apply/render.js';
import { defaultChoice, completeChoice } from '../../web/lib/options_form.js';

const close = (a, b, tol = 1e-9) => assert.ok(Math.abs(a - b) <= tol, `${a} vs ${b} (tol ${tol})`);

// The pairing itself is the engine's (tests/wasm/pairs_page.test.mjs); the page only picks the ids
// its "leave out saturated" toggle writes into the recipe's sampling.exclude.
test('the saturated patches the page leaves out are picked by their flags', () => {
  const s = { ids: ['A1', 'A2', 'X9', 'B1'], flags: [[], ['saturated'], ['dark'], ['saturated', 'nonuniform']] };
  assert.deepEqual(excludedBy(s, (f) => f.includes('saturated')), ['A2', 'B1']);
  assert.deepEqual(excludedBy({ ids: ['A1'] }, (f) => f.includes('saturated')), []);
});

test('ΔE00 bar segments add up to ΔE00', () => {
  const segs = deSegments([{ id: 'A1', dE: 3, dL: 1, dC: 2, dH: 2 }]);
  close(segs.reduce((s, x) => s + x.value, 0), 3, 1e-12);
  close(segs[0].value, 3 / 9, 1e-12);
});

test('chromaticities, locus closing, scatter data, colours', () => {
  const xy = xyFromXYZ([95.047, 100, 108.883]);
  close(xy[0].x, 0.3127, 1e-4); close(xy[0].y, 0.3290, 1e-4);
  const l = locusData({ wavelengths: [460, 520, 620], x: [0.14, 0.07, 0.69], y: [0.03, 0.83, 0.31] });
  assert.deepEqual(l.line[0], l.line[l.line.length - 1]);
  assert.equal(l.ticks.length, 3);
  assert.equal(xyzScatterData([{ X: 1, Y: 2, Z: 3, Xe: 1, Ye: 2, Ze: 3 }]).length, 3);
  assert.deepEqual(cssColours([1, 0, 0.5]), ['rgb(255, 0, 128)']);
  assert.deepEqual(cssColours([255, 0, 128]), ['rgb(255, 0, 128)']);
});

test('Y map: the white is at the top of the colour table, half the white in its middle', () => {
  // (Display sRGB and L*a*b* come from the engine: tests/wasm/colorimetry.test.mjs.)
  const d50 = [96.422, 100, 82.521];
  const lut = new Uint8Array(768).map((_, i) => Math.floor(i / 3));
  const matrix = [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01], enc = new Uint8ClampedArray(4096);
  const r = renderXYZ(Float32Array.from([...d50, ...d50.map((v) => v / 2)]), 2, 1, { matrix, enc, lut, yMax: 100 });
  assert.deepEqual(Array.from(r.ymap.slice(0, 4)), [255, 255, 255, 255]);
  assert.ok(Math.abs(r.ymap[4] - 127.5) <= 0.5, `half white maps to the middle of the table (${r.ymap[4]})`);
});

test('options forms: a MethodChoice from an OptionSpec table, stored choices completed', () => {
  const info = { id: 'de2000', options: [
    { name: 'algorithm', type: 'choice', default_text: 'auto', default_number: 0, choices: ['auto', 'lm'] },
    { name: 'rms', type: 'boolean', default_number: 0, default_text: '' },
    { name: 'max_evaluations', type: 'integer', default_number: 0, default_text: '' }] };
  assert.deepEqual(defaultChoice(info), { method: 'de2000', parameters: { rms: 0, max_evaluations: 0 }, settings: { algorithm: 'auto' } });
  const stored = { method: 'de2000', parameters: { rms: 1, gone: 3 }, settings: {} };
  assert.deepEqual(completeChoice(info, stored), { method: 'de2000', parameters: { rms: 1, max_evaluations: 0 }, settings: { algorithm: 'auto' } });
});
