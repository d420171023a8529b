// The page's session as a project file's parts (pure functions, tested in node): the session's
// byte buffers (chart RAW, dark frames, flat, scene) become the project's images, every typed
// array a tagged list, the rest JSON as it is; decodeSession gives the session back as the page
// keeps it in IndexedDB.

/// {json, images: [{key, name, bytes: Uint8Array}]} of a session object.
export function encodeSession(session) {
  const images = [];
  const walk = (v, key, name) => {
    if (v instanceof ArrayBuffer) {
      images.push({ key, name: name ?? key, bytes: new Uint8Array(v.slice(0)) });
      return { $image: images.length - 1 };
    }
    if (ArrayBuffer.isView(v)) return { $typed: v.constructor.name, data: Array.from(v) };
    if (Array.isArray(v)) return v.map((x) => walk(x, key, name));
    if (v && typeof v === 'object') {
      const out = {};
      for (const [k, x] of Object.entries(v)) out[k] = walk(x, key, typeof v.name === 'string' ? v.name : name);
      return out;
    }
    return v;
  };
  const json = {};
  for (const [k, v] of Object.entries(session)) if (v !== undefined) json[k] = walk(v, k, undefined);
  return { json: JSON.stringify(json), images };
}

const TYPED = { Float64Array, Float32Array, Int32Array, Uint32Array, Int16Array, Uint16Array, Int8Array, Uint8Array, Uint8ClampedArray };

/// The session of encodeSession's parts (`images`: [{bytes}] in the same order).
export function decodeSession(json, images) {
  const walk = (v) => {
    if (Array.isArray(v)) return v.map(walk);
    if (v && typeof v === 'object') {
      if (Number.isInteger(v.$image) && Object.keys(v).length === 1) {
        const im = images[v.$image];
        if (!im) throw Object.assign(new Error(`the project names image ${v.$image}, which it does not hold`), { code: 'PARSE_ERROR' });
        return new Uint8Array(im.bytes).slice().buffer;
      }
      if (typeof v.$typed === 'string' && Array.isArray(v.data)) {
        const Ctor = TYPED[v.$typed];
        if (!Ctor) throw Object.assign(new Error(`unknown array type '${v.$typed}' in the project`), { code: 'PARSE_ERROR' });
        return Ctor.from(v.data);
      }
      return Object.fromEntries(Object.entries(v).map(([k, x]) => [k, walk(x)]));
    }
    return v;
  };
  const parsed = typeof json === 'string' ? JSON.parse(json) : json;
  return walk(parsed);
}

/// The rows of a results text ("name value …" per line) as [name, value].
export const resultRows = (text) => text.split('\n').filter(Boolean).map((line) => {
  const sp = line.indexOf(' ');
  return sp < 0 ? [line, ''] : [line.slice(0, sp), line.slice(sp + 1)];
});

/// What the Share step offers for a `link` against the engine's length `limit` (shareLinkLimit):
/// {link, note} within it; beyond it no link, and a note that says why and offers a project file.
export function linkOffer(link, limit, label) {
  if (link.length > limit)
    return { link: '', note: `The link would have ${link.length} characters, more than ${limit} (some mail and chat programs cut such links): export a project file instead (below).` };
  return { link, note: `${label}: ${link.length} characters. Whoever opens it recomputes this profile from the data in the link (in this page, or with tristim reproduce) and sees whether it comes out the same. Nothing is uploaded: the data are in the part after #, which browsers never send.` };
}
