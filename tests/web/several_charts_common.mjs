// Helpers of the several-charts browser tests (issue 48): the CLI fit of a profile's recipe, the
// Results swatches without a colour, and a Share link opened in a fresh browser.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { execFileSync } from 'node:child_process';
import { openBrowser } from './harness.mjs';
import { waitReady, step, CLI, artifact } from './journey.mjs';

const VERDICT = '#share-verdict-title[data-verdict]';

/// The profile JSON `tristim fit --recipe <recipe> <args>` writes (recipe and output in test-artifacts/<name>*).
export function cliFit(recipe, args, name) {
  const r = artifact(`${name}-recipe.json`), out = artifact(`${name}-cli.json`);
  fs.writeFileSync(r, JSON.stringify(recipe));
  execFileSync(CLI, ['fit', '--recipe', r, ...args, '--out', out], { stdio: 'pipe' });
  return JSON.parse(fs.readFileSync(out, 'utf8'));
}

/// Asserts that the CLI on the page's profile's recipe (with `args`: the --raw files, …) gives its
/// coefficients to the bit and each chart's figures (`charts`: the page's, the objects of the profile's "charts").
export function assertCliEqual(profile, charts, args, name) {
  const cli = cliFit(profile.recipe, args, name);
  assert.deepEqual(profile.model.coefficients, cli.model.coefficients, 'the page fits what the CLI fits, to the bit');
  assert.deepEqual(charts, cli.charts, 'the figures per chart the CLI writes, member for member');
}

/// The ids of the selected result's Results swatches drawn grey (no reference colour), on the Results step.
export async function greySwatches(page) {
  await step(page, 'results');
  return page.evaluate(async () => {
    const { perPatch } = await import('/lib/perpatch.js');
    const t = window.tristim, r = t.session.results.find((x) => x.key === t.session.selected);
    return perPatch(r, t.derived.reference).rows.filter((row) => row.fill === '#999').map((row) => row.id);
  });
}

/// Opens `link` in a fresh browser, waits for its verdict ("reproduced" asserted), runs
/// check(page), then fails on any problem the browser recorded.
export async function openShared(link, check) {
  const b = await openBrowser();
  try {
    await b.page.goto(link.replace(/^http:\/\/127\.0\.0\.1:\d+/, b.origin));
    await waitReady(b.page, 120000);
    await b.page.waitForSelector(VERDICT, { timeout: 120000 });
    assert.equal(await b.page.getAttribute(VERDICT, 'data-verdict'), 'reproduced');
    await check(b.page);
    assert.deepEqual(b.problems, []);
  } finally { await b.close(); }
}
