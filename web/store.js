// The session kept in IndexedDB, so a reload or an accidental tab close loses nothing.
// One object store, 'session', keyed by name: 'settings', 'files.chart', 'files.dark', 'files.flat',
// 'corners', 'results', ... Values are structured-cloned (ArrayBuffers and typed arrays included).
const DB_NAME = 'tristim';
const STORE = 'session';

let dbPromise = null;
function db() {
  dbPromise ??= new Promise((resolve, reject) => {
    const req = indexedDB.open(DB_NAME, 1);
    req.onupgradeneeded = () => req.result.createObjectStore(STORE);
    req.onsuccess = () => resolve(req.result);
    req.onerror = () => reject(req.error);
  });
  return dbPromise;
}

function run(mode, fn) {
  return db().then((d) => new Promise((resolve, reject) => {
    const tx = d.transaction(STORE, mode);
    const req = fn(tx.objectStore(STORE));
    tx.oncomplete = () => resolve(req?.result);
    tx.onerror = () => reject(tx.error);
    tx.onabort = () => reject(tx.error);
  }));
}

export const store = {
  get: (key) => run('readonly', (s) => s.get(key)),
  set: (key, value) => run('readwrite', (s) => s.put(value, key)),
  delete: (key) => run('readwrite', (s) => s.delete(key)),
  clear: () => run('readwrite', (s) => s.clear()),
  /// All entries as an object {key: value}.
  async all() {
    const keys = await run('readonly', (s) => s.getAllKeys());
    const values = await run('readonly', (s) => s.getAll());
    return Object.fromEntries(keys.map((k, i) => [k, values[i]]));
  },
};
