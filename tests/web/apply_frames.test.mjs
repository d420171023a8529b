// Step 5 on another RAW with its own frames (Abed 2013 App. C step 8): a flat field and a light trap
// typed as corners (dark frames take the same setDark as step 2's, not exercised here: the one RAW
// of this camera at hand minus itself is zero); the page's applied XYZ equal `tristim apply …
// --flat … --light-trap …` (float32 PFM) at sampled pixels, to the bit, and are not all zero.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { execFileSync } from 'node:child_process';
import { screenshot } from './harness.mjs';
import { pageTest, step, CLI, DNG, artifact, filePath, noErrorNear } from './journey.mjs';

/// A colour PFM (bottom-up rows) -> {width, height, at(x, y) -> [X, Y, Z]}.
function readPfm(buf) {
  let pos = 0;
  const token = () => { while (/\s/.test(String.fromCharCode(buf[pos]))) pos++; const s = pos; while (!/\s/.test(String.fromCharCode(buf[pos]))) pos++; return buf.subarray(s, pos).toString(); };
  assert.equal(token(), 'PF');
  const width = Number(token()), height = Number(token()), scale = Number(token());
  pos++;
  const data = new DataView(buf.buffer, buf.byteOffset + pos);
  const little = scale < 0;
  return { width, height, at: (x, y) => [0, 1, 2].map((c) => data.getFloat32(4 * (3 * ((height - 1 - y) * width + x) + c), little)) };
}

pageTest('apply with the scene\'s own flat field and light trap equals tristim apply', { timeout: 600000 }, async ({ page }) => {
  await page.waitForFunction(() => window.tristim.session.results?.length > 0, null, { timeout: 300000 });
  await step(page, 'apply');
  await page.selectOption('#step-apply select', 'scene');
  const dng = filePath(DNG);
  await page.setInputFiles('#step-apply input[type="file"]:not([data-frame])', dng);
  // The same RAW as its flat field, fitted as a radial fall-off (Guarnera 2018 eq 7; a per-pixel
  // flat needs signal in every pixel, which a chart photo lacks), and a light trap typed as corners.
  await page.setInputFiles('#step-apply input[data-frame="flat"]', dng);
  await page.check('#step-apply input[data-flat-mode="radial"]');
  const trap = '20,20,80,20,80,60,20,60';
  await page.fill('#step-apply input[data-frame="light-trap"]', trap);
  await page.click('#step-apply button.primary');
  // The frames' line, or the error shown next to an input (then the test fails naming it).
  const said = await page.waitForFunction(() => {
    const note = document.querySelector('#step-apply .frames-note')?.textContent ?? '';
    const err = [...document.querySelectorAll('#step-apply .field-error:not([hidden])')].map((e) => e.textContent).join(' ');
    return /light trap: flare/.test(note) ? note : err || null;
  }, null, { timeout: 120000 }).then((h) => h.jsonValue());
  assert.match(said, /flat field \(radial\); light trap: flare/);
  await page.waitForFunction(() => /Applied to/.test(document.querySelector('#step-apply p.summary:not(.frames-note)')?.textContent ?? ''), null, { timeout: 120000 });
  assert.ok(await noErrorNear(page, '#step-apply button.primary'));
  const profile = await page.evaluate(() => { const t = window.tristim; return (t.session.results.find((r) => r.key === t.session.selected) ?? t.session.results[0]).fit.profile; });
  fs.writeFileSync(artifact('apply-frames-profile.json'), profile);
  const out = artifact('apply-frames.pfm');
  execFileSync(CLI, ['apply', artifact('apply-frames-profile.json'), dng, '--flat', dng, '--flat-mode', 'radial', '--light-trap', trap, '--out', out], { stdio: 'ignore' });
  const pfm = readPfm(fs.readFileSync(out));
  const points = [[0, 0], [300, 200], [500, 400], [pfm.width - 1, pfm.height - 1], [123, 77]];
  assert.ok(points.some(([x, y]) => pfm.at(x, y)[1] > 0.1), 'the CLI\'s image has signal');
  for (const [x, y] of points) {
    const p = await page.evaluate(([px, py]) => window.tristim.engine.call('pixel', { x: px, y: py }), [x, y]);
    assert.deepEqual(p.XYZ, pfm.at(x, y), `pixel (${x}, ${y})`);
  }
  await screenshot(page, 'apply-frames');
});
