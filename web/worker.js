// The Web Worker that hosts the wasm module. It creates the module once, lazily, and answers
// requests by type. The message table is assembled from the features: each web/<feature>/
// handlers.js exports {type: (T, msg, {state, progress}) -> {result, transfer}}. Heavy state
// (decoded images, the applied XYZ image) stays here, in `state`.
import createTristim from './tristim.mjs';
import { reply } from './lib/reply.js';
import * as reference from './reference/handlers.js';
import * as surface from './surface/handlers.js';
import * as images from './images/handlers.js';
import * as detect from './images/detect.js';
import * as linearisation from './linearisation/handlers.js';
import * as fit from './fit/handlers.js';
import * as apply from './apply/handlers.js';
import * as exporter from './export/handlers.js';
import * as absolute from './absolute/handlers.js';
import * as share from './share/handlers.js';
import * as lab from './lab/handlers.js';
import * as labExercises from './lab/exercises_handlers.js';

const FEATURES = [reference, surface, images, detect, linearisation, fit, apply, exporter, absolute, lab, labExercises, share];

const handlers = {
  hello: (T) => ({ result: { version: T.version() } }),
  /// Every table the page builds its pickers from (the engine's method tables and layouts).
  catalog: (T) => reply({
    charts: T.listCharts(), illuminants: T.listIlluminants(), observers: T.listObservers(), cameras: T.listCameras(),
    models: T.listModels(), modelFamilies: T.listModelFamilies(), objectives: T.listObjectives(),
    linearisations: T.listLinearisations(), spectral: T.spectralMethod(), surfaces: T.listSurfaceCorrections(), surfacePresets: T.listSurfacePresets(),
    flatFieldModes: T.listFlatFieldModes(), absoluteOptions: T.listAbsoluteOptions(), fusionModes: T.listFusionModes(),
    surfaceOptions: T.listSurfaceOptions(), sensitivityOptions: T.listSensitivityOptions(),
    layoutOptions: T.listLayoutOptions(), labOptions: T.listLabOptions(), sampleFlags: T.listSampleFlags(),
    absoluteWhiteRules: T.listAbsoluteWhiteRules(), absoluteSensitivities: T.listAbsoluteSensitivities(),
    labCharts: T.listLabCharts(), labFileKinds: T.listLabFileKinds(), metamerMatches: T.listMetamerMatches(), shenTrainings: T.listShenTrainings(),
    bootstrapOptions: T.bootstrapOptions(),
    exampleLights: T.listExampleLights(), exampleTrainings: T.listExampleTrainings(),
    layouts: Object.fromEntries(T.listChartLayouts().map((id) => [id, id === 'custom' ? null : T.chartLayout({ chart: id })])),
  }),
  /// A light trap's box rows for an image of this size (light_trap_option_table: the boxes' bounds).
  lightTrapOptions: (T, { width, height }) => reply(T.listLightTrapOptions(width, height)),
  /// Test-only (tests/web/worker_restart.test.mjs): makes this worker die the two ways a real one
  /// can — 'abort': the module traps (what an abort or out-of-memory in wasm throws); 'uncaught':
  /// an error escapes the worker. It can only stop the caller's own worker, which the page replaces.
  testCrash: (T, { how }) => {
    if (how === 'uncaught') { setTimeout(() => { throw new Error('test: uncaught error in the worker'); }); return { result: 'crashing' }; }
    throw new WebAssembly.RuntimeError('Aborted(test: the module was made to abort)');
  },
};
for (const f of FEATURES) {
  for (const type of Object.keys(f.handlers)) if (handlers[type]) throw new Error(`two features handle '${type}'`);
  Object.assign(handlers, f.handlers);
}

// The page posts {type: 'module', module} first (protocol.js): a compiled WebAssembly.Module to
// instantiate, or null (the worker then fetches and compiles the module itself).
let receiveModule;
const pageModule = new Promise((resolve) => { receiveModule = resolve; });
let modulePromise = null;
const engine = () => (modulePromise ??= pageModule.then((module) => (module ? new Promise((resolve, reject) => {
  createTristim({
    instantiateWasm(imports, done) {
      WebAssembly.instantiate(module, imports).then((instance) => done(instance, module), reject);
      return {};
    },
  }).then(resolve, reject);
}) : createTristim())));
const state = {};  // per-worker state shared by handlers (e.g. the decoded images)

// Anything that escapes the request handlers is a bug: say so on the console (the browser tests
// fail on any console error). The page's onerror only rejects the pending calls.
self.addEventListener('unhandledrejection', (e) => console.error(`worker: unhandled rejection: ${e.reason?.stack ?? e.reason?.message ?? e.reason}`));
self.addEventListener('error', (e) => console.error(`worker: uncaught error: ${e.error?.stack ?? e.message}`));

self.onmessage = async (ev) => {
  const msg = ev.data;
  if (msg.type === 'module') { receiveModule(msg.module); engine(); return; }
  const handler = handlers[msg.type];
  // A request naming a file of the site (the example's RAW: decode's `url`) starts its download
  // now, while the module may still be instantiating; the handler takes the response from here.
  if (handler && typeof msg.url === 'string') {
    msg.response = fetch(msg.url);
    msg.response.catch(() => {});   // a failed download is reported by the handler, which awaits it
  }
  try {
    if (!handler) throw Object.assign(new Error(`unknown request '${msg.type}'`), { code: 'INVALID_ARGUMENT' });
    const T = await engine();
    const progress = (fraction, stage) => self.postMessage({ type: 'progress', id: msg.id, fraction, stage });
    const out = await handler(T, msg, { state, progress });
    const { result, transfer = [] } = out ?? {};
    self.postMessage({ type: 'result', id: msg.id, result }, transfer);
  } catch (e) {
    // A trap or abort of the wasm module (out of memory, a failed assertion) leaves it unusable:
    // say so and close; the page starts a new worker (web/lib/engine.js recover).
    const fatal = e instanceof WebAssembly.RuntimeError || /^Aborted\(/.test(String(e?.message));
    self.postMessage({ type: 'error', id: msg.id, code: fatal ? 'ENGINE_CRASHED' : e?.code ?? 'INTERNAL',
      message: String(e?.message ?? e), fatal });
    if (fatal) self.close();
  }
};
