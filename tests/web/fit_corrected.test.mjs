// Step 3 offers Abed 2013's corrected 3×3 (eqs 6-13, App. C eqs 26-28) on the user's own chart: the
// brightest patch is its white reference, and the fit log and the results summary show the white
// scaling μ (eq 27) — the module's number for the same recipe.
import test from 'node:test';
import assert from 'node:assert/strict';
import { screenshot } from './harness.mjs';
import { openPage, step, noErrorNear } from './journey.mjs';

test('the fit step fits corrected-3x3 and shows mu in the log and the results', async () => {
  const b = await openPage();
  try {
    const { page } = b;
    await step(page, 'fit');
    // Only corrected-3x3 × ls.
    await page.$$eval('#step-fit input[data-model], #step-fit input[data-objective]', (els) => {
      for (const e of els) {
        const want = e.dataset.model ? e.dataset.model === 'corrected-3x3' : e.dataset.objective === 'ls';
        if (e.checked !== want) e.click();
      }
    });
    await page.click('#step-fit button.primary');
    const line = await page.waitForFunction(() => {
      const li = [...document.querySelectorAll('#step-fit .fit-log li')].map((e) => e.textContent).find((t) => /μ =/.test(t));
      return li ?? null;
    }, null, { timeout: 120000 }).then((h) => h.jsonValue());
    const mu = Number(/μ = ([\d.]+)/.exec(line)[1]);
    assert.ok(mu > 0.8 && mu < 1.25, line);
    await step(page, 'results');
    const summary = await page.waitForFunction(() => {
      const t = [...document.querySelectorAll('#step-results p.summary')].map((e) => e.textContent).find((x) => /white scaling μ/.test(x));
      return t ?? null;
    }, null, { timeout: 60000 }).then((h) => h.jsonValue());
    assert.match(summary, new RegExp(`μ = ${mu.toFixed(4)}`));
    assert.ok(await noErrorNear(page, '#step-fit button.primary'));
    await screenshot(page, 'fit-corrected-3x3');
  } finally {
    await b.close();
  }
});
