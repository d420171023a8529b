// The page's first script (classic, no imports, run while the document is parsed): starts the
// engine's worker, the compile of the wasm module and — a new session — the example's fetch and
// decode before main.js's module graph (the views, the plots) has loaded. main.js's Engine takes
// the worker and its pending requests over (protocol.js EngineClient, `self.tristimBoot`).
// Requests and replies are those of protocol.js: {type, id, ...}; ids 1, 2, … are used here first.
(() => {
  const worker = new Worker('worker.js', { type: 'module' });
  const module = WebAssembly.compileStreaming(fetch('tristim.wasm', { credentials: 'same-origin' }))
    .catch((e) => { console.warn(`the page could not compile the engine (${e.message}); each worker loads its own`); return null; });
  // The worker waits for this message before it creates the module (worker.js).
  module.then((m) => {
    try { worker.postMessage({ type: 'module', module: m }); } catch { worker.postMessage({ type: 'module', module: null }); }
  });
  const boot = { worker, module, pending: new Map(), nextId: 1, fatal: null, failed: null, client: null };
  // Until main.js takes the worker over, replies are handled here as protocol.js would.
  worker.onmessage = (ev) => {
    const msg = ev.data, p = boot.pending.get(msg.id);
    if (!p) return;
    if (msg.type === 'progress') { p.onProgress?.(msg); return; }
    boot.pending.delete(msg.id);
    if (msg.type === 'result') p.resolve(msg.result);
    else p.reject(Object.assign(new Error(msg.message), { code: msg.code }));
    if (msg.fatal) boot.fatal = msg.message;
  };
  worker.onerror = (ev) => {
    ev.preventDefault();
    for (const p of boot.pending.values()) p.reject(Object.assign(new Error(`worker failed: ${ev.message}`), { code: 'WORKER_FAILED' }));
    boot.pending.clear();
    boot.failed = `the worker failed: ${ev.message}`;
  };
  // Once main.js has taken the worker over (boot.client), requests go through it (one id sequence).
  const call = (type, args = {}, transfer = []) => {
    if (boot.client) return boot.client.call(type, args, { transfer });
    const id = boot.nextId++;
    return new Promise((resolve, reject) => {
      boot.pending.set(id, { resolve, reject });
      worker.postMessage({ type, id, ...args }, transfer);
    });
  };
  boot.hello = call('hello');
  boot.catalog = call('catalog');
  for (const p of [boot.hello, boot.catalog]) p.catch(() => {});   // reported by main.js

  // A new session (no settings in IndexedDB, store.js's database) loads the example: its bytes
  // are fetched and their decode queued behind the catalog. {cfg, bytes, decoding, t0} as
  // images/example.js's decodeExample, or null for a kept session.
  const settingsKept = new Promise((resolve) => {
    let req;
    try { req = indexedDB.open('tristim', 1); } catch { resolve(false); return; }
    req.onupgradeneeded = () => req.result.createObjectStore('session');
    req.onerror = () => resolve(false);
    req.onsuccess = () => {
      const db = req.result;
      try {
        const get = db.transaction('session', 'readonly').objectStore('session').count('settings');
        get.onsuccess = () => { resolve(get.result > 0); db.close(); };
        get.onerror = () => { resolve(false); db.close(); };
      } catch { resolve(false); db.close(); }
    };
  });
  // The worker fetches the RAW itself (the decode does not wait for this thread, busy loading the
  // views); the page fetches its own copy (kept in the session, re-sent if the worker restarts).
  boot.example = settingsKept.then(async (kept) => {
    if (kept) return null;
    const cfg = await (await fetch('examples/passport.json')).json();
    const url = `examples/${cfg.file}`;
    const t0 = performance.now();
    const decoding = call('decode', { slot: 'chart', url, previewSide: 0 });
    decoding.catch(() => {});   // reported by the images view, which awaits it
    const res = await fetch(url);
    if (!res.ok) throw Object.assign(new Error(`${url}: HTTP ${res.status}`), { code: 'EXAMPLE_MISSING' });
    return { cfg, bytes: await res.arrayBuffer(), decoding, t0, generation: 0 };
  });
  boot.example.catch(() => {});   // reported by the images view (restore)
  self.tristimBoot = boot;
})();
