// Several chart images in one fit (issue 48, docs/multi-image.md) through the module: each image
// sampled, paired with its entry's reference (trainingSet on imageRecipe), the union
// (trainingUnion) fitted (fitTraining) — the page's path — gives the coefficients of
// `tristim fit --recipe r.json --raw a --raw b` on the same recipe to the bit, and the same
// per-chart figures ("charts").
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { loadTristim, readBytes, testFiles, repoRoot } from './load.mjs';

const CLI = path.join(repoRoot, 'build/native/core/tristim');
const EXAMPLE = JSON.parse(fs.readFileSync(path.join(repoRoot, 'examples/web/passport.json'), 'utf8'));

/// The module's fit of a recipe with images, each entry sampled on `raws[k]` at its corners.
function moduleFit(T, recipe, raws) {
  const parts = recipe.images.map((e, k) => {
    const own = T.imageRecipe(recipe, e);
    const { layout, homography, patches } = T.sampleChart(raws[k], e.sampling.layout, e.sampling.corners, { area: e.sampling.area });
    return { name: e.name, training: T.trainingSet(own, { layout, homography, patches }, T.recipeReference(own)) };
  });
  return T.fitTraining(recipe, T.trainingUnion(recipe, parts));
}

for (const duplicates of ['each', 'once']) {
  test(`two chart images (duplicates ${duplicates}): the module's union fit equals tristim fit --recipe to the bit`, () => loadTristim().then((T) => {
    const bytes = readBytes(testFiles.passportDng);
    const c1 = EXAMPLE.corners, c2 = c1.map((v, i) => v + (i % 2 ? 1 : -1.5));   // a second placement of the chart
    const reference = { chart: 'passport', illuminant: 'D50', observer: '1931' };
    const entry = (name, corners) => ({ name, sha256: T.sha256(bytes), reference, sampling: { layout: { chart: 'passport' }, corners, area: 0.5 } });
    const recipe = T.completeRecipe({ reference, sampling: entry('', c1).sampling, characterisation: { model: 'Finlayson2015-2', objective: { method: 'ls' } },
      images: [entry('a.dng', c1), entry('b.dng', c2)], duplicates });
    const raw = T.decodeRaw(bytes);
    let out;
    try { out = moduleFit(T, recipe, [raw, raw]); } finally { raw.delete(); }
    assert.equal(out.ids.length, duplicates === 'each' ? 48 : 24);
    assert.deepEqual(out.charts.map((c) => [c.chart, c.patches]), [['a.dng', 24], ['b.dng', 24]]);
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tristim-recipe-images-'));
    try {
      fs.writeFileSync(path.join(dir, 'r.json'), T.recipeToJson(out.recipe));
      execFileSync(CLI, ['fit', '--recipe', path.join(dir, 'r.json'), '--raw', testFiles.passportDng, '--raw', testFiles.passportDng,
        '--out', path.join(dir, 'p.json')], { stdio: 'pipe' });
      const cli = JSON.parse(fs.readFileSync(path.join(dir, 'p.json'), 'utf8'));
      const mine = JSON.parse(out.profile);
      assert.deepEqual(mine.model.coefficients, cli.model.coefficients);
      assert.deepEqual(mine.recipe.images.map((e) => [e.name, e.sha256]), cli.recipe.images.map((e) => [e.name, e.sha256]));
      assert.deepEqual(out.charts, cli.charts, 'the figures per chart are the profile\'s "charts", member for member');
    } finally {
      fs.rmSync(dir, { recursive: true, force: true });
    }
  }));
}
