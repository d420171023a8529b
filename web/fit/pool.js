// The workers of the compare (step 3): a few workers running the page's worker.js (the same wasm
// module, the same 'fit' handler as one fit), fed one row at a time so rows run side by side and
// come back as each finishes. Only self-contained requests go here (a recipe, the chart sample and
// the reference travel with each row); the decoded images stay in the engine's own worker, which
// the compare leaves alone. Messages only (postMessage), no shared memory.
import { EngineClient } from '../protocol.js';

const cancelled = () => Object.assign(new Error('cancelled'), { code: 'CANCELLED' });

export class WorkerPool {
  /// size: how many workers (the page passes navigator.hardwareConcurrency, at least 2).
  /// onCrash(reason): a worker died (its module aborted or the worker failed); it is replaced.
  constructor(size, { onCrash } = {}) {
    this.size = size;
    this.onCrash = onCrash;
    this.clients = [];
    this.generation = 0;   // bumped by stop(): answers of an earlier run are dropped
  }

  /// Starts the workers (each instantiates the page's compiled module), if not yet running.
  warm() {
    while (this.clients.length < this.size) {
      const c = this.spawn();
      this.clients.push(c);
      c.call('hello').catch(() => {});
    }
  }

  spawn() {
    const c = new EngineClient();
    c.onfatal = (reason) => {
      const i = this.clients.indexOf(c);
      if (i < 0) return;
      c.terminate();
      this.clients[i] = this.spawn();
      this.onCrash?.(reason);
    };
    return c;
  }

  /// Runs `task(client, job)` for every job, in the order given, two jobs per worker at a time (the
  /// next one waits in the worker's queue, so the worker does not idle while the page is busy
  /// drawing the previous answer); `onDone(job, {result} | {error})` as each one ends. Resolves once every job has ended, or
  /// with false as soon as stop() is called (later answers are dropped).
  async map(jobs, task, onDone) {
    this.warm();
    const generation = this.generation;
    const queue = [...jobs];
    const lane = async (slot) => {
      while (queue.length && generation === this.generation) {
        const job = queue.shift();
        let out;
        try { out = { result: await task(this.clients[slot], job) }; } catch (error) { out = { error }; }
        if (generation !== this.generation) return;
        onDone(job, out);
      }
    };
    await Promise.all(this.clients.flatMap((_, slot) => [lane(slot), lane(slot)]));
    return generation === this.generation;
  }

  /// Runs one job on another client (the page passes the engine's own worker, whose module is
  /// instantiated and warm, for the first row of the first screen) under this pool's stop():
  /// onDone as in map(). Resolves with false when stop() was called meanwhile (the answer is
  /// dropped; that worker is not the pool's to terminate).
  async one(client, job, task, onDone) {
    const generation = this.generation;
    let out;
    try { out = { result: await task(client, job) }; } catch (error) { out = { error }; }
    if (generation !== this.generation) return false;
    onDone(job, out);
    return true;
  }

  /// Stops every worker now (the work really stops: the workers are terminated); their pending
  /// calls reject with CANCELLED. The next map() starts fresh workers.
  stop() {
    this.generation++;
    for (const c of this.clients) {
      const pending = [...c.pending.values()];
      c.pending.clear();
      c.terminate();
      for (const p of pending) p.reject(cancelled());
    }
    this.clients = [];
  }
}
