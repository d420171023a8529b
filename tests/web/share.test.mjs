// Share links in the page (issue 44): Share makes a link to the selected profile (the CLI checks it
// out too); a fresh browser opening it recomputes the profile in the worker and shows "reproduced"
// with the same numbers; the source RAW dropped on it is checked by SHA-256 and sampled again; a
// link whose data give other numbers shows both results side by side; a tampered, truncated, bomb
// or future-version link shows its coded error where it was opened, and the session (results,
// selection, storage) is untouched.
import test from 'node:test';
import assert from 'node:assert/strict';
import zlib from 'node:zlib';
import crypto from 'node:crypto';
import path from 'node:path';
import { spawnSync } from 'node:child_process';
import { openBrowser, screenshot, repoRoot } from './harness.mjs';
import { openPage, step, waitReady, errorFor, upload, fileBuffer, DNG } from './journey.mjs';
import { loadTristim } from '../wasm/load.mjs';

const VERDICT = '#share-verdict-title[data-verdict]';
/// The session's state a link must not change: the selected result, the results, what is stored.
const sessionState = (page) => page.evaluate(async () => ({
  selected: window.tristim.session.selected,
  results: (window.tristim.session.results ?? []).map((r) => r.key),
  stored: Object.keys(await window.tristim.store.all()).sort(),
  corners: Array.from(window.tristim.session.corners ?? []),
}));
const dictionary = Buffer.from((await loadTristim()).shareLinkDictionary(), 'latin1');

/// Version 2 content (docs/link-format.md: JSON NUL heads, mantissa bytes 0–3, patch values' bytes
/// 0–1, SHA-256s, mantissa bytes 4–7, values' bytes 2–7) with the top mantissa bit of the last
/// patch value flipped: that camera B is 1.5× or 2/3 of what it was.
function changeLastPatchValue(content) {
  const nul = content.indexOf(0);
  const json = JSON.parse(content.subarray(0, nul).toString());
  const n = json.results.length - 1;
  let at = nul + 1;
  for (let i = 0; i < n; i++) while (content[at++] & 0x80);   // the heads (LEB128)
  const v = (content.length - at - 8 * n - 32 * json.sources.length) / 8;
  assert.ok(Number.isInteger(v) && v > 0, `${v} patch values`);
  const out = Buffer.from(content);
  out[at + 4 * n + v + (v - 1)] ^= 0x08;                      // byte 1 of the last value
  return out;
}
const row = (page, name) => page.evaluate((n) => [...document.querySelectorAll(`#share-verdict tr[data-name="${n}"] td`)].map((td) => td.textContent), name);

test('a link made in the page reproduces in a fresh browser; damaged links give coded errors, the session untouched', async () => {
  const maker = await openPage();
  let link, made;
  try {
    const { page } = maker;
    await step(page, 'share');
    await page.click('#share-make');
    await page.waitForFunction(() => document.getElementById('share-link').value.includes('#tristim='), null, { timeout: 60000 });
    link = await page.inputValue('#share-link');
    assert.ok(link.startsWith(maker.origin + '/'), link.slice(0, 60));
    assert.ok(link.length < 1400, `${link.length} characters`);
    assert.match(link, /#tristim=2\./);
    made = await page.evaluate(() => {
      const s = window.tristim.session, r = s.results.find((x) => x.key === s.selected) ?? s.results[0];
      return { model: r.recipe.characterisation.model, dE00: r.fit.evaluation.training.dE00.mean };
    });
    // The CLI checks out the page's link.
    const cli = spawnSync(path.join(repoRoot, 'build/native/core/tristim'), ['reproduce', link], { encoding: 'utf8' });
    assert.equal(cli.status, 0, cli.stderr + cli.stdout);
    assert.match(cli.stdout, /^reproduced/);
    await screenshot(page, 'share-make');
    assert.deepEqual(maker.problems, []);
  } finally { await maker.close(); }

  // A fresh browser (its own storage) opens the link.
  const b = await openBrowser();
  try {
    const { page } = b;
    const theirs = link.replace(/^http:\/\/127\.0\.0\.1:\d+/, b.origin);
    await page.goto(theirs);
    await waitReady(page, 120000);
    await page.waitForSelector(VERDICT, { timeout: 120000 });
    assert.equal(await page.getAttribute(VERDICT, 'data-verdict'), 'reproduced');
    assert.equal((await row(page, 'model'))[0], made.model);
    const [linkDe, hereDe] = await row(page, 'training.dE00');
    assert.equal(linkDe, hereDe);
    assert.equal(Number(linkDe.split(' ')[0]), Number(made.dE00.toPrecision(6)), 'the maker\'s training mean ΔE00');
    await screenshot(page, 'share-open');

    // The source RAW dropped on the opened link: its SHA-256 matches, its patches are sampled again.
    await upload(page, '#share-image', 'passport.dng', fileBuffer(DNG));
    await page.waitForFunction(() => /sampled again/.test(document.getElementById('share-verdict-title')?.textContent ?? ''), null, { timeout: 60000 });
    assert.equal(await page.getAttribute(VERDICT, 'data-verdict'), 'reproduced');
    // Another file is not the link's source.
    await upload(page, '#share-image', 'other.dng', Buffer.concat([fileBuffer(DNG), Buffer.from([0])]));
    assert.equal((await errorFor(page, '#share-image', 'other.dng')).code, 'PATCH_MISMATCH');

    // Damaged links, pasted into the Open box: each its code; the session does not change.
    const before = await sessionState(page);
    const payload = theirs.split('#tristim=')[1];
    const mid = payload.indexOf('.') + 50;
    const cases = [
      ['tampered', theirs.slice(0, theirs.indexOf('#tristim=') + 9) + payload.slice(0, mid) + (payload[mid] === 'A' ? 'B' : 'A') + payload.slice(mid + 1), 'PARSE_ERROR'],
      ['truncated', theirs.slice(0, theirs.length - 25), 'PARSE_ERROR'],
      ['bomb', `1.${zlib.deflateRawSync(Buffer.alloc(32 << 20, '[')).toString('base64url')}.AAAAAAAAAAAAAAAA`, 'LIMIT_EXCEEDED'],
      ['future version', '3' + payload.slice(1), 'PROFILE_VERSION'],
    ];
    for (const [what, text, code] of cases) {
      await page.fill('#share-open-text', text);
      await page.click('#share-open');
      await page.waitForFunction((c) => document.getElementById('step-share').dataset.linkError === c, code, { timeout: 30000 })
        .catch(() => {});
      const shown = await page.evaluate(() => {
        const b = document.getElementById('share-open'), slot = document.getElementById(b.getAttribute('aria-describedby'));
        return { code: slot.dataset.code, hidden: slot.hidden };
      });
      assert.equal(shown.code, code, what);
      assert.equal(shown.hidden, false, what);
      assert.deepEqual(await sessionState(page), before, `${what}: the session is untouched`);
      assert.equal(await page.getAttribute(VERDICT, 'data-verdict'), 'reproduced', `${what}: the opened link stays shown`);
    }
    // A link whose data give other numbers (one camera RGB value changed, the check made again, as
    // another sampling would): "differs", both results side by side, the session untouched.
    const content = changeLastPatchValue(zlib.inflateRawSync(Buffer.from(payload.split('.')[1], 'base64url'), { dictionary }));
    const data = zlib.deflateRawSync(content, { level: 9, dictionary });   // version 2 checks the compressed bytes
    const check = crypto.createHash('sha256').update(data).digest().subarray(0, 12).toString('base64url');
    await page.fill('#share-open-text', `2.${data.toString('base64url')}.${check}`);
    await page.click('#share-open');
    await page.waitForSelector('#share-verdict-title[data-verdict="differs"]', { timeout: 60000 });
    const differing = await page.evaluate(() => [...document.querySelectorAll('#share-verdict tr.differs')].map((tr) => tr.dataset.name));
    assert.ok(differing.includes('coefficients'), differing.join(', '));
    const [inLink, here] = await row(page, 'coefficients');
    assert.notEqual(inLink, here);
    assert.deepEqual(await sessionState(page), before, 'differs: the session is untouched');
    await screenshot(page, 'share-differs');

    // A bad link in the address bar: the same, where it was opened.
    await page.goto(`${b.origin}/#tristim=3${payload.slice(1)}`);
    await waitReady(page, 120000);
    await page.waitForFunction(() => document.getElementById('step-share').dataset.linkError === 'PROFILE_VERSION', null, { timeout: 60000 });
    assert.deepEqual((await sessionState(page)).results, before.results);
    await screenshot(page, 'share-bad-link');
    assert.deepEqual(b.problems, []);
  } finally { await b.close(); }
});
