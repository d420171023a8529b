// The catalog's rows cross by their field lists (tristim/methods.hpp, characterisation/models.hpp):
// listModels, listModelFamilies, listLayoutOptions, listSampleFlags and listLinearisations give the
// objects `tristim models --json` and `tristim linearise --list` print (names, order, values); a
// method row handed back (completeChoice) is read by the same strict list.
import test from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { loadTristim, repoRoot } from './load.mjs';

const CLI = path.join(repoRoot, 'build/native/core/tristim');
const cli = (...args) => JSON.parse(execFileSync(CLI, args, { encoding: 'utf8' }));
const OPTION = ['name', 'type', 'label', 'default_number', 'default_text', 'min', 'max', 'choices', 'description', 'step', 'unit',
  'min_exclusive'];

test('catalog rows: the module lists what tristim models --json and linearise --list print', async () => {
  const T = await loadTristim();
  const models = cli('models', '--json');
  assert.deepEqual(T.listModels(), models.models);
  assert.deepEqual(T.listModelFamilies(), models.families);
  assert.deepEqual(T.listLayoutOptions(), models.layout_options);
  assert.deepEqual(T.listSampleFlags(), models.sample_flags);
  assert.ok(models.models.some((m) => m.terms.length === m.n_terms && m.term_names.length === m.n_terms));
  for (const o of [...models.layout_options, ...models.sample_flags]) assert.deepEqual(Object.keys(o), OPTION);
  const listing = T.listLinearisations();
  assert.deepEqual(listing, cli('linearise', '--list'));
  assert.ok(listing.some((l) => l.options.length > 0));
  for (const l of listing) {
    assert.deepEqual(Object.keys(l), ['id', 'label', 'reference', 'needs', 'needs_text', 'options']);
    for (const o of l.options) assert.deepEqual(Object.keys(o), OPTION);
  }
});

test('catalog rows: a method row handed back is read strictly (unknown member refused with its code)', async () => {
  const T = await loadTristim();
  const gamma = T.listLinearisations().find((l) => l.id === 'gamma');
  const info = { id: gamma.id, label: gamma.label, reference: gamma.reference, options: gamma.options };
  assert.equal(T.completeChoice(info, { method: 'gamma' }).parameters.gamma, gamma.options[0].default_number);
  const bad = { ...info, options: [{ ...gamma.options[0], maximum: 3 }] };
  assert.throws(() => T.completeChoice(bad, { method: 'gamma' }),
    (e) => e.code === 'INVALID_ARGUMENT' && /options\[0\]\.maximum/.test(e.message));
  // A bound that is not a number crosses as null and reads back as NaN (unbounded), not refused.
  const open = { ...info, options: [{ ...gamma.options[0], min: null, max: null }] };
  assert.equal(T.completeChoice(open, { method: 'gamma', parameters: { gamma: 7 } }).parameters.gamma, 7);
});
