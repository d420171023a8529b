// The example chart of a new session (examples/passport.json and its RAW). main.js fetches it as
// soon as it knows the session is new and starts its decode in the engine's worker while the
// views load and mount; the images view (restore) takes the decode over.

/// {cfg, bytes}: the example's settings and its RAW file.
export async function fetchExample() {
  const cfg = await (await fetch('examples/passport.json')).json();
  const res = await fetch(`examples/${cfg.file}`);
  if (!res.ok) throw Object.assign(new Error(`examples/${cfg.file}: HTTP ${res.status}`), { code: 'EXAMPLE_MISSING' });
  return { cfg, bytes: await res.arrayBuffer() };
}

/// Starts decoding the example's bytes (a copy is transferred; no preview: the images view asks
/// for it after the sampling). decoding: the engine's reply, taken over by the images view; t0:
/// when it was sent (the view says how long the decode took).
export function decodeExample(engine, example) {
  const t0 = performance.now();
  const copy = new Uint8Array(example.bytes).slice().buffer;
  const decoding = engine.call('decode', { slot: 'chart', bytes: copy, previewSide: 0 }, { transfer: [copy] });
  decoding.catch(() => {});   // reported by the images view, which awaits it
  return { ...example, decoding, t0, generation: engine.generation };
}
