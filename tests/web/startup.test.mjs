import test from 'node:test';
import assert from 'node:assert/strict';
import { openBrowser, screenshot } from './harness.mjs';

test('the page starts the engine in a worker, with no console error and no off-origin request', async () => {
  const b = await openBrowser();
  try {
    await b.page.goto(b.origin + '/');
    await b.page.waitForSelector('#engine-status[data-ready="true"]', { timeout: 30000 });
    assert.match(await b.page.textContent('#engine-status'), /tristim \d+\.\d+\.\d+ ready/);
    const csp = await b.page.evaluate(() => document.querySelector('meta[http-equiv="Content-Security-Policy"]')?.content);
    assert.match(csp, /default-src 'self'/);
    await screenshot(b.page, 'startup');
    assert.deepEqual(b.problems, []);
  } finally {
    await b.close();
  }
});
