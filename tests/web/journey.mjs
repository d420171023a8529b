// Helpers shared by the journey tests: open the page fresh, wait for it, move between steps,
// upload files, read errors, count plot marks.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { openBrowser, repoRoot, artifacts } from './harness.mjs';
import { testFiles, readTestFile } from '../support/test_files.mjs';

/// The real images the journeys upload (tests/support/test_files.mjs): the example Passport DNG,
/// a Canon EOS 30D CR2 (another camera, 8.2 MP) and the Passport's sRGB preview JPEG.
export const DNG = testFiles.passportDng;
export const CR2 = testFiles.canon30dCr2;
export const JPEG = testFiles.passportJpeg;
export const fixture = (name) => path.join(repoRoot, 'tests/web/fixtures', name);

/// Opens the page and waits until it has restored (or built) its session.
export async function openPage() {
  const b = await openBrowser();
  try {
    await b.page.goto(b.origin + '/');
    await waitReady(b.page);
  } catch (e) {
    await b.close();   // a page that never gets ready must not keep the browser (and the test) alive
    throw new Error(`${e.message}\nrecorded: ${JSON.stringify(b.problems)}`);
  }
  return b;
}

/// A browser test on a fresh browser: opens it (`open`: openPage by default; openBrowser when the
/// test loads the page itself), runs body(b) with b = {page, origin, problems, context, close},
/// then fails on any console error, page error or off-origin request recorded (`problems: false`
/// when the test judges b.problems itself), and closes the browser whatever happened. Other
/// options go to node:test (timeout, ...).
export function pageTest(name, ...args) {
  const body = args.pop();
  const { problems = true, open = openPage, ...options } = args[0] ?? {};
  test(name, options, async () => {
    const b = await open();
    try {
      await body(b);
      if (problems) assert.deepEqual(b.problems, []);
    } finally {
      await b.close();
    }
  });
}

/// The native CLI the byte-for-byte tests compare the page with.
export const CLI = path.join(repoRoot, 'build/native/core/tristim');
/// A file in test-artifacts/ (created if missing), for downloads and the CLI's outputs.
export function artifact(name) {
  fs.mkdirSync(artifacts, { recursive: true });
  return path.join(artifacts, name);
}

/// Fits the matrix-3x3 with the first objective alone in the Fit step and waits for the run's
/// summary line ("1 of 1 fits … in N s."), with no error next to the button.
export async function fitMatrix3x3(page) {
  const FIT = '#step-fit button.primary';
  await step(page, 'fit');
  const models = page.locator('#step-fit input[data-model]');
  for (let i = 0; i < await models.count(); i++) await models.nth(i).setChecked(await models.nth(i).getAttribute('data-model') === 'matrix-3x3');
  const objs = page.locator('#step-fit input[data-objective]');
  for (let i = 0; i < await objs.count(); i++) await objs.nth(i).setChecked(i === 0);
  await page.evaluate(() => document.querySelector('#step-fit .fit-log').replaceChildren());  // the run's lines only
  await page.click(FIT);
  await page.waitForFunction(() => /fits in [\d.]+ s\.$/.test(document.querySelector('#step-fit .fit-log li:last-child')?.textContent ?? ''),
    null, { timeout: 120000 });
  assert.match(await page.textContent('#step-fit .fit-log li:last-child'), /^1 of 1 fits/);
  assert.ok(await noErrorNear(page, FIT), 'the fit succeeds');
}

export async function waitReady(page, timeout = 60000) {
  await page.waitForSelector('body[data-ready="true"]', { timeout });
}

export async function step(page, name) {
  await page.click(`#steps a[data-step="${name}"]`);
  await page.waitForSelector(`#step-${name}:not([hidden])`);
}

/// Sets a file input to an in-memory file {name, buffer}.
export async function upload(page, selector, name, buffer) {
  await page.setInputFiles(selector, { name, mimeType: 'application/octet-stream', buffer });
}
/// The bytes of a file (its first n if n is given). A missing test file throws an error naming it.
export const fileBuffer = (p, n) => (n ? readTestFile(p).subarray(0, n) : readTestFile(p));
/// A test file's path for page.setInputFiles, once it is known to exist (else as fileBuffer).
export const filePath = (p) => { readTestFile(p); return p; };

/// The coded error shown next to a control (its aria-describedby slot): {code, text} or null.
/// The coded error next to `selector` once its text names `name` (so an earlier error on the same
/// control is not taken for this one): {code, text}.
export function errorFor(page, selector, name, timeout = 60000) {
  return page.waitForFunction(([sel, n]) => {
    const el = document.querySelector(sel);
    const slot = el && document.getElementById(el.getAttribute('aria-describedby'));
    return slot && !slot.hidden && slot.dataset.code && slot.textContent.includes(n) ? { code: slot.dataset.code, text: slot.textContent } : null;
  }, [selector, name], { timeout }).then((h) => h.jsonValue());
}

export function errorNear(page, selector, timeout = 30000) {
  return page.waitForFunction((sel) => {
    const el = document.querySelector(sel);
    const slot = el && document.getElementById(el.getAttribute('aria-describedby'));
    return slot && !slot.hidden && slot.dataset.code ? { code: slot.dataset.code, text: slot.textContent } : null;
  }, selector, { timeout }).then((h) => h.jsonValue());
}
export function noErrorNear(page, selector) {
  return page.evaluate((sel) => {
    const el = document.querySelector(sel);
    const slot = el && document.getElementById(el.getAttribute('aria-describedby'));
    return !slot || slot.hidden;
  }, selector);
}

/// Drawn data marks (circles, paths, rects, ... of the plot's marks, not axes, grids, frames or
/// tips) inside a plot figure, by mark: {dot: 24, arrow: 24, ...}. Facets nest groups, so
/// shapes are counted as descendants of each top-level mark group.
export function markCounts(page, plotName) {
  return page.evaluate((n) => {
    const fig = document.querySelector(`figure[data-plot="${n}"]`);
    if (!fig) return null;
    const out = {};
    for (const g of fig.querySelectorAll('svg > g[aria-label]')) {
      const k = g.getAttribute('aria-label');
      if (/axis|grid|frame|tip/.test(k)) continue;
      out[k] = (out[k] ?? 0) + g.querySelectorAll('circle, path, line, rect, text, polygon').length;
    }
    return out;
  }, plotName);
}
export async function marks(page, plotName) {
  const c = await markCounts(page, plotName);
  return c ? Object.values(c).reduce((a, b) => a + b, 0) : -1;
}

/// Places the four corners (as a drag would) and waits until the table is sampled with them.
export async function setCorners(page, corners) {
  await page.evaluate((cs) => { const ed = window.tristim.views.images.editor; ed.setCorners(cs); ed.onChange(ed.corners, true); }, corners);
  await waitSampled(page, corners);
}

/// Waits until the corners are stored and the patch table shows a sampling made with them.
export function waitSampled(page, corners) {
  return page.waitForFunction((cs) => {
    const same = (a) => a && a.length === 8 && Array.from(a).every((v, i) => Math.abs(v - cs[i]) < 1e-9);
    return same(window.tristim.session.corners) && same(window.tristim.derived.sample?.corners);
  }, corners, { timeout: 30000 });
}
