// Shared by the Apply step's browser tests: a scene RAW chosen in step 5, the apply with its frames,
// the CLI's float XYZ output (PFM) read back, and the page's applied pixels compared with it to the bit.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { step, noErrorNear, artifact } from './journey.mjs';

/// A colour PFM (bottom-up rows) -> {width, height, at(x, y) -> [X, Y, Z]}.
export function readPfm(buf) {
  let pos = 0;
  const token = () => { while (/\s/.test(String.fromCharCode(buf[pos]))) pos++; const s = pos; while (!/\s/.test(String.fromCharCode(buf[pos]))) pos++; return buf.subarray(s, pos).toString(); };
  assert.equal(token(), 'PF');
  const width = Number(token()), height = Number(token()), scale = Number(token());
  pos++;
  const data = new DataView(buf.buffer, buf.byteOffset + pos);
  const little = scale < 0;
  return { width, height, at: (x, y) => [0, 1, 2].map((c) => data.getFloat32(4 * (3 * ((height - 1 - y) * width + x) + c), little)) };
}

/// Once the first screen's fit is there: step 5, "Another RAW file…", this scene file, and (when
/// given) its flat field in `flatMode`.
export async function chooseScene(page, scene, { flat, flatMode } = {}) {
  await page.waitForFunction(() => window.tristim.session.results?.length > 0, null, { timeout: 300000 });
  await step(page, 'apply');
  await page.selectOption('#step-apply select', 'scene');
  await page.setInputFiles('#step-apply input[type="file"]:not([data-frame])', scene);
  if (flat) await page.setInputFiles('#step-apply input[data-frame="flat"]', flat);
  if (flatMode) await page.check(`#step-apply input[data-flat-mode="${flatMode}"]`);
}

/// Clicks Apply and waits for the frames' line matching `said` (or fails naming the error shown next
/// to an input) and the applied image with no error; returns the frames' line and the file name of
/// the selected profile, written to test-artifacts/<name>-profile.json for the CLI.
export async function applyScene(page, said, name) {
  await page.click('#step-apply button.primary');
  const note = await page.waitForFunction((re) => {
    const n = document.querySelector('#step-apply .frames-note')?.textContent ?? '';
    const err = [...document.querySelectorAll('#step-apply .field-error:not([hidden])')].map((e) => e.textContent).join(' ');
    return new RegExp(re).test(n) ? n : err || null;
  }, said.source, { timeout: 120000 }).then((h) => h.jsonValue());
  assert.match(note, said);
  await page.waitForFunction(() => /Applied to/.test(document.querySelector('#step-apply p.summary:not(.frames-note)')?.textContent ?? ''), null, { timeout: 120000 });
  assert.ok(await noErrorNear(page, '#step-apply button.primary'));
  const profile = await page.evaluate(() => { const t = window.tristim; return (t.session.results.find((r) => r.key === t.session.selected) ?? t.session.results[0]).fit.profile; });
  const file = artifact(`${name}-profile.json`);
  fs.writeFileSync(file, profile);
  return { note, profile: file };
}

/// The page's applied X, Y, Z (the worker's `pixel`) at `points` equal the PFM's, to the bit, and
/// the PFM has signal at one of them at least.
export async function samePixels(page, pfm, points) {
  assert.ok(points.some(([x, y]) => pfm.at(x, y)[1] > 0.1), 'the CLI\'s image has signal');
  for (const [x, y] of points) {
    const p = await page.evaluate(([px, py]) => window.tristim.engine.call('pixel', { x: px, y: py }), [x, y]);
    assert.deepEqual(p.XYZ, pfm.at(x, y), `pixel (${x}, ${y})`);
  }
}
