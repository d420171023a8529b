// Journey: the light trap of step 2 (Abed, Berns & Masaoka 2013, App. C step 1). The example's black
// patch D6 is marked as the trap: its mean after the dark frame is the flare, subtracted from every
// pixel before sampling, so every patch drops by exactly that flare and D6 itself lands near 0; the
// trap and its flare go into the fit's recipe; a trap outside the image is refused next to its
// input and the chart is sampled without it; a drag on the image marks a trap.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { screenshot, repoRoot } from './harness.mjs';
import { step, errorNear, noErrorNear, pageTest } from './journey.mjs';

const TRAP = { x: 603, y: 443, width: 40, height: 38 };   // inside D6 of the example Passport
const box = '#step-images fieldset.light-trap';
const rgbOf = (page, id) => page.evaluate((pid) => {
  const s = window.tristim.derived.sample;
  const i = s.ids.indexOf(pid);
  return [0, 1, 2].map((c) => s.RGB[3 * i + c]);
}, id);
const waitTrap = (page, used) => page.waitForFunction((u) => {
  const s = window.tristim.derived.sample;
  return s && (u ? !!s.lightTrap : !s.lightTrap && !s.lightTrapError);
}, used, { timeout: 30000 });

async function setTrap(page, t) {
  for (const [k, v] of Object.entries(t)) {
    await page.fill(`${box} input[data-trap="${k}"]`, String(v));
    await page.dispatchEvent(`${box} input[data-trap="${k}"]`, 'change');
  }
}

pageTest('light trap: flare measured in the marked region is subtracted before sampling and lands in the recipe', async ({ page }) => {
  await step(page, 'images');
  await page.waitForFunction(() => window.tristim.derived.sample?.ids?.length === 24, null, { timeout: 60000 });
  const a1 = await rgbOf(page, 'A1'), d6 = await rgbOf(page, 'D6');

  // 1. The trap over D6: the flare shown is the engine's, every patch drops by exactly it.
  await page.check(`${box} input[type=checkbox]`);
  await setTrap(page, TRAP);
  // each box's change samples again: wait for the sampling of the last one (the full rectangle)
  await page.waitForFunction((c) => JSON.stringify(window.tristim.derived.sample?.lightTrapCorners) === c,
    JSON.stringify([603, 443, 643, 443, 643, 481, 603, 481]), { timeout: 30000 });
  await page.waitForFunction((s) => /Flare subtracted/.test(document.querySelector(s)?.textContent ?? ''), `${box} .light-trap-state`);
  await waitTrap(page, true);
  const trap = await page.evaluate(() => { const t = window.tristim.derived.sample.lightTrap; return { mean: Array.from(t.mean), n: t.n, corners: window.tristim.derived.sample.lightTrapCorners }; });
  assert.deepEqual(trap.corners, [603, 443, 643, 443, 643, 481, 603, 481]);
  assert.ok(trap.n > 100, `trap pixels averaged: ${trap.n}`);
  // The trap covers D6's centre: the flare is the black patch's own level (D6 sampled before).
  for (let c = 0; c < 3; c++) assert.ok(Math.abs(trap.mean[c] - d6[c]) < 0.25 * d6[c], `flare ${trap.mean} ≈ D6 ${d6}`);
  const a1t = await rgbOf(page, 'A1'), d6t = await rgbOf(page, 'D6');
  for (let c = 0; c < 3; c++) {
    assert.ok(Math.abs(a1t[c] - (a1[c] - trap.mean[c])) < 1e-3, `A1 channel ${c}: ${a1[c]} − flare ${trap.mean[c]} = ${a1t[c]}`);
    assert.ok(Math.abs(d6t[c]) < 0.25 * d6[c], `D6 channel ${c} (the trap itself) is near 0 after the flare: ${d6t[c]} (was ${d6[c]})`);
  }
  assert.match(await page.textContent(`${box} .light-trap-state`), new RegExp(`R ${trap.mean[0].toFixed(1)}, G ${trap.mean[1].toFixed(1)}, B ${trap.mean[2].toFixed(1)} DN`));
  assert.equal(await page.locator('#step-images .overlay rect.light-trap').count(), 1);
  await screenshot(page, 'light-trap-1-d6');

  // 2. The fit's recipe carries the trap and its flare.
  await step(page, 'fit');
  await page.click('#step-fit button.primary');
  await page.waitForFunction(() => (window.tristim.session.results ?? []).some((r) => /"light_trap"/.test(r.fit?.profile ?? '')), null, { timeout: 120000 });
  const profile = JSON.parse(await page.evaluate(() => window.tristim.session.results.find((r) => /"light_trap"/.test(r.fit.profile)).fit.profile));
  assert.deepEqual(profile.recipe.capture.light_trap, trap.corners);
  for (let c = 0; c < 3; c++) assert.ok(Math.abs(profile.recipe.capture.flare[c] - trap.mean[c]) < 1e-9);
  // The page's recipe run by the CLI on the same RAW (issue 8): `tristim fit --recipe r.json
  // --raw passport.dng` measures the trap again and gives the page's coefficients (1e-9 relative).
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-trap-'));
  fs.writeFileSync(path.join(dir, 'r.json'), JSON.stringify(profile.recipe)); fs.writeFileSync(path.join(repoRoot, 'test-artifacts/light-trap-recipe.json'), JSON.stringify(profile.recipe, null, 1));
  execFileSync(path.join(repoRoot, 'build/native/core/tristim'), ['fit', '--recipe', path.join(dir, 'r.json'),
    '--raw', path.join(repoRoot, 'examples/web/passport.dng'), '--out', path.join(dir, 'cli.json')], { stdio: ['ignore', 'ignore', 'pipe'] });
  const cli = JSON.parse(fs.readFileSync(path.join(dir, 'cli.json'), 'utf8'));
  const a = profile.model.coefficients.flat(), c2 = cli.model.coefficients.flat();
  assert.equal(c2.length, a.length);
  const scale = Math.max(...a.map(Math.abs));
  const worst = Math.max(...a.map((v, i) => Math.abs(v - c2[i]) / scale));
  assert.ok(worst < 1e-9, `CLI coefficients from the page's recipe differ by ${worst} (relative to the largest); ${profile.model.id} ${profile.objective}; page ${a.slice(0, 3)} CLI ${c2.slice(0, 3)}; page training ${profile.metrics?.training?.dE00?.mean} CLI ${cli.metrics?.training?.dE00?.mean}; recipe ${JSON.stringify(profile.recipe.sampling)}`);
  fs.rmSync(dir, { recursive: true, force: true });

  // 3. A trap outside the image: refused next to the trap's input; the chart is sampled without it.
  await step(page, 'images');
  await setTrap(page, { x: 5000 });
  const err = await errorNear(page, `${box} input[type=checkbox]`);
  assert.equal(err.code, 'CORNERS_OUTSIDE');
  await waitTrap(page, false).catch(() => {});
  await page.waitForFunction(() => !window.tristim.derived.sample.lightTrap && window.tristim.derived.sample.lightTrapError, null, { timeout: 30000 });
  assert.deepEqual(await rgbOf(page, 'A1'), a1);
  assert.match(await page.textContent(`${box} .light-trap-state`), /Not subtracted/);
  assert.ok(await noErrorNear(page, '#step-images .corner-editor'), 'the chart corners are not blamed');

  // 4. Marked with a drag on the image: the inputs take the rectangle, the flare is measured there.
  await page.click(`${box} button:has-text("Mark it on the image")`);
  await page.locator('#step-images .corner-editor').scrollIntoViewIfNeeded();
  const pts = await page.evaluate(([x0, y0, x1, y1]) => {
    const svg = document.querySelector('#step-images svg.overlay');
    const m = svg.getScreenCTM();
    const at = (x, y) => { const p = svg.createSVGPoint(); p.x = x; p.y = y; const q = p.matrixTransform(m); return [q.x, q.y]; };
    return [at(x0, y0), at(x1, y1)];
  }, [TRAP.x, TRAP.y, TRAP.x + TRAP.width, TRAP.y + TRAP.height]);
  await page.mouse.move(...pts[0]);
  await page.mouse.down();
  await page.mouse.move(...pts[1], { steps: 4 });
  await page.mouse.up();
  await waitTrap(page, true);
  const marked = await page.evaluate(() => window.tristim.derived.sample.lightTrapCorners);
  for (let i = 0; i < 8; i++) assert.ok(Math.abs(marked[i] - trap.corners[i]) < 3, `dragged trap ${marked} ≈ ${trap.corners}`);
  assert.ok(await noErrorNear(page, `${box} input[type=checkbox]`));

  // 5. Off again: the sampling is the one without a trap.
  await page.uncheck(`${box} input[type=checkbox]`);
  await waitTrap(page, false);
  assert.deepEqual(await rgbOf(page, 'A1'), a1);
});
