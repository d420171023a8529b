// Worker handlers of step 6: the engine's exports (ICC, .cube, per-patch CSV) and the evaluation
// of a profile loaded back on the current chart data.
import { reply, displayOf } from '../lib/reply.js';

export const handlers = {
  evaluate: (T, { profile, rgb, xyz, ids }) => {
    const out = T.evaluateProfile(profile, rgb, xyz, ids);
    out.display = displayOf(T, xyz, out.estimated, out.profile.white);
    return reply(out);
  },

  exportIcc: (T, { profile }) => reply({ bytes: T.exportIcc(profile) }),
  patchCsv: (T, { ids, rgb, xyz, estimated, white, loo }) => ({ result: { text: T.patchCsv(ids, rgb, xyz, estimated, white, loo) } }),
  exportCube: (T, { profile, size = 33 }) => ({ result: { text: T.exportCube(profile, size) } }),
};
