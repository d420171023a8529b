// Page entry: starts the engine in a worker and mounts the views.
import { EngineClient } from './protocol.js';

const engine = new EngineClient();
const status = document.getElementById('engine-status');

try {
  const { version } = await engine.call('hello');
  status.textContent = `Colour engine tristim ${version} ready (WebAssembly, in a worker).`;
  status.dataset.ready = 'true';
} catch (e) {
  status.textContent = `The colour engine failed to start: ${e.message} (${e.code}).`;
  status.classList.add('error');
}
