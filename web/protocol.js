// Page <-> worker protocol. Requests: {type, id, ...args}. Replies: {type:'result', id, result},
// {type:'error', id, code, message, fatal?}, {type:'progress', id, fraction, stage}. `fatal`: the
// wasm module aborted (out of memory, a trap); the worker is closing and must be replaced.
// The page talks to the worker only through `call`, which returns a promise.

// The wasm module is compiled once, in the page, and posted to every worker (the engine's and the
// compare's): each worker instantiates it instead of fetching and compiling its own copy, and the
// compiled code (with V8's tier-up and code cache) is shared. null when the page cannot compile it:
// the worker then loads the module itself.
// boot.js (the page's first script) has usually started that compile already.
let compiled = self.tristimBoot?.module ?? null;
export const sharedModule = () => (compiled ??= WebAssembly.compileStreaming(fetch(new URL('./tristim.wasm', import.meta.url), { credentials: 'same-origin' }))
  .catch((e) => { console.warn(`the page could not compile the engine (${e.message}); each worker loads its own`); return null; }));

export class EngineClient {
  /// boot: boot.js's early worker (self.tristimBoot), taken over with its pending requests; the
  /// module was already posted to it.
  constructor(url = new URL('./worker.js', import.meta.url), { boot = null } = {}) {
    if (boot) {
      this.worker = boot.worker;
      this.nextId = boot.nextId;
      this.pending = boot.pending;
      boot.client = this;   // boot.js's later requests (the example's decode) come here
    } else {
      this.worker = new Worker(url, { type: 'module' });
      // The worker waits for this message before it creates the module (worker.js).
      sharedModule().then((module) => {
        try { this.worker.postMessage({ type: 'module', module }); } catch { this.worker.postMessage({ type: 'module', module: null }); }
      });
      this.nextId = 1;
      this.pending = new Map();
    }
    this.worker.onmessage = (ev) => this.onMessage(ev.data);
    this.onfatal = null;   // (reason) => …: the worker or its module died (Engine restarts it)
    this.worker.onerror = (ev) => {
      ev.preventDefault();
      for (const p of this.pending.values()) p.reject(Object.assign(new Error(`worker failed: ${ev.message}`), { code: 'WORKER_FAILED' }));
      this.pending.clear();
      this.onfatal?.(`the worker failed: ${ev.message}`);
    };
  }

  /// Sends a request; resolves with the result, rejects with an Error carrying `.code`.
  call(type, args = {}, { transfer = [], onProgress } = {}) {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject, onProgress });
      this.worker.postMessage({ type, id, ...args }, transfer);
    });
  }

  onMessage(msg) {
    const p = this.pending.get(msg.id);
    if (!p) return;
    if (msg.type === 'progress') { p.onProgress?.(msg); return; }
    this.pending.delete(msg.id);
    if (msg.type === 'result') p.resolve(msg.result);
    else p.reject(Object.assign(new Error(msg.message), { code: msg.code }));
    if (msg.fatal) this.onfatal?.(msg.message);   // the module aborted: this worker is done
  }

  terminate() { this.worker.terminate(); }
}
