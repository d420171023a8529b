// The Share step's pure functions (web/share/project.js) under node: a session with typed arrays
// and byte buffers goes into a project's parts and comes back equal; the results text splits into
// rows; a project naming an image it does not hold, or an unknown array type, is a coded error;
// a link beyond the engine's limit is not offered, the note says why and points to a project file.
import test from 'node:test';
import assert from 'node:assert/strict';
import { encodeSession, decodeSession, resultRows, linkOffer } from '../../web/share/project.js';
import { loadTristim } from '../wasm/load.mjs';

test('a session round-trips through encodeSession / decodeSession', () => {
  const raw = new Uint8Array([1, 2, 3, 250]).buffer;
  const session = {
    settings: { illuminant: 'D65', observer: '1931' },
    corners: [1.5, 2, 3, 4, 5, 6, 7, 8],
    'files.chart': { name: 'chart.dng', bytes: raw },
    'files.dark': { name: 'a.dng, b.dng', list: [{ name: 'a.dng', bytes: new Uint8Array([9]).buffer }, { name: 'b.dng', bytes: new Uint8Array([8, 7]).buffer }] },
    results: [{ key: 'm|ls', rgb: Float64Array.from([0.1, 1e-300, -2]), n: Int32Array.from([3, -4]) }],
    gone: undefined,
  };
  const { json, images } = encodeSession(session);
  assert.deepEqual(images.map((i) => [i.key, i.name, Array.from(i.bytes)]),
    [['files.chart', 'chart.dng', [1, 2, 3, 250]], ['files.dark', 'a.dng', [9]], ['files.dark', 'b.dng', [8, 7]]]);
  const back = decodeSession(json, images);
  assert.equal('gone' in back, false);
  assert.deepEqual(new Uint8Array(back['files.chart'].bytes), new Uint8Array(raw));
  assert.ok(back['files.chart'].bytes instanceof ArrayBuffer);
  assert.ok(back.results[0].rgb instanceof Float64Array);
  assert.deepEqual(Array.from(back.results[0].rgb), [0.1, 1e-300, -2]);
  assert.ok(back.results[0].n instanceof Int32Array);
  const { 'files.chart': c, 'files.dark': d, results, ...rest } = back;
  assert.deepEqual(rest, { settings: session.settings, corners: session.corners });
  assert.deepEqual(d.list.map((x) => Array.from(new Uint8Array(x.bytes))), [[9], [8, 7]]);
});

test('a project that names a missing image or an unknown array type is refused with a code', () => {
  assert.throws(() => decodeSession('{"x": {"$image": 3}}', []), (e) => e.code === 'PARSE_ERROR');
  assert.throws(() => decodeSession('{"x": {"$typed": "BigInt64Array", "data": [1]}}', []), (e) => e.code === 'PARSE_ERROR');
});

test('results text rows', () => {
  assert.deepEqual(resultRows('model matrix-3x3\ncoefficients 1 2 3\nstatus\n'), [['model', 'matrix-3x3'], ['coefficients', '1 2 3'], ['status', '']]);
});

test('a link beyond the engine\'s limit is not offered: the note says why and offers a project file', async () => {
  const limit = (await loadTristim()).shareLinkLimit();
  assert.equal(limit, 16000);
  const within = linkOffer('x'.repeat(limit), limit, 'matrix-3x3');
  assert.equal(within.link.length, limit);
  assert.match(within.note, /^matrix-3x3: 16000 characters\./);
  const beyond = linkOffer('x'.repeat(limit + 1), limit, 'matrix-3x3');
  assert.equal(beyond.link, '');
  assert.match(beyond.note, /16001 characters, more than 16000 .*cut such links.*project file/);
});
