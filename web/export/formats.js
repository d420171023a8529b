// Light readers used to load exports back (.cube header and size, ICC header), so a user can
// check a file before trusting it. (Every file the page writes comes from the engine.)
/// .cube (Adobe/Resolve 3D LUT, optionally after a Resolve 1D shaper of LUT_1D_SIZE rows):
/// returns {size, shaperSize, title, entries, domainMin, domainMax} or throws; entries counts 3D rows.
export function readCube(text) {
  let size = 0, shaperSize = 0, title = '', entries = 0, domainMin = [0, 0, 0], domainMax = [1, 1, 1];
  const lines = text.split(/\r?\n/);
  lines.forEach((line, k) => {
    const t = line.trim();
    if (!t || t.startsWith('#')) return;
    const [key, ...rest] = t.split(/\s+/);
    if (key === 'TITLE') title = t.slice(6).replace(/^"|"$/g, '');
    else if (key === 'LUT_3D_SIZE') size = Number(rest[0]);
    else if (key === 'LUT_1D_SIZE') shaperSize = Number(rest[0]);
    else if (key === 'DOMAIN_MIN') domainMin = rest.map(Number);
    else if (key === 'DOMAIN_MAX') domainMax = rest.map(Number);
    else if (/^[-+.\deE]/.test(key)) {
      const v = [key, ...rest].map(Number);
      if (v.length !== 3 || v.some((x) => !Number.isFinite(x))) throw Object.assign(new Error(`line ${k + 1}: expected three numbers`), { code: 'PARSE_ERROR' });
      entries++;
    }
  });
  if (!size) throw Object.assign(new Error('no LUT_3D_SIZE line'), { code: 'PARSE_ERROR' });
  if (entries !== shaperSize + size ** 3) {
    const want = shaperSize ? `${shaperSize} shaper + ${size}³ = ${shaperSize + size ** 3}` : `${size}³ = ${size ** 3}`;
    throw Object.assign(new Error(`${entries} table rows, expected ${want}`), { code: 'PARSE_ERROR' });
  }
  return { size, shaperSize, title, entries: entries - shaperSize, domainMin, domainMax };
}

/// ICC header (ICC.1:2022 §7.2): size, version, class, colour space, PCS, and the description.
export function readIccHeader(bytes) {
  const b = bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes);
  if (b.length < 132) throw Object.assign(new Error(`${b.length} bytes: too short for an ICC profile`), { code: 'PARSE_ERROR' });
  const dv = new DataView(b.buffer, b.byteOffset, b.byteLength);
  const sig = (o) => String.fromCharCode(b[o], b[o + 1], b[o + 2], b[o + 3]);
  if (sig(36) !== 'acsp') throw Object.assign(new Error('no ICC signature "acsp" at byte 36'), { code: 'PARSE_ERROR' });
  const size = dv.getUint32(0);
  if (size !== b.length) throw Object.assign(new Error(`header says ${size} bytes, file has ${b.length}`), { code: 'PARSE_ERROR' });
  const tags = dv.getUint32(128);
  const tagSigs = [];
  for (let k = 0; k < tags && 132 + 12 * k + 12 <= b.length; k++) tagSigs.push(sig(132 + 12 * k));
  return { size, version: `${b[8]}.${b[9] >> 4}`, deviceClass: sig(12), colourSpace: sig(16).trim(), pcs: sig(20).trim(), tags: tagSigs };
}
