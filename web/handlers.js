// Worker request handlers, by request type: (T, msg, {state, progress}) -> {result, transfer}.
// T is the wasm module; handlers stay thin and call the core through it.
export const handlers = {
  hello: (T) => ({ result: { version: T.version() } }),
};
