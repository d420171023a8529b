// Grid shapes of the built-in chart layouts, for drawing the overlay and ordering ids.
// Patch id conventions (TEAM brief): cc24/passport "A1".."D6" = row letter, column number;
// Gaps between patches as fractions of the patch size follow the engine's chart_layout.
// sg140 "A1".."N10" = column letter, row number; custom "R1C1"...
export const LAYOUTS = {
  passport: { rows: 4, cols: 6, gap: 0.14, label: 'ColorChecker Passport (classic side)' },
  cc24: { rows: 4, cols: 6, gap: 0.14, label: 'ColorChecker Classic 24' },
  'cc24-2005': { rows: 4, cols: 6, gap: 0.14, label: 'ColorChecker Classic 24 (before Nov 2014)' },
  sg140: { rows: 10, cols: 14, label: 'ColorChecker SG 140' },
  'sg140-2005': { rows: 10, cols: 14, label: 'ColorChecker SG 140 (before Nov 2014)' },
  custom: { rows: 4, cols: 6, label: 'Custom grid' },
};

const L = 'ABCDEFGHIJKLMNOPQRSTUVWXYZ';
/// Patch id of the cell (row, col) of a layout.
export function cellId(layout, row, col) {
  if (layout.startsWith('sg140')) return `${L[col]}${row + 1}`;
  if (layout === 'custom') return `R${row + 1}C${col + 1}`;
  return `${L[row]}${col + 1}`;
}
