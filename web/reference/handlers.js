// Worker handlers of step 1: reference colours of a built-in chart or a file, the spectral locus.
import { reply } from '../lib/reply.js';

export const handlers = {
  reference: (T, { chart, illuminant, observer }) => reply(T.referenceChart(chart, illuminant, observer)),
  /// A reference file, with the digest a recipe records for it.
  parseReference: (T, { text, fileName, illuminant, observer }) =>
    reply({ ...T.parseReferenceFile(text, fileName, illuminant, observer), data_digest: T.bytesDigest(text) }),
  spectralLocus: (T, { observer }) => reply(T.spectralLocus(observer)),
};
