// Only under node: node's fetch cannot read file URLs, so hand the .wasm bytes over directly.
// (No import.meta here: the optimiser crashes on it inside --pre-js.)
if (typeof process === 'object' && process.versions && process.versions.node && !Module['wasmBinary'] &&
    typeof require === 'function' && typeof __dirname === 'string') {
  Module['wasmBinary'] = require('fs').readFileSync(require('path').join(__dirname, 'tristim.wasm'));
}
