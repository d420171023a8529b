#!/usr/bin/env python3
"""Phase I of Abed, Berns & Masaoka (2013) on real data: the ColorChecker SG measured in two geometries.

From: COOLPI's X-Rite Digital ColorChecker SG (January 2007 edition), Konica Minolta CM-600d,
d:8 specular included (SCI). To: X-Rite's reference spectra of the SG charts made before Nov 2014
(as redistributed by dcamprof; a 45:0 instrument). Each surface correction is fitted over
400-700 nm with `tristim surface fit` (spectral RMS, bounded NLopt) and scored under D50 and the
CIE 1931 observer: mean and max CIEDE2000 before and after.

Exit status 1 if the paper's ranking does not hold on mean CIEDE2000:
  scaler ~ none (within 15 %), offset < scaler, scaler-offset < offset, Saunderson <= scaler-offset.

Usage: sg_two_geometries.py [--tristim PATH] [--json]
"""
import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, '..', '..'))
FROM = 'examples/web/sg_d8_sci_coolpi.csv'
TO = 'core/data/charts/colorcheckerSG_before_nov2014_reflectance_380-730_10nm.csv'

# (label, method, extra arguments)
ROWS = [
    ('none', 'none', []),
    ('scaler', 'scaler', []),
    ('offset', 'offset', []),
    ('scaler-offset', 'scaler-offset', []),
    ('Saunderson, d:8 SCI preset fixed', 'saunderson', ['--measurement', 'd8-sci', '--capture', '45-0']),
    ('Saunderson, 45:0 preset fixed', 'saunderson', ['--measurement', 'd8-sci', '--capture', '45-0',
                                                      '--free', 'measurement']),
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--tristim', default=os.environ.get('TRISTIM_BIN', os.path.join(REPO, 'build/native/core/tristim')))
    ap.add_argument('--json', action='store_true')
    a = ap.parse_args()
    paths = [os.path.join(REPO, p) for p in (FROM, TO)]
    for p in paths:
        if not os.path.exists(p):
            sys.exit(f'{p} not found: it is part of the repository')
    results = []
    for label, method, extra in ROWS:
        out = subprocess.run([a.tristim, 'surface', 'fit', '--from', paths[0], '--to', paths[1], '--method', method,
                              '--range', '400-700', '--illuminant', 'D50', '--observer', '1931', '--json'] + extra,
                             check=True, capture_output=True, text=True).stdout
        r = json.loads(out)
        r['label'] = label
        results.append(r)
    if a.json:
        print(json.dumps([{k: r[k] for k in ('label', 'surface', 'status', 'spectral_rms', 'dE00')} for r in results],
                         indent=2))
    else:
        print('ColorChecker SG: d:8 SCI (COOLPI XRCCSG, CM-600d) -> X-Rite reference (before Nov 2014)')
        print('400-700 nm, D50, CIE 1931; CIEDE2000 before: mean %.2f, max %.2f\n'
              % (results[0]['dE00']['before']['mean'], results[0]['dE00']['before']['max']))
        print('| correction | spectral RMS | mean ΔE00 | max ΔE00 | status | coefficients |')
        print('| --- | --- | --- | --- | --- | --- |')
        for r in results:
            c = r['choice']['parameters']
            coef = ', '.join('%s %.4g' % (k, v) for k, v in c.items())
            print('| %s | %.4f | %.2f | %.2f | %s | %s |' % (r['label'], r['spectral_rms']['after'],
                                                          r['dE00']['after']['mean'], r['dE00']['after']['max'],
                                                          r['status'], coef or '-'))
    mean = {r['label']: r['dE00']['after']['mean'] for r in results}
    so = mean['scaler-offset']
    claims = [
        ('scaler ~ none (within 15 %)', abs(mean['scaler'] - mean['none']) < 0.15 * mean['none']),
        ('offset < scaler', mean['offset'] < mean['scaler']),
        ('scaler-offset < offset', so < mean['offset']),
        ('Saunderson (SCI fixed) <= scaler-offset', mean[ROWS[4][0]] <= so),
        ('Saunderson (45:0 fixed) <= scaler-offset', mean[ROWS[5][0]] <= so),
    ]
    sys.stdout.flush()
    failed = [name for name, ok in claims if not ok]
    for name, ok in claims:
        print(('ok    ' if ok else 'FAILED ') + name, file=sys.stderr)
    sys.exit(1 if failed else 0)


if __name__ == '__main__':
    main()
