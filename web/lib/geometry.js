// Display geometry for the corner overlay: a homography from the unit square to the four chart
// corners (for drawing the patch grid only; the engine does the real sampling).

/// corners: [x0,y0, x1,y1, x2,y2, x3,y3] = top-left, top-right, bottom-right, bottom-left.
/// Returns (u, v) -> [x, y], u along the top edge, v down the left edge (Heckbert 1989).
export function squareToQuad(c) {
  const [x0, y0, x1, y1, x2, y2, x3, y3] = c;
  const dx1 = x1 - x2, dx2 = x3 - x2, dy1 = y1 - y2, dy2 = y3 - y2;
  const sx = x0 - x1 + x2 - x3, sy = y0 - y1 + y2 - y3;
  let g = 0, hh = 0;
  const det = dx1 * dy2 - dx2 * dy1;
  if (Math.abs(sx) > 1e-12 || Math.abs(sy) > 1e-12) {
    g = (sx * dy2 - dx2 * sy) / det;
    hh = (dx1 * sy - sx * dy1) / det;
  }
  const a = x1 - x0 + g * x1, b = x3 - x0 + hh * x3, cc = x0;
  const d = y1 - y0 + g * y1, e = y3 - y0 + hh * y3, f = y0;
  return (u, v) => {
    const w = g * u + hh * v + 1;
    return [(a * u + b * v + cc) / w, (d * u + e * v + f) / w];
  };
}

/// Patch cells of a rows x cols grid inside the corners (the outer corners of the corner
/// patches), with `gap` between patches as a fraction of the patch size (as the engine's
/// chart_layout), each shrunk to its central `area` fraction of width and height:
/// [{row, col, quad: [[x,y]x4], centre}].
export function gridCells(corners, rows, cols, area = 0.5, gap = 0) {
  const map = squareToQuad(corners);
  const pu = 1 / (cols + (cols - 1) * gap), pv = 1 / (rows + (rows - 1) * gap);
  const cells = [];
  for (let r = 0; r < rows; r++) {
    for (let c = 0; c < cols; c++) {
      const uc = c * pu * (1 + gap) + pu / 2, vc = r * pv * (1 + gap) + pv / 2;
      const du = (pu * area) / 2, dv = (pv * area) / 2;
      const quad = [[uc - du, vc - dv], [uc + du, vc - dv], [uc + du, vc + dv], [uc - du, vc + dv]].map(([u, v]) => map(u, v));
      cells.push({ row: r, col: c, quad, centre: map(uc, vc) });
    }
  }
  return cells;
}

/// True when the quadrilateral's edges cross (self-intersecting corners).
export function isCrossed(c) {
  const p = [[c[0], c[1]], [c[2], c[3]], [c[4], c[5]], [c[6], c[7]]];
  const cross = (o, a, b) => (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  const inter = (a, b, c2, d) => cross(a, b, c2) * cross(a, b, d) < 0 && cross(c2, d, a) * cross(c2, d, b) < 0;
  return inter(p[0], p[1], p[2], p[3]) || inter(p[1], p[2], p[3], p[0]);
}
