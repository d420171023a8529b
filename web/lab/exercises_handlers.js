// Worker handlers of the Lab's exercises 3-5 (the papers' tables): each returns the engine's
// results for the plots and its results tables (LabTable: columns with units, cells as text) with
// the CSV the engine writes for them (lab_table_csv: the same bytes `tristim lab …` prints).
import { reply } from '../lib/reply.js';

const sensitivities = (T, camera) => (camera === 'cmf' ? T.cmfSensitivities() : T.cameraSensitivities(camera));
const withCsv = (T, table) => ({ ...table, csv: T.labTableCsv(table) });

export const handlers = {
  /// Exercise 3: Shen 2008's J sweep (Figs 2-3) and L table (Tables I-II) on a camera and chart.
  labShen: (T, { camera, chart }) => {
    const e = T.labShen(sensitivities(T, camera), { chart });
    return reply({ exercise: e, tables: [withCsv(T, T.labShenLTable(e)), withCsv(T, T.labShenJTable(e))] });
  },
  /// Exercise 4: Abed 2013 Table IV, every training row × method, the paper's cells beside.
  labTable4: (T, { camera, illuminant, noise }) => {
    const rows = T.labTable4(camera, illuminant, noise, 1);
    return reply({ rows, tables: [withCsv(T, T.labTable4Table(rows))] });
  },
  /// Exercise 5: exposure invariance (ΔE00 vs k) and Table 4 under one light, both trainings.
  labGuarnera: (T, { camera, illuminant }) => {
    const exposure = T.labExposure(sensitivities(T, camera), T.illuminantSpectrum(illuminant));  // the engine's models and k
    const table4 = camera === 'cmf' ? [] : T.labGuarneraTable4(camera, [illuminant], ['projector', 'reflective']);
    const tables = [withCsv(T, T.labExposureTable(exposure))];
    if (table4.length) tables.push(withCsv(T, T.labGuarneraTable(table4)));
    return reply({ exposure, table4, tables });
  },
};
