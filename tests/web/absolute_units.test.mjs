// Node unit tests of the Absolute mode's pure functions: the luminance colour-bar limits and
// rendering (linear and log10, NaN drawn as "no value"), the source-exposure map, the OECF rows.
import test from 'node:test';
import assert from 'node:assert/strict';
import { luminanceRange, renderLuminance, renderSource, NO_VALUE_RGB } from '../../web/absolute/render.js';
import { oecfRows } from '../../web/plots/oecf.js';

const grey = Uint8Array.from({ length: 768 }, (_, i) => Math.floor(i / 3));  // entry k = (k, k, k)

test('luminance colour bar: log needs a positive low end; linear starts at 0', () => {
  assert.deepEqual(luminanceRange(0.3, 3000, true), [0.3, 3000]);
  assert.deepEqual(luminanceRange(-1, 3000, true), [0.3, 3000]);   // 1e-4 of the top
  assert.deepEqual(luminanceRange(0.3, 3000, false), [0, 3000]);
  assert.deepEqual(luminanceRange(5, 5, true), [0.5, 5]);
});

test('luminance map: log10 between the limits, clipped at the ends, NaN as no value', () => {
  const Y = [0.1, 1, 10, 100, 1000, NaN];
  const xyz = new Float32Array(3 * Y.length);
  Y.forEach((y, i) => { xyz[3 * i + 1] = y; });
  const r = renderLuminance(xyz, Y.length, 1, { lut: grey, log: true, low: 1, high: 100 });
  const v = Array.from({ length: Y.length }, (_, i) => r.rgba[4 * i]);
  assert.deepEqual(v.slice(0, 5), [0, 0, 128, 255, 255]);   // log10 1 -> 0, 10 -> 127.5, 100 -> 255
  assert.deepEqual(Array.from(r.rgba.slice(20, 23)), NO_VALUE_RGB);
  const lin = renderLuminance(xyz, Y.length, 1, { lut: grey, log: false, low: 1, high: 100 });
  assert.equal(lin.rgba[4 * 2], Math.round(255 * 10 / 100));
  assert.deepEqual(lin.range, [0, 100]);
});

test('source map: one colour per exposure, 255 = none; downsampled by an integer factor', () => {
  const src = Uint8Array.from([0, 1, 255, 1]);
  const r = renderSource(src, 4, 1, { colours: [[1, 2, 3], [4, 5, 6]] });
  assert.deepEqual(Array.from(r.rgba), [1, 2, 3, 255, 4, 5, 6, 255, ...NO_VALUE_RGB, 255, 4, 5, 6, 255]);
  const half = renderSource(new Uint8Array(40 * 20), 40, 20, { colours: [[9, 9, 9]], maxSide: 20 });
  assert.equal(half.factor, 2);
  assert.equal(half.width, 20);
});

test('OECF rows: points, common and own curves per exposure and channel', () => {
  const p = { label: '1/60 s f/8 ISO 100', point_Y: [[30, 60], [30], []], point_R: [[0.1, 0.2], [0.1], []],
    curve_Y: [[1, 2], [1], [1]], curve_R: [[0.01, 0.02], [0.01], [0.01]], own_Y: [[1.1, 2.1], [], []] };
  const { points, curves, own } = oecfRows([p]);
  assert.equal(points.length, 3);
  assert.deepEqual(points[0], { exposure: p.label, channel: 'R', Y: 30, R: 0.1 });
  assert.equal(curves.length, 4);
  assert.deepEqual(own.map((d) => [d.Y, d.R]), [[1.1, 0.01], [2.1, 0.02]]);
});
