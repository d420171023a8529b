#!/usr/bin/env python3
"""Measures the four outer corners of the example Passport's patch grid from edge profiles, the
way one would by hand with a ruler on a zoomed image, but repeatably — a check of the manual
preset (examples/web/passport.json) that does not use tristim's detector.

For each patch on the grid's border, the image (linear luminance Y of `tristim apply` with a 3×3
least-squares profile) is read along the normal of its outer edge: the profiles of the middle 60 %
of the edge are averaged (one profile per 0.5 px along the edge, bilinear), and the edge is where
that mean profile crosses halfway between the patch's level and the surround's. The four outer
lines of the grid (left of column 1, right of column 6, top of row A, bottom of row D) are fitted
to those edge points (total least squares, points weighted by their contrast / noise), and the
corners are the lines' intersections. Low-contrast edges (the black patch D6 against the black
frame) are left out. Nothing here depends on the layout's gap ratio.

usage: measure_passport_corners.py --tristim build/native/core/tristim --dng examples/web/passport.dng
       [--corners x1,y1,...,x4,y4 (start; default: the preset)] [--check]
Prints the measured corners and each one's distance to the start and to `tristim detect`.
Needs Debian's python3-numpy and python3-opencv (to read the float TIFF).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

ROWS, COLS, GAP = 4, 6, 0.14  # Passport classic side; GAP only places the profiles, not the result


def homography(src, dst):
    A = []
    for (x, y), (u, v) in zip(src, dst):
        A.append([x, y, 1, 0, 0, 0, -u * x, -u * y, -u])
        A.append([0, 0, 0, x, y, 1, -v * x, -v * y, -v])
    _, _, vt = np.linalg.svd(np.array(A, float))
    return vt[-1].reshape(3, 3) / vt[-1][-1]


def apply_h(H, u, v):
    p = H @ np.array([u, v, 1.0])
    return p[:2] / p[2]


def bilinear(img, x, y):
    h, w = img.shape
    x0 = np.clip(np.floor(x - 0.5).astype(int), 0, w - 2)  # pixel (i, j) covers [i, i+1): centre i + 0.5
    y0 = np.clip(np.floor(y - 0.5).astype(int), 0, h - 2)
    fx = np.clip(x - 0.5 - x0, 0, 1)
    fy = np.clip(y - 0.5 - y0, 0, 1)
    return ((1 - fx) * (1 - fy) * img[y0, x0] + fx * (1 - fy) * img[y0, x0 + 1]
            + (1 - fx) * fy * img[y0 + 1, x0] + fx * fy * img[y0 + 1, x0 + 1])


def edge_point(img, a, b, outward, reach=7.0, step=0.1):
    """Edge between image points a and b (the patch's outer edge, predicted), `outward` its unit
    normal. Returns (point on the edge, contrast/noise) or None."""
    along = b - a
    length = np.linalg.norm(along)
    ts = np.arange(-reach, reach + 1e-9, step)
    ss = np.arange(0.2 * length, 0.8 * length + 1e-9, 0.5)
    d = along / length
    xs = a[0] + np.outer(ss, d)[:, 0][:, None] + np.outer(np.ones_like(ss), ts * outward[0])
    ys = a[1] + np.outer(ss, d)[:, 1][:, None] + np.outer(np.ones_like(ss), ts * outward[1])
    prof = bilinear(img, xs, ys)
    mean = prof.mean(axis=0)
    inside, outside = mean[ts < -reach / 2], mean[ts > reach / 2]
    lin, lout = np.median(inside), np.median(outside)
    noise = (prof[:, ts < -reach / 2].std() + prof[:, ts > reach / 2].std()) / np.sqrt(len(ss)) + 1e-9
    snr = abs(lin - lout) / noise
    if snr < 20:
        return None
    half = 0.5 * (lin + lout)
    s = np.sign(lin - lout)
    # the crossing nearest the predicted edge (t = 0)
    above = s * (mean - half) > 0
    crossings = [i for i in range(len(ts) - 1) if above[i] and not above[i + 1]]
    if not crossings:
        return None
    i = min(crossings, key=lambda k: abs(ts[k]))
    t = ts[i] + (mean[i] - half) / (mean[i] - mean[i + 1]) * step
    mid = a + 0.5 * along
    return mid + t * outward, snr


def fit_line(points, weights):
    P = np.array(points)
    w = np.array(weights) / np.sum(weights)
    c = (w[:, None] * P).sum(axis=0)
    Q = (P - c) * np.sqrt(w)[:, None]
    _, _, vt = np.linalg.svd(Q)
    n = vt[-1]  # normal
    return n, n @ c  # line: n·p = d


def intersect(l1, l2):
    (n1, d1), (n2, d2) = l1, l2
    return np.linalg.solve(np.array([n1, n2]), np.array([d1, d2]))


def measure(img, corners):
    unit = [(0, 0), (1, 0), (1, 1), (0, 1)]
    H = homography(unit, corners)
    pw, ph = 1 / (COLS + (COLS - 1) * GAP), 1 / (ROWS + (ROWS - 1) * GAP)
    edges = {'top': [], 'right': [], 'bottom': [], 'left': []}
    for r in range(ROWS):
        for c in range(COLS):
            u0, v0 = c * pw * (1 + GAP), r * ph * (1 + GAP)
            u1, v1 = u0 + pw, v0 + ph
            P = {k: apply_h(H, *uv) for k, uv in {'tl': (u0, v0), 'tr': (u1, v0), 'br': (u1, v1), 'bl': (u0, v1)}.items()}
            centre = apply_h(H, (u0 + u1) / 2, (v0 + v1) / 2)
            sides = []
            if r == 0: sides.append(('top', P['tl'], P['tr']))
            if r == ROWS - 1: sides.append(('bottom', P['bl'], P['br']))
            if c == 0: sides.append(('left', P['tl'], P['bl']))
            if c == COLS - 1: sides.append(('right', P['tr'], P['br']))
            for name, a, b in sides:
                d = (b - a) / np.linalg.norm(b - a)
                n = np.array([-d[1], d[0]])
                if n @ (0.5 * (a + b) - centre) < 0:
                    n = -n
                e = edge_point(img, a, b, n)
                if e:
                    edges[name].append((e[0], e[1], f'{"ABCD"[r]}{c + 1}'))
    lines = {}
    for name, pts in edges.items():
        if len(pts) < 2:
            sys.exit(f'too few edge points on the {name} side: {[p[2] for p in pts]}')
        lines[name] = fit_line([p[0] for p in pts], [p[1] for p in pts])
    out = [intersect(lines['top'], lines['left']), intersect(lines['top'], lines['right']),
           intersect(lines['bottom'], lines['right']), intersect(lines['bottom'], lines['left'])]
    used = {k: [p[2] for p in v] for k, v in edges.items()}
    resid = {k: max(abs(lines[k][0] @ p[0] - lines[k][1]) for p in v) for k, v in edges.items()}
    return np.array(out), used, resid


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--tristim', required=True)
    ap.add_argument('--dng', required=True)
    ap.add_argument('--preset', default=os.path.join(os.path.dirname(__file__), '../web/passport.json'))
    ap.add_argument('--corners')
    ap.add_argument('--check', action='store_true',
                    help='exit 1 unless the preset is within 0.5 px of the measurement and the detector within 2 px')
    args = ap.parse_args()
    import cv2  # Debian's python3-opencv, only to read the float TIFF
    preset = json.load(open(args.preset))['corners']
    start = [float(v) for v in args.corners.split(',')] if args.corners else preset
    with tempfile.TemporaryDirectory() as tmp:
        run = lambda *a, **k: subprocess.run([args.tristim, *a], check=True, capture_output=True, text=True, **k).stdout
        csv = os.path.join(tmp, 'p.csv')
        open(csv, 'w').write(run('sample', args.dng, '--chart', 'passport', '--corners', ','.join(map(str, start))))
        ref = os.path.join(tmp, 'ref.csv')
        open(ref, 'w').write(run('reference', '--chart', 'passport', '--illuminant', 'D50'))
        prof = os.path.join(tmp, 'p.json')
        run('fit', '--rgb', csv, '--xyz', ref, '--model', 'matrix-3x3', '--objective', 'ls', '--no-loo', '--out', prof)
        tif = os.path.join(tmp, 'xyz.tiff')
        run('apply', prof, args.dng, '--out', tif)
        Y = cv2.imread(tif, cv2.IMREAD_UNCHANGED)[:, :, 1].astype(float)  # BGR order: Y stays in the middle
        detected = json.loads(run('detect', args.dng, '--chart', 'passport'))['candidates'][0]['corners']
    corners = np.array(start, float).reshape(4, 2)
    for _ in range(3):  # re-place the profiles on the measured grid
        corners, used, resid = measure(Y, corners)
    det = np.array(detected, float).reshape(4, 2)
    pre = np.array(preset, float).reshape(4, 2)
    print('edges used:', {k: ' '.join(v) for k, v in used.items()})
    print('largest distance of an edge point from its fitted line (px):', {k: round(v, 2) for k, v in resid.items()})
    print('corner  measured            preset        |d|    detected            |d|')
    for i, name in enumerate(['A1 top-left', 'A6 top-right', 'D6 bottom-right', 'D1 bottom-left']):
        m = corners[i]
        print(f'{name:16s} ({m[0]:7.2f}, {m[1]:7.2f})  ({pre[i][0]:5.0f}, {pre[i][1]:5.0f})  {np.linalg.norm(m - pre[i]):5.2f}'
              f'   ({det[i][0]:7.2f}, {det[i][1]:7.2f})  {np.linalg.norm(m - det[i]):5.2f}')
    print('corners:', ','.join(f'{v:.1f}' for v in corners.ravel()))
    if args.check:
        dp = max(np.linalg.norm(corners - pre, axis=1))
        dd = max(np.linalg.norm(corners - det, axis=1))
        print(f'check: preset {dp:.2f} px (limit 0.5), detector {dd:.2f} px (limit 2) from the measurement')
        if dp > 0.5 or dd > 2:
            sys.exit(1)


if __name__ == '__main__':
    main()
