#!/usr/bin/env python3
"""Gamma 2.2 + CIEDE2000 3x3: tristim next to OpenCV's ccm on the same 8-bit chart patches.

Input: the 24 patches of a real photographed ColorChecker as OpenCV's own ccm tests use them
(`tests/data/opencv-ccm/opencv_mcc_sample_colorchecker_rgb.csv`: 8-bit sRGB-encoded camera
values and OpenCV's ColorChecker 2005 L*a*b*, D50, 2 deg).

OpenCV (Debian's python3-opencv, cv2.ccm, 4.6):
  * linearisation: LINEARIZATION_GAMMA, gamma 2.2, on src / 255 (x -> sign(x) |x|^2.2);
  * CCM_3x3, DISTANCE_CIE2000, colour space sRGB: the CCM maps linear camera RGB (row vector)
    to *linear sRGB*; the reference L*a*b* (D50) is taken to linear sRGB through XYZ and a
    Bradford adaptation D50 -> D65; the loss is the RMS CIEDE2000 between L*a*b* computed
    *relative to D65* (sRGB's white), started from least squares, refined by downhill simplex.
tristim, made to use the same conventions:
  * `tristim linearise --method gamma:gamma=2.2 --full-scale 255` (the same curve);
  * reference XYZ: the same L*a*b* D50 -> XYZ (Y = 100) -> Bradford to D65;
  * `tristim fit --model matrix-3x3 --objective de2000 --de-rms --lab-white D65`: the 3x3 maps
    linear camera RGB to XYZ (column vector), L*a*b* relative to D65, RMS CIEDE2000 loss
    (Levenberg-Marquardt from least squares).
Then tristim's matrix should equal 100 * M_sRGB * CCM^T (M_sRGB: linear sRGB -> XYZ, D65) and the
two losses should agree. Also printed: tristim's own default convention (reference XYZ D50,
L*a*b* relative to D50), which differs from OpenCV's by the white and the adaptation.

Exit status 1 if a claim fails: linearised values equal OpenCV's to 1e-12; tristim's RMS
CIEDE2000 (scored by tristim) <= OpenCV's + 1e-3; the matrices agree to 2 % of their largest entry.
Usage: opencv_gamma_ccm.py [--tristim PATH] [--json]
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, '..', '..'))
sys.path.insert(0, os.path.join(REPO, 'tests', 'support'))
from cie_lab import D50, D65, lab_to_xyz  # noqa: E402  (the independent L*a*b* -> XYZ)
BRADFORD = [[0.8951, 0.2664, -0.1614], [-0.7502, 1.7135, 0.0367], [0.0389, -0.0685, 1.0296]]
SRGB_TO_XYZ = [[0.4124564, 0.3575761, 0.1804375], [0.2126729, 0.7151522, 0.0721750],
               [0.0193339, 0.1191920, 0.9503041]]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(len(b))) for j in range(len(b[0]))] for i in range(len(a))]


def matvec(a, v):
    return [sum(a[i][k] * v[k] for k in range(len(v))) for i in range(len(a))]


def inverse3(m):
    a, b, c = m[0]
    d, e, f = m[1]
    g, h, i = m[2]
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    return [[(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det],
            [(f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det],
            [(d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det]]


def bradford(src_white, dst_white):
    s, d = matvec(BRADFORD, src_white), matvec(BRADFORD, dst_white)
    scale = [[d[0] / s[0], 0, 0], [0, d[1] / s[1], 0], [0, 0, d[2] / s[2]]]
    return matmul(inverse3(BRADFORD), matmul(scale, BRADFORD))


def run(cmd):
    return subprocess.run(cmd, check=True, capture_output=True, text=True).stdout


def write_csv(path, header, rows):
    with open(path, 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(header)
        for r in rows:
            w.writerow(r)


def tristim_fit(tristim, tmp, lin_csv, ref_rows, white_name, tag):
    ref_csv = os.path.join(tmp, f'ref_{tag}.csv')
    write_csv(ref_csv, ['patch', 'X', 'Y', 'Z'], ref_rows)
    prof = json.loads(run([tristim, 'fit', '--rgb', lin_csv, '--xyz', ref_csv, '--model', 'matrix-3x3',
                           '--objective', 'de2000', '--de-rms', '--lab-white', white_name, '--no-loo']))
    return prof, ref_csv


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--tristim', default=os.environ.get('TRISTIM_BIN', os.path.join(REPO, 'build/native/core/tristim')))
    ap.add_argument('--json', action='store_true')
    args = ap.parse_args()
    try:
        import numpy as np
        import cv2
    except ImportError:
        print('python3-opencv / numpy not importable (run with Debian\'s /usr/bin/python3; '
              'scripts/install-deps.sh installs python3-opencv)')
        return 1

    with open(os.path.join(REPO, 'tests', 'data', 'opencv-ccm', 'opencv_mcc_sample_colorchecker_rgb.csv')) as f:
        rows = list(csv.DictReader(f))
    ids = [r['index'] for r in rows]
    rgb = [[float(r['R_8bit']), float(r['G_8bit']), float(r['B_8bit'])] for r in rows]
    lab = [[float(r['ref_L_D50']), float(r['ref_a_D50']), float(r['ref_b_D50'])] for r in rows]
    out, failures = {}, []
    with tempfile.TemporaryDirectory() as tmp:
        rgb_csv, lin_csv = os.path.join(tmp, 'rgb.csv'), os.path.join(tmp, 'linear.csv')
        write_csv(rgb_csv, ['patch', 'R', 'G', 'B'], [[i] + v for i, v in zip(ids, rgb)])
        run([args.tristim, 'linearise', '--method', 'gamma:gamma=2.2', '--rgb', rgb_csv, '--full-scale', '255',
             '--out', lin_csv])
        with open(lin_csv) as f:
            lin = [[float(r['R']), float(r['G']), float(r['B'])] for r in csv.DictReader(f)]

        # --- OpenCV
        src = (np.array(rgb, dtype=np.float64) / 255.0).reshape(24, 1, 3)
        dst = np.array(lab, dtype=np.float64).reshape(24, 1, 3)
        model = cv2.ccm_ColorCorrectionModel(src, dst, cv2.ccm.COLOR_SPACE_Lab_D50_2)
        model.setColorSpace(cv2.ccm.COLOR_SPACE_sRGB)
        model.setCCM_TYPE(cv2.ccm.CCM_3x3)
        model.setDistance(cv2.ccm.DISTANCE_CIE2000)
        model.setLinear(cv2.ccm.LINEARIZATION_GAMMA)
        model.setLinearGamma(2.2)
        model.run()
        ccm = np.array(model.getCCM())
        src_lin = np.array(model.get_src_rgbl()).reshape(-1, 3)
        mask = np.array(model.getMask()).reshape(-1).astype(bool)
        lin_masked = np.array(lin)[mask]
        out['linearised_max_difference'] = float(np.abs(lin_masked - src_lin).max())
        if not out['linearised_max_difference'] < 1e-12:
            failures.append('gamma 2.2 linearisation differs from OpenCV\'s')
        out['opencv_patches_used'] = int(mask.sum())
        opencv_xyz_d65 = (100.0 * np.array(SRGB_TO_XYZ) @ ccm.T).tolist()  # camera RGB (column) -> XYZ D65, Y = 100
        out['opencv'] = {'ccm_row_vector_to_linear_sRGB': ccm.tolist(), 'as_camera_to_XYZ_D65': opencv_xyz_d65,
                         'loss_rms_dE00_Lab_D65': float(model.getLoss())}

        # --- tristim with OpenCV's conventions: XYZ adapted D50 -> D65 (Bradford), Lab relative to D65
        to_d65 = bradford(D50, D65)
        ref_d65 = [[i] + matvec(to_d65, lab_to_xyz(l, D50)) for i, l in zip(ids, lab)]
        prof, ref_d65_csv = tristim_fit(args.tristim, tmp, lin_csv, [r for r, m in zip(ref_d65, mask) if m] if not mask.all() else ref_d65, 'D65', 'd65')
        M = prof['model']['coefficients']
        out['tristim_opencv_convention'] = {'camera_to_XYZ_D65': M, 'objective_rms_dE00_Lab_D65': prof['fit']['objective_value']}
        # Score OpenCV's matrix with tristim's CIEDE2000 on the same data (same white).
        ocv_prof = dict(prof)
        ocv_prof['model'] = dict(prof['model'], coefficients=opencv_xyz_d65)
        for k in ('recipe', 'metrics'):
            ocv_prof.pop(k, None)
        pj = os.path.join(tmp, 'opencv_profile.json')
        with open(pj, 'w') as f:
            json.dump(ocv_prof, f)
        ev = json.loads(run([args.tristim, 'evaluate', '--profile', pj, '--rgb', lin_csv, '--xyz', ref_d65_csv]))
        out['opencv']['rms_dE00_scored_by_tristim'] = ev['metrics']['dE00']['rms']
        biggest = max(abs(v) for row in M for v in row)
        out['matrix_max_difference_relative'] = max(abs(M[i][j] - opencv_xyz_d65[i][j]) for i in range(3) for j in range(3)) / biggest
        if not prof['fit']['objective_value'] <= ev['metrics']['dE00']['rms'] + 1e-3:
            failures.append('tristim RMS CIEDE2000 above OpenCV\'s (same metric)')
        if not out['matrix_max_difference_relative'] < 0.02:
            failures.append('matrices differ by more than 2 % of the largest entry')

        # --- tristim's own default: reference XYZ D50, Lab relative to D50
        ref_d50 = [[i] + lab_to_xyz(l, D50) for i, l in zip(ids, lab)]
        prof50, _ = tristim_fit(args.tristim, tmp, lin_csv, ref_d50, 'D50', 'd50')
        out['tristim_default_convention'] = {'camera_to_XYZ_D50': prof50['model']['coefficients'],
                                             'objective_rms_dE00_Lab_D50': prof50['fit']['objective_value']}
    out['conventions'] = {
        'opencv': 'Lab relative to D65 (sRGB white, xy 0.3127/0.3290); reference Lab D50 -> XYZ -> Bradford D50->D65 -> linear sRGB; CCM maps row vectors to linear sRGB; loss RMS CIEDE2000; saturation mask (0, 0.98)',
        'tristim': 'Lab relative to --lab-white (D50 by default: 96.4212, 100, 82.5188); reference XYZ as given; matrix maps column vectors to XYZ (Y = 100 scale); --de-rms: RMS CIEDE2000'}
    out['failures'] = failures
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        f3 = lambda m: '\n'.join('    [' + ', '.join(f'{v:10.5f}' for v in row) + ']' for row in m)
        print('OpenCV ccm (gamma 2.2, CCM_3x3, DISTANCE_CIE2000, sRGB), patches used: %d of 24' % out['opencv_patches_used'])
        print('  CCM (linear camera RGB row -> linear sRGB row):\n' + f3(out['opencv']['ccm_row_vector_to_linear_sRGB']))
        print('  as camera RGB -> XYZ D65 (Y = 100):\n' + f3(out['opencv']['as_camera_to_XYZ_D65']))
        print('  loss (RMS CIEDE2000, Lab D65): %.6f   scored by tristim: %.6f' %
              (out['opencv']['loss_rms_dE00_Lab_D65'], out['opencv']['rms_dE00_scored_by_tristim']))
        print('tristim, OpenCV\'s conventions (reference adapted to D65, --lab-white D65):')
        print('  camera RGB -> XYZ D65:\n' + f3(out['tristim_opencv_convention']['camera_to_XYZ_D65']))
        print('  RMS CIEDE2000: %.6f' % out['tristim_opencv_convention']['objective_rms_dE00_Lab_D65'])
        print('  largest matrix difference: %.3g of the largest entry; linearised values differ by at most %.2g'
              % (out['matrix_max_difference_relative'], out['linearised_max_difference']))
        print('tristim, its default conventions (reference XYZ D50, Lab relative to D50):')
        print('  camera RGB -> XYZ D50:\n' + f3(out['tristim_default_convention']['camera_to_XYZ_D50']))
        print('  RMS CIEDE2000: %.6f' % out['tristim_default_convention']['objective_rms_dE00_Lab_D50'])
        print('conventions:\n  OpenCV:  ' + out['conventions']['opencv'] + '\n  tristim: ' + out['conventions']['tristim'])
        for f_ in failures:
            print('FAILED: ' + f_)
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
