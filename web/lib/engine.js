// The page's handle on the worker. Cancelling long work terminates the worker and starts a
// fresh one; `generation` tells views that worker-side state (decoded images) is gone and must
// be re-sent from the bytes the page keeps.
import { EngineClient } from '../protocol.js';

export class Engine extends EventTarget {
  constructor() {
    super();
    this.generation = 0;
    this.client = new EngineClient();
  }

  call(type, args, opts) { return this.client.call(type, args, opts); }

  /// Stops whatever the worker is doing (pending calls reject with code CANCELLED) and starts a
  /// new worker.
  restart() {
    const pending = [...this.client.pending.values()];
    this.client.pending.clear();
    this.client.terminate();
    for (const p of pending) p.reject(Object.assign(new Error('cancelled'), { code: 'CANCELLED' }));
    this.client = new EngineClient();
    this.generation++;
    this.dispatchEvent(new Event('restart'));
  }
}
