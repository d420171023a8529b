// Only under node: Emscripten's EXPORT_ES6 loader expects CommonJS `require` and `__dirname`.
// In the browser and in workers these stay undefined and are never read.
var require, __dirname;
if (typeof process === 'object' && process.versions && process.versions.node &&
    typeof process.getBuiltinModule === 'function') {
  require = process.getBuiltinModule('module').createRequire(import.meta.url);
  __dirname = require('path').dirname(require('url').fileURLToPath(import.meta.url));
}
