// Shared by the node --test suites: the shape of a per-patch result from the wasm module.
import assert from 'node:assert/strict';

/// Asserts that `result.ids` holds `count` patches, the first `first` and the last `last`, and
/// that each of `keys` is a Float64Array of 3 values per patch.
export function assertPatchArrays(result, { count, first, last }, keys) {
  assert.equal(result.ids.length, count);
  assert.equal(result.ids[0], first);
  assert.equal(result.ids[count - 1], last);
  for (const k of keys) {
    assert.ok(result[k] instanceof Float64Array, k);
    assert.equal(result[k].length, 3 * count, k);
  }
}
