// A worker that dies — its wasm module aborts (what out-of-memory or a trap does), or an error
// escapes the worker — is replaced by the page: the status line says what happened, the session
// (chart image, corners, results) is kept, and the next sampling and fit work in the new worker.
// The crash is provoked with the worker's test-only 'testCrash' message.
import assert from 'node:assert/strict';
import { screenshot } from './harness.mjs';
import { step, setCorners, pageTest, fitMatrix3x3 } from './journey.mjs';

for (const how of ['abort', 'uncaught']) {
  pageTest(`a worker that dies (${how}) is restarted, the page says so and keeps the session`, { problems: false }, async (b) => {
    const { page } = b;
    await step(page, 'images');
    await page.waitForFunction(() => document.querySelectorAll('#step-images .patch-table tbody tr').length === 24, null, { timeout: 60000 });
    const corners = await page.evaluate(() => Array.from(window.tristim.session.corners));
    const results = await page.evaluate(() => window.tristim.session.results?.length ?? 0);
    const generation = await page.evaluate(() => window.tristim.engine.generation);

    const code = await page.evaluate((h) => window.tristim.engine.call('testCrash', { how: h }).then(() => 'OK', (e) => e.code), how);
    if (how === 'abort') assert.equal(code, 'ENGINE_CRASHED');
    await page.waitForFunction(() => document.getElementById('engine-status').dataset.crashes === '1', null, { timeout: 30000 });
    assert.match(await page.textContent('#engine-status'), /stopped .* restarted; your files, corners and results are kept/);
    assert.equal(await page.evaluate(() => window.tristim.engine.generation), generation + 1);
    assert.deepEqual(await page.evaluate(() => Array.from(window.tristim.session.corners)), corners);
    assert.equal(await page.evaluate(() => window.tristim.session.results?.length ?? 0), results);
    await screenshot(page, `worker-restart-${how}`);

    // The new worker decodes the kept chart again for a new sampling, and fits.
    const moved = corners.map((v, i) => v + (i % 2 ? 1 : -1));
    await setCorners(page, moved);
    assert.equal(await page.locator('#step-images .patch-table tbody tr').count(), 24);
    await fitMatrix3x3(page);
    // The only console errors are the worker's report of the provoked crash.
    assert.deepEqual(b.problems.filter((p) => !/test: (uncaught error in the worker|the module was made to abort)/.test(p)), []);
  });
}

pageTest('a compare worker that dies is replaced, the page says so, and the next compare runs', { problems: false }, async (b) => {
  const { page } = b;
  const size = await page.evaluate(() => window.tristim.views.fit.pool.size);
  const code = await page.evaluate(() => window.tristim.views.fit.pool.clients[0].call('testCrash', { how: 'abort' }).then(() => 'OK', (e) => e.code));
  assert.equal(code, 'ENGINE_CRASHED');
  await page.waitForFunction(() => document.getElementById('engine-status').dataset.crashes === '1', null, { timeout: 30000 });
  assert.match(await page.textContent('#engine-status'), /stopped .* restarted/);
  assert.equal(await page.evaluate(() => window.tristim.views.fit.pool.clients.length), size, 'the dead worker was replaced');
  await fitMatrix3x3(page);
  assert.deepEqual(b.problems.filter((p) => !/test: the module was made to abort/.test(p)), []);
});
