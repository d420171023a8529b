// Page <-> worker protocol. Requests: {type, id, ...args}. Replies: {type:'result', id, result},
// {type:'error', id, code, message, fatal?}, {type:'progress', id, fraction, stage}. `fatal`: the
// wasm module aborted (out of memory, a trap); the worker is closing and must be replaced.
// The page talks to the worker only through `call`, which returns a promise.

export class EngineClient {
  constructor(url = new URL('./worker.js', import.meta.url)) {
    this.worker = new Worker(url, { type: 'module' });
    this.nextId = 1;
    this.pending = new Map();
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
