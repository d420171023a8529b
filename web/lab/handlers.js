// Worker handlers of the Lab mode: a chart photograph rendered by the engine from measured
// spectra (DNG bytes, transferred, and its truth as JSON), and camera quality: the SMI / μ ranking
// of the 52 cameras and one camera's curves beside their best-fit CMF combination; metamer pairs.
import { reply } from '../lib/reply.js';

export const handlers = {
  /// options: LabRenderOptions fields (camera, chart, illuminant, exposure, shot_gain, oecf, …);
  /// format: 'dng', 'tiff' or 'jpeg'; the illuminant's SPD is the engine's for its id, or read by
  /// the engine from an uploaded CSV `spd` {name, text}.
  /// `refl` {name, text}: uploaded reflectances, read by the engine, drawn as a generated grid.
  labRender: (T, { options, format = 'dng', spd, refl }) => {
    T.labOption('render.seed', options.seed);   // a whole number before it becomes the engine's integer
    const L = spd ? T.readIlluminantCsv(spd.text, spd.name) : T.illuminantSpectrum(options.illuminant ?? 'D65');
    const o = { ...options, illuminant_spd: L };
    const out = refl ? T.labRenderReflectances(o, T.readReflectanceFile(refl.text, refl.name), format) : T.labRender(o, format);
    return { result: { dng: out.dng, truth: JSON.parse(out.truth), reference: out.reference, format }, transfer: [out.dng.buffer] };
  },
  labOecfs: (T) => reply(T.listLabOecfs()),
  /// Exercise 1: one patch's spectra and its XYZ / Lab / xy under each illuminant and observer.
  labSpectra: (T, { chart, patch, illuminants, observers }) => reply(T.labSpectraToColour(chart, patch, illuminants, observers)),
  /// Exercise 2: models × training charts on training, leave-one-out and the Munsell chips.
  labOverfit: (T, { camera, illuminant = 'D65', noise }) => reply(T.labOverfit(
    camera === 'cmf' ? T.cmfSensitivities() : T.cameraSensitivities(camera), T.illuminantSpectrum(illuminant), { noise })),
  labRanking: (T, { illuminant = 'D65' }) => reply(T.cameraQualityRanking(T.illuminantSpectrum(illuminant))),
  labCamera: (T, { camera, illuminant = 'D65' }) => {
    const ssf = T.cameraSensitivities(camera), L = T.illuminantSpectrum(illuminant);
    return reply({ quality: T.cameraQuality(ssf, L, camera), fit: T.lutherFit(ssf, L) });
  },
  /// The metamerism explorer: options are MetamerOptions fields; `construct` a Munsell id builds a
  /// metamer of that chip, otherwise pairs are searched in the Munsell set.
  labMetamers: (T, { options, construct }) => {
    if (!construct) T.labOption('metamers.top', options.top);   // a whole number before it becomes the engine's int
    return reply(construct ? T.labConstructMetamer(options, construct) : T.labMetamers(options));
  },
  labMunsell: (T) => reply(T.listMunsell()),
};
