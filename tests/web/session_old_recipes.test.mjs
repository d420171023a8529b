// Results a browser kept from before the recipe crossed the engine's boundary as its JSON (their
// layouts with margin_left … instead of `margins`): after a reload each result's recipe is the one
// its profile embeds, and the engine takes it again (the Compare checks, the link, the bootstrap).
import assert from 'node:assert/strict';
import { pageTest, waitReady } from './journey.mjs';

pageTest('results saved with an old layout form are read back in the engine\'s form after a reload', async ({ page }) => {
  await page.waitForFunction(() => window.tristim.session.results?.length > 0, null, { timeout: 120000 });
  const planted = await page.evaluate(async () => {
    const app = window.tristim;
    const old = (L) => ({ chart: L.chart, rows: L.rows, columns: L.columns, margin_left: 0, margin_top: 0, margin_right: 0, margin_bottom: 0, gap: L.gap });
    const results = app.session.results.map((r) => {
      const recipe = { ...r.recipe, sampling: { ...r.recipe.sampling, layout: old(r.recipe.sampling.layout) } };
      return { ...r, recipe, fit: { ...r.fit, recipe } };
    });
    await app.store.set('results', results);
    // the engine refuses the old form
    try { await app.engine.call('ridgeRow', { recipe: results[0].recipe, ids: results[0].ids, rgb: results[0].rgb, xyz: results[0].xyz }); return 'taken'; } catch (e) { return e.code; }
  });
  assert.equal(planted, 'INVALID_ARGUMENT');
  await page.reload();
  await waitReady(page);
  const r = await page.evaluate(async () => {
    const app = window.tristim, r = app.session.results[0];
    const out = { layout: r.recipe.sampling.layout, same: r.recipe === r.fit.recipe, chart: JSON.parse(r.fit.profile).recipe.sampling.layout.chart };
    try { await app.engine.call('ridgeRow', { recipe: r.fit.recipe, ids: r.ids, rgb: r.rgb, xyz: r.xyz }); out.taken = true; } catch (e) { out.taken = `${e.code} ${e.message}`; }
    return out;
  });
  assert.deepEqual(r.layout.margins, [0, 0, 0, 0]);
  assert.equal(r.layout.chart, r.chart);
  assert.ok(!('margin_left' in r.layout));
  assert.equal(r.same, true);
  assert.equal(r.taken, true);
});
