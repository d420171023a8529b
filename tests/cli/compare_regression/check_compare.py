#!/usr/bin/env python3
"""`tristim compare` against the numbers recorded before issue 13's speed work.

The expected_*.csv files were written by `tristim compare --json` at commit 8389a72 (main before
issue 13; mean-CIEDE2000 objective by NLopt BOBYQA), on
  * passport: the 24 Passport DNG patches (tests/data/passport/camera_rgb_dcraw_emu.csv, camera
    RGB derived by dcraw_emu) against X-Rite's ColorChecker Classic before-Nov-2014 L*a*b* D50, plain and with
    the white patch D1 preserved (--white D1), as examples/compare/compare_passport.py builds them;
  * sg140: sg140_camera_rgb.csv = `tristim simulate --camera Canon_EOS_5D_Mark_II --reflectances
    sg140 --illuminant D50 --white 4000 --noise 5 --seed 140`, sg140_reference_XYZ_D50.csv =
    `tristim reference --chart sg140 --illuminant D50 --precision 17` (X, Y, Z columns).

The ls and psm rows were re-recorded (`--record`) when the fits became the same
bits natively and in wasm (Eigen scalar in both builds, Lab and CIEDE2000 through
core/src/detmath.hpp): the last bits moved, and three things amplify them -- the pattern search
(Guarnera 2018 Algorithm 2) is a discrete search whose end point moves with its start's last bits
(Passport: Shen2008 psm training mean 2.492225 -> 2.492077, Cheung2004-11 psm 2.497357 ->
2.493967), and Finlayson2015-4 (ill-conditioned, leave-one-out mean 51 ΔE00 on the Passport)
moved by up to 1e-4 relative on the Passport (plain and --white D1) and 2e-8 on the SG (its
fourth roots are now sqrt(sqrt(p)) instead of pow(p, 0.25)); every other ls and psm row was
within 1e-9 of the 8389a72 record. The de2000 rows keep the 8389a72 record (the rule below).

Stated tolerance (exit status 1 otherwise):
  * every row: the same models, objectives, ok / refused and has-leave-one-out flags;
  * ls and psm rows (same algorithms as before): training and leave-one-out mean / max / p95
    CIEDE2000 equal to 1e-9 relative;
  * de2000 rows: the mean-CIEDE2000 optimiser changed (reweighted Levenberg-Marquardt instead of
    BOBYQA, which stopped early), so the training mean -- the loss being minimised -- must be at
    most the recorded one + 0.001 ΔE00 (+ 0.01 for a fit flagged ill_conditioned, whose
    coefficients are poorly determined); the leave-one-out figures change with the optimum and
    are printed, not compared.
Usage: check_compare.py --tristim PATH [--only passport|sg140] [--record]
  --record: rewrite the ls and psm rows of the expected files from this run (de2000 rows kept).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, '..', '..', '..'))


def expected(name):
    with open(os.path.join(HERE, name), newline='') as f:
        return {(r['model'], r['objective']): r for r in csv.DictReader(f)}


def record(exp_name, rows):
    path = os.path.join(HERE, exp_name)
    with open(path, newline='') as f:
        reader = csv.DictReader(f)
        fields, old = reader.fieldnames, list(reader)
    for e in old:
        r = rows[(e['model'], e['objective'])]
        if e['objective'] == 'de2000' or not r['ok']:
            continue
        e.update(train_mean=repr(r['train_dE00']['mean']), train_max=repr(r['train_dE00']['max']))
        if r.get('has_loo'):
            e.update(loo_mean=repr(r['loo_dE00']['mean']), loo_p95=repr(r['loo_dE00']['p95']),
                     loo_max=repr(r['loo_dE00']['max']))
    with open(path, 'w', newline='') as f:
        w = csv.DictWriter(f, fieldnames=fields, lineterminator='\n')
        w.writeheader()
        w.writerows(old)
    print(f'{exp_name}: ls and psm rows re-recorded')


def compare(tristim, rgb, xyz, extra, exp_name, rerecord=False):
    exp = expected(exp_name)
    out = subprocess.run([tristim, 'compare', '--rgb', rgb, '--xyz', xyz, '--json'] + extra,
                         check=True, capture_output=True, text=True).stdout
    rows = {(r['model'], r['objective']): r for r in json.loads(out)['rows']}
    if rerecord:
        record(exp_name, rows)
        exp = expected(exp_name)
    fails, loo_shift = [], []
    if set(rows) != set(exp):
        return [f'{exp_name}: rows differ: {sorted(set(rows) ^ set(exp))}']
    for k, e in exp.items():
        r = rows[k]
        if int(r['ok']) != int(e['ok']) or int(r.get('has_loo', False)) != int(e['has_loo']):
            fails.append(f'{exp_name} {k}: ok/has_loo {r["ok"]},{r.get("has_loo")} expected {e["ok"]},{e["has_loo"]}')
            continue
        if not r['ok']:
            continue
        got = {'train_mean': r['train_dE00']['mean'], 'train_max': r['train_dE00']['max']}
        if r.get('has_loo'):
            got.update(loo_mean=r['loo_dE00']['mean'], loo_p95=r['loo_dE00']['p95'], loo_max=r['loo_dE00']['max'])
        if k[1] == 'de2000':
            old = float(e['train_mean'])
            tol = 1e-2 if r['status'] == 'ill_conditioned' else 1e-3
            if not got['train_mean'] <= old + tol:
                fails.append(f'{exp_name} {k}: training mean {got["train_mean"]:.6f} > recorded {old:.6f} + {tol}')
            if 'loo_mean' in got:
                loo_shift.append((got['loo_mean'] - float(e['loo_mean']), k, float(e['loo_mean']), got['loo_mean']))
            continue
        for name, v in got.items():
            want = float(e[name])
            if abs(v - want) > 1e-9 * max(1.0, abs(want)):
                fails.append(f'{exp_name} {k} {name}: {v!r} expected {want!r} (tolerance 1e-9 relative)')
    if loo_shift:
        worst = max(loo_shift, key=lambda t: abs(t[0]))
        print(f'{exp_name}: de2000 leave-one-out means moved by {min(t[0] for t in loo_shift):+.3f} .. '
              f'{max(t[0] for t in loo_shift):+.3f} ΔE00 (largest: {worst[1]} {worst[2]:.3f} -> {worst[3]:.3f})')
    print(f'{exp_name}: {len(exp)} rows checked, {len(fails)} failures')
    return fails


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--tristim', required=True)
    ap.add_argument('--only', choices=['passport', 'sg140'])
    ap.add_argument('--record', action='store_true')
    args = ap.parse_args()
    fails = []
    if args.only in (None, 'passport'):
        with tempfile.TemporaryDirectory(prefix='tristim_cmp_') as tmp:
            def rows(path):
                with open(os.path.join(REPO, path), newline='') as f:
                    return list(csv.DictReader(f))
            rgb = rows('tests/data/passport/camera_rgb_dcraw_emu.csv')
            lab = {r['patch']: r for r in rows('core/data/charts/colorchecker24_xrite_before_nov2014_Lab_D50.csv')}
            ids = ['ABCD'[i // 6] + str(i % 6 + 1) for i in range(24)]
            rgb_csv, ref_csv = os.path.join(tmp, 'rgb.csv'), os.path.join(tmp, 'ref.csv')
            with open(rgb_csv, 'w') as f:
                f.write('id,R,G,B\n' + ''.join(f"{i},{r['R']},{r['G']},{r['B']}\n" for i, r in zip(ids, rgb)))
            with open(ref_csv, 'w') as f:
                f.write('id,L,a,b\n' + ''.join(f"{i},{lab[r['patch']]['L']},{lab[r['patch']]['a']},{lab[r['patch']]['b']}\n"
                                               for i, r in zip(ids, rgb)))
            fails += compare(args.tristim, rgb_csv, ref_csv, [], 'expected_passport.csv', args.record)
            fails += compare(args.tristim, rgb_csv, ref_csv, ['--white', 'D1'], 'expected_passport_white_D1.csv', args.record)
    if args.only in (None, 'sg140'):
        fails += compare(args.tristim, os.path.join(HERE, 'sg140_camera_rgb.csv'),
                         os.path.join(HERE, 'sg140_reference_XYZ_D50.csv'), [], 'expected_sg140.csv', args.record)
    for f in fails:
        print('FAIL', f)
    return 1 if fails else 0


if __name__ == '__main__':
    sys.exit(main())
