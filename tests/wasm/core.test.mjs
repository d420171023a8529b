import test from 'node:test';
import assert from 'node:assert/strict';
import { loadTristim, throwsCode } from './load.mjs';

test('module loads under node and reports its version', async () => {
  const T = await loadTristim();
  assert.match(T.version(), /^\d+\.\d+\.\d+$/);
});

test('a core error reaches JS as an Error with a code', async () => {
  const T = await loadTristim();
  throwsCode(assert, () => T.builtinFile('no/such.csv'), 'UNKNOWN_ID');
});
