// A chart cut by the frame (issue 48), from the page to the CLI: the example Passport DNG with its
// sensor rows below 880 cut off (row D outside the image, as in cut_chart.test.mjs). The page's fit
// of the 18 patches inside equals `tristim fit --recipe r.json --raw cut.dng` on the recipe the
// page's profile embeds, to the bit, both naming the 6 patches outside (the fit's left-out list, the
// profile's recipe: sampling.missing); the page's share link
// reproduces with `tristim reproduce`. The corner editor shows the handles below the image in a
// padded view: every handle inside the editor, the editor above what follows it.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { spawnSync } from 'node:child_process';
import { screenshot } from './harness.mjs';
import { pageTest, step, setCorners, fitMatrix3x3, CLI, artifact } from './journey.mjs';
import { EXAMPLE } from './image_fixtures.mjs';
import { CUT, openCutChart } from './cut_chart_fixture.mjs';
import { loadTristim } from '../wasm/load.mjs';

/// The screen boxes of the corner editor, its handles' rings and the elements that follow it.
const editorBoxes = (page) => page.evaluate(() => {
  const ed = document.querySelector('#step-images .corner-editor');
  const box = (el) => { const r = el.getBoundingClientRect(); return { left: r.left, top: r.top, right: r.right, bottom: r.bottom }; };
  const after = [];
  for (let n = ed.nextElementSibling; n; n = n.nextElementSibling) if (n.getClientRects().length) after.push({ tag: n.className || n.tagName, ...box(n) });
  return { editor: box(ed), canvas: box(ed.querySelector('canvas')), padded: ed.classList.contains('padded'),
    handles: [...ed.querySelectorAll('.handle circle.ring')].map(box), after };
});

pageTest('a chart cut by the frame: the page\'s fit equals fit --recipe --raw on its recipe, its link reproduces, the handles stay in view', { timeout: 240000 }, async ({ page }) => {
  await openCutChart(page);
  assert.ok(EXAMPLE.corners[5] > 427 && EXAMPLE.corners[7] > 427, 'corners 3 and 4 lie below the image');

  // The corner editor: a padded view holds every handle; the image keeps its place inside it.
  const b = await editorBoxes(page);
  assert.ok(b.padded, 'the view is padded');
  assert.ok(b.canvas.bottom < b.editor.bottom - 5, `the image (bottom ${b.canvas.bottom}) ends above the editor's bottom ${b.editor.bottom}`);
  b.handles.forEach((h, i) => assert.ok(h.left >= b.editor.left - 0.5 && h.right <= b.editor.right + 0.5 && h.top >= b.editor.top - 0.5 && h.bottom <= b.editor.bottom + 0.5,
    `handle ${i + 1} ${JSON.stringify(h)} inside the editor ${JSON.stringify(b.editor)}`));
  for (const a of b.after) assert.ok(a.top >= b.editor.bottom - 0.5, `${a.tag} (top ${a.top}) starts below the editor (bottom ${b.editor.bottom})`);
  // A handle outside the image is still draggable: corner 3 dragged 10 image px to the right.
  const before = await page.evaluate(() => Array.from(window.tristim.views.images.editor.corners));
  const handle = page.locator('#step-images .corner-editor .handle[data-corner="2"] circle.ring');
  await handle.scrollIntoViewIfNeeded();
  const ring = await handle.boundingBox();
  const perPx = (b.canvas.right - b.canvas.left) / (await page.evaluate(() => window.tristim.derived.image.width));
  await page.mouse.move(ring.x + ring.width / 2, ring.y + ring.height / 2);
  await page.mouse.down();
  await page.mouse.move(ring.x + ring.width / 2 + 10 * perPx, ring.y + ring.height / 2, { steps: 4 });
  await page.mouse.up();
  const moved = await page.evaluate(() => Array.from(window.tristim.views.images.editor.corners));
  assert.ok(Math.abs(moved[4] - before[4] - 10) < 1.5 && Math.abs(moved[5] - before[5]) < 1.5, `corner 3 moved from ${before.slice(4, 6)} to ${moved.slice(4, 6)}`);
  await screenshot(page, 'cut-chart-recipe-1-handles');
  await setCorners(page, EXAMPLE.corners);

  // The page's fit of the 18 patches inside, and the CLI on the recipe its profile embeds.
  await fitMatrix3x3(page);
  const page_ = await page.evaluate(() => {
    const t = window.tristim, r = t.session.results.find((x) => x.key === t.session.selected);
    return { profile: r.fit.profile, ids: Array.from(r.ids), excluded: Array.from(r.fit.excluded), note: document.querySelector('#step-fit .summary').textContent };
  });
  const profile = JSON.parse(page_.profile);
  assert.equal(page_.ids.length, 18);
  // The 6 patches outside the frame: in the fit's left-out list, the step's note, and the profile's
  // recipe (sampling.missing), so the profile and its link say what the fit was made without.
  const rowD = ['D1', 'D2', 'D3', 'D4', 'D5', 'D6'];
  for (const id of rowD) assert.ok(page_.excluded.includes(`${id} (outside the frame)`), `${id} outside the frame in ${page_.excluded}`);
  assert.match(page_.note, /outside the frame \(not sampled\): D1, D2, D3, D4, D5, D6\./);
  assert.deepEqual(profile.recipe.sampling.missing, rowD);
  // The fit step's sample-flag toggles are the engine's table (sample_flag_table: name, label,
  // default), and the recipe's sampling.exclude_flags lists the checked ones: the engine applies them.
  const flags = (await loadTristim()).listSampleFlags();
  const toggles = await page.$$eval('#step-fit input[data-flag]', (l) => l.map((i) => ({ name: i.dataset.flag, checked: i.checked, label: i.labels[0]?.textContent })));
  assert.deepEqual(toggles, flags.map((f) => ({ name: f.name, checked: f.default_number === 1, label: f.label })));
  assert.deepEqual(profile.recipe.sampling.exclude_flags, flags.filter((f) => f.default_number === 1).map((f) => f.name));
  await step(page, 'fit');
  await page.locator('#step-fit .summary').scrollIntoViewIfNeeded();
  await screenshot(page, 'cut-chart-recipe-2-fit');
  assert.ok(!page_.ids.some((id) => id.startsWith('D')), `no row-D patch in the fit: ${page_.ids}`);
  assert.deepEqual(profile.recipe.sampling.corners, EXAMPLE.corners);
  const recipe = artifact('cut-chart-recipe.json'), raw = artifact('cut-chart.dng'), out = artifact('cut-chart-recipe-cli.json');
  fs.writeFileSync(recipe, JSON.stringify(profile.recipe, null, 1));
  fs.writeFileSync(raw, Buffer.from(CUT));
  const fit = spawnSync(CLI, ['fit', '--recipe', recipe, '--raw', raw, '--out', out], { encoding: 'utf8' });
  assert.equal(fit.status, 0, fit.stderr);
  for (const id of ['D1', 'D6']) assert.match(fit.stderr, new RegExp(`left out ${id} \\(outside the frame\\)`));
  const cli = JSON.parse(fs.readFileSync(out, 'utf8'));
  assert.deepEqual(cli.model.coefficients, profile.model.coefficients, 'the CLI\'s coefficients are the page\'s, to the bit');
  assert.deepEqual(cli.metrics, profile.metrics);
  assert.deepEqual(cli.training, profile.training);
  assert.deepEqual(cli.recipe.sampling.missing, rowD, 'the CLI\'s profile names the same missing patches');

  // The page's share link reproduces with the CLI.
  await step(page, 'share');
  await page.click('#share-make');
  await page.waitForFunction(() => document.getElementById('share-link').value.includes('#tristim='), null, { timeout: 60000 });
  const link = await page.inputValue('#share-link');
  const rep = spawnSync(CLI, ['reproduce', link], { encoding: 'utf8' });
  assert.equal(rep.status, 0, rep.stderr + rep.stdout);
  assert.match(rep.stdout, /^reproduced/);
  const again = artifact('cut-chart-recipe-link.json');   // the link's profile, recomputed: it names them too
  assert.equal(spawnSync(CLI, ['reproduce', link, '--out', again], { encoding: 'utf8' }).status, 0);
  assert.deepEqual(JSON.parse(fs.readFileSync(again, 'utf8')).recipe.sampling.missing, rowD);
});
