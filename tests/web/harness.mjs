// Browser-test harness: serves build/wasm/site on 127.0.0.1 and drives Debian's Chromium through
// playwright-core. Records console errors, page errors and every request to another origin, so a
// test can fail on any of them. Screenshots go to test-artifacts/.
import { chromium } from 'playwright-core';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { serve } from '../../scripts/serve.mjs';

export const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
export const siteDir = process.env.TRISTIM_SITE_DIR || path.join(repoRoot, 'build/wasm/site');
export const artifacts = path.join(repoRoot, 'test-artifacts');

export async function openBrowser() {
  const server = await serve(siteDir, 0);
  const origin = `http://127.0.0.1:${server.address().port}`;
  const userDir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-chromium-'));
  const context = await chromium.launchPersistentContext(userDir, {
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    viewport: { width: 1400, height: 1000 },
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync',
      // Extra flags for experiments, e.g. CHROMIUM_FLAGS='--js-flags=--no-liftoff' (optimised wasm only).
      ...(process.env.CHROMIUM_FLAGS ? process.env.CHROMIUM_FLAGS.split(' ') : [])],
  });
  const problems = [];   // console errors, page errors, off-origin requests
  const watch = (page) => {
    page.on('console', (m) => { if (m.type() === 'error') problems.push(`console error: ${m.text()}`); });
    page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
    page.on('request', (r) => {
      const u = r.url();
      if (!u.startsWith(origin) && !u.startsWith('data:') && !u.startsWith('blob:')) problems.push(`off-origin request: ${u}`);
    });
  };
  context.on('page', watch);
  const page = context.pages()[0] ?? await context.newPage();
  watch(page);
  // Unhandled promise rejections inside the page show up as page errors too; record them explicitly.
  await page.addInitScript(() => {
    self.addEventListener('unhandledrejection', (e) => console.error('unhandled rejection: ' + (e.reason?.message ?? e.reason)));
  });
  const close = async () => {
    await context.close();
    server.close();
    fs.rmSync(userDir, { recursive: true, force: true });
  };
  return { context, page, origin, problems, close };
}

export async function screenshot(page, name) {
  fs.mkdirSync(artifacts, { recursive: true });
  const file = path.join(artifacts, `${name}.png`);
  await page.evaluate(() => window.scrollTo(0, 0));   // the sticky header stays at the top
  await page.mouse.move(0, 0);
  await page.screenshot({ path: file, fullPage: true });
  return file;
}
