// The Web Worker that hosts the wasm module. It creates the module once, lazily, and answers
// requests by type; handlers live in handlers.js. Heavy state (decoded images) stays here.
import createTristim from './tristim.mjs';
import { handlers } from './handlers.js';

let modulePromise = null;
const engine = () => (modulePromise ??= createTristim());
const state = {};  // per-worker state shared by handlers (e.g. the decoded image)

// Anything that escapes the request handlers is a bug: say so on the console (the browser tests
// fail on any console error). The page's onerror only rejects the pending calls.
self.addEventListener('unhandledrejection', (e) => console.error(`worker: unhandled rejection: ${e.reason?.stack ?? e.reason?.message ?? e.reason}`));
self.addEventListener('error', (e) => console.error(`worker: uncaught error: ${e.error?.stack ?? e.message}`));

self.onmessage = async (ev) => {
  const msg = ev.data;
  const handler = handlers[msg.type];
  try {
    if (!handler) throw Object.assign(new Error(`unknown request '${msg.type}'`), { code: 'INVALID_ARGUMENT' });
    const T = await engine();
    const progress = (fraction, stage) => self.postMessage({ type: 'progress', id: msg.id, fraction, stage });
    const out = await handler(T, msg, { state, progress });
    const { result, transfer = [] } = out ?? {};
    self.postMessage({ type: 'result', id: msg.id, result }, transfer);
  } catch (e) {
    self.postMessage({ type: 'error', id: msg.id, code: e?.code ?? 'INTERNAL', message: String(e?.message ?? e) });
  }
};
