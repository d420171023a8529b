// Catch2 suite under node: node's fetch cannot read file paths, so hand the .wasm bytes over.
if (typeof __filename === 'string' && !Module['wasmBinary']) {
  Module['wasmBinary'] = require('fs').readFileSync(__filename.replace(/\.cjs$/, '.wasm'));
}
