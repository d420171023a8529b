// Worker handlers of the Absolute mode's spectral sensitivities (eq 7's channel areas A_R, A_G,
// A_B, Guarnera 2018): an uploaded CSV read by the engine's parser, the Jiang, Liu, Gu &
// Süsstrunk 2013 estimate from per-patch camera RGB (the chart step's samples or a patch file)
// paired by id with a built-in chart's reflectances under an illuminant, and a built-in camera's
// curves with the RMS difference for the comparison plot. The chosen set stays here
// (state.abs.ssf) and goes to absFit.
import { reply, coded } from '../lib/reply.js';

const spectral = (d) => ({ wavelengths: Array.from(d.wavelengths), values: d.values.map((v) => Array.from(v)) });

function ssfState(state) {
  state.abs ??= {};
  state.abs.ssf ??= { upload: null, estimate: null };
  return state.abs.ssf;
}

/// The sensitivities a fit uses: 'upload' | 'estimate' (kept here), anything else: none.
export function chosenSensitivities(state, which) {
  const s = ssfState(state);
  if (which !== 'upload' && which !== 'estimate') return null;
  if (!s[which]) throw coded(which === 'upload' ? 'no sensitivities CSV loaded' : 'no sensitivities estimated yet', 'NO_SENSITIVITIES');
  return s[which];
}

export const handlers = {
  /// An uploaded sensitivities CSV (wavelength_nm,R,G,B): the engine's parser, then its channel
  /// areas (a channel without a positive area is refused).
  absSsfUpload: (T, { text, name }, { state }) => {
    const s = ssfState(state);
    const ssf = T.readSensitivitiesCsv(text, name);
    const areas = T.channelAreas(ssf);
    s.upload = { ssf, source: `file:${name}` };
    return reply({ ssf: spectral(ssf), areas, name });
  },

  /// The estimate's own light or chart, as the CLI's --illuminant / --reflectances files:
  /// kind 'illuminant' (wavelength and one value column, read_illuminant_csv) or 'reflectances'
  /// (spectral CSV or CGATS with spectra, read_reflectance_file), kept here for absSsfEstimate.
  absSsfSpectra: (T, { kind, text, name }, { state }) => {
    const s = ssfState(state);
    if (kind !== 'illuminant' && kind !== 'reflectances') throw coded(`unknown spectra kind '${kind}'`, 'INVALID_ARGUMENT');
    s[kind] = null;
    const data = kind === 'illuminant' ? T.readIlluminantCsv(text, name) : T.readReflectanceFile(text, name);
    s[kind] = { data, name };
    const wl = data.wavelengths;
    return reply({ name, columns: data.names.length, wavelengths: [wl[0], wl[wl.length - 1], wl.length] });
  },

  /// Jiang 2013 from per-patch linear camera RGB: {ids, rgb: Float64Array(3N)} or a patch file
  /// {patchFile: {text, name}} (R, G, B columns), paired by id with `chart`'s reflectances under
  /// `illuminant` (built-in ids; 'file': the ones absSsfSpectra read).
  absSsfEstimate: (T, { ids, rgb, patchFile, chart, illuminant, options = {} }, { state }) => {
    const s = ssfState(state);
    if (patchFile) {
      const p = T.parsePatchFile(patchFile.text, patchFile.name);
      if (!p.has_RGB) throw coded(`${patchFile.name}: no R, G, B columns`, 'MISSING_COLUMN');
      ids = p.ids; rgb = p.RGB;
    }
    if (!ids?.length) throw coded('no patches: sample the chart in step 2 or load a patch file', 'NO_PATCHES');
    const fromFile = (kind, what) => {
      if (!s[kind]) throw coded(`no ${what} file loaded`, 'NO_SPECTRA');
      return s[kind];
    };
    let refl, spd;
    if (chart === 'file') { const f = fromFile('reflectances', 'reflectance'); refl = f.data; chart = `file:${f.name}`; } else refl = T.chartReflectances(chart);
    if (illuminant === 'file') { const f = fromFile('illuminant', 'illuminant'); spd = f.data; illuminant = `file:${f.name}`; } else spd = T.illuminantSpectrum(illuminant);
    // SensitivityEstimate's field list: the object `tristim sensitivities estimate` prints (plain arrays, NaN as null)
    const e = T.estimateSensitivities(ids, rgb, refl, spd, options);
    // the areas' uncertainty (leave-one-camera-out bases, K ± 1) and whether the camera is unlike the basis
    const u = T.sensitivityUncertainty(ids, rgb, refl, spd, options, e);
    const label = `Jiang 2013 estimate (${chart}, ${illuminant}, ${e.patches} patches)`;
    const left = options.exclude_cameras?.length ? ` basis without ${options.exclude_cameras.join(' ')}` : '';
    s.estimate = { ssf: e.ssf, source: `estimate:Jiang2013 ${chart} ${illuminant} ${e.patches} patches K ${e.components}${left} residual ${e.residual_rms.toPrecision(3)}` };
    return reply({ ...e, csv: T.sensitivitiesToCsv(e.ssf), label,
      uncertainty: u });  // SensitivityUncertainty's field list: plain arrays, what the CLI prints as "uncertainty"
  },

  /// A built-in camera's curves and areas; with `which` ('upload' | 'estimate') the RMS difference
  /// of that set from the camera's (each channel scaled to peak 1).
  absSsfCompare: (T, { camera, which }, { state }) => {
    const cam = T.cameraSensitivities(camera);
    const set = which ? ssfState(state)[which] : null;
    return reply({ ssf: spectral(cam), areas: T.channelAreas(cam), rms: set ? T.sensitivityRms(set.ssf, cam) : null });
  },
};
