// Worker handlers of step 6: the engine's exports (ICC, .cube, DCP, ACES IDT, per-patch CSV), the
// engine's DCP, CLF, .cube and ICC readers for a download read back, and the evaluation of a profile loaded back on the current
// chart data.
import { reply, displayOf } from '../lib/reply.js';

export const handlers = {
  evaluate: (T, { profile, rgb, xyz, ids }) => {
    const out = T.evaluateProfile(profile, rgb, xyz, ids);
    out.display = displayOf(T, xyz, out.estimated, out.profile.colorimetry.white);
    return reply(out);
  },

  exportIcc: (T, { profile }) => reply({ bytes: T.exportIcc(profile) }),
  patchCsv: (T, { ids, rgb, xyz, estimated, white, loo }) => ({ result: { text: T.patchCsv(ids, rgb, xyz, estimated, white, loo) } }),
  exportCube: (T, { profile, size = 33 }) => ({ result: { text: T.exportCube(profile, size) } }),
  // options: DcpOptions (camera_model, hue_sat_map …); the same bytes as `tristim export --dcp`.
  exportDcp: (T, { profile, options }) => reply({ bytes: T.exportDcp(profile, options) }),
  // Two profiles of the camera under two illuminants: `tristim export --profile p --second p2 --dcp`.
  exportDcpDual: (T, { profile, second, options }) => reply({ bytes: T.exportDcpDual(profile, second, options) }),
  readDcp: (T, { bytes }) => reply(T.readDcp(bytes)),
  // ACES IDT: {clf, matrix, json}, the files of `tristim idt --camera … --illuminant …` (or of a
  // chart's patches), and the engine's CLF reader for a download read back.
  idtCamera: (T, { camera, illuminant, adaptation }) => reply(T.idtCamera(camera, illuminant, adaptation)),
  idtSensitivities: (T, { text, name, illuminant, adaptation }) => reply(T.idtSensitivities(text, name, illuminant, adaptation)),
  idtChart: (T, { rgb, xyz, white, adaptation, rgbName, referenceName, illuminant }) =>
    reply(T.idtChart(rgb, xyz, white, adaptation, rgbName, referenceName, illuminant)),
  readClf: (T, { text }) => reply(T.readClf(text)),
  // The engine's .cube and ICC header readers (tristim/profile/headers.hpp) for a file read back.
  readCube: (T, { text, name }) => ({ result: T.readCubeHeader(text, name) }),
  readIcc: (T, { bytes, name }) => ({ result: T.readIccHeader(bytes, name) }),
};
