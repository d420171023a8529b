// The page's handle on the worker. Cancelling long work terminates the worker and starts a
// fresh one; `generation` tells views that worker-side state (decoded images) is gone and must
// be re-sent from the bytes the page keeps.
import { EngineClient } from '../protocol.js';

export class Engine extends EventTarget {
  /// boot: boot.js's early worker (self.tristimBoot) to take over, or null (a new worker).
  constructor({ boot = null } = {}) {
    super();
    this.generation = 0;
    this.crashes = 0;
    this.client = this.connect(boot);
  }

  connect(boot = null) {
    const client = new EngineClient(undefined, { boot });
    client.onfatal = (reason) => { if (client === this.client) this.recover(reason); };
    // boot.js's worker may have died before it was taken over
    const died = boot && (boot.fatal ?? boot.failed);
    if (died) queueMicrotask(() => client.onfatal(died));
    return client;
  }

  /// The worker died (its module aborted: out of memory, a trap; or the worker itself failed):
  /// a new one is started, views re-send what they need (the 'restart' event), and 'crashed'
  /// {detail: reason} tells the page to say what happened. The session (files, corners,
  /// results) lives in the page and is kept.
  recover(reason) {
    this.crashes++;
    this.restart();
    this.dispatchEvent(new CustomEvent('crashed', { detail: reason }));
  }

  call(type, args, opts) { return this.client.call(type, args, opts); }

  /// Stops whatever the worker is doing (pending calls reject with code CANCELLED) and starts a
  /// new worker.
  restart() {
    const pending = [...this.client.pending.values()];
    this.client.pending.clear();
    this.client.terminate();
    for (const p of pending) p.reject(Object.assign(new Error('cancelled'), { code: 'CANCELLED' }));
    this.client = this.connect();
    this.generation++;
    this.dispatchEvent(new Event('restart'));
  }
}
