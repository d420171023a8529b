#!/usr/bin/env python3
"""tristim's chart detector beside OpenCV's mcc detector on the synthetic detection test set.

Runs `detect_testset --write DIR` (tristim detects in the linear images and writes each scene as an
8-bit sRGB PPM plus DIR/truth.csv), then OpenCV's mcc (`cv2.mcc`, Debian's python3-opencv) on the
PPM files, and prints, per chart and in all: detection rate (right place AND right orientation),
median / 95th-percentile corner error of those detections, wrong orientations and misplaced
detections, and the median / 95th-percentile error of the patch centres.

mcc reports the box of its own chart model (patches 2.5 units with 0.25 gaps, 0.25 border); its
box is converted to the patch grid's outer corners with that model, and its patch centres are its
model's centres through the same box. tristim's corners are the grid's outer corners directly,
its centres follow from them and the gap it fitted. Corners are compared in the order each tool
reports them (A1 first); a detection counts as in the right place when some cyclic order of its
corners is within a quarter of a patch pitch of the truth.

usage: compare_mcc.py --testset build/native/tests/detect_testset [--count 300] [--seed 1]
                      [--keep DIR] [--check]
--check: exit 1 unless tristim's rate is at least mcc's, its median corner error at most mcc's,
         and it has no wrong orientation among accepted detections.
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile
import time

try:
    import cv2
    import numpy as np
except ImportError as e:  # pragma: no cover
    print(f"SKIP: OpenCV for Python not importable ({e}); install Debian's python3-opencv")
    sys.exit(0)

LAYOUT = {"cc24": (4, 6), "passport": (4, 6), "sg140": (10, 14)}


def homography(src, dst):
    return cv2.getPerspectiveTransform(np.float32(src), np.float32(dst))


def transform(H, pts):
    return cv2.perspectiveTransform(np.float64(pts).reshape(-1, 1, 2), H).reshape(-1, 2)


def centres_unit(rows, cols, gap):
    """Patch centres in the unit square of the patch grid (layout.hpp convention), row-major."""
    w = 1.0 / (cols + (cols - 1) * gap)
    h = 1.0 / (rows + (rows - 1) * gap)
    return [((c * (1 + gap) + 0.5) * w, (r * (1 + gap) + 0.5) * h) for r in range(rows) for c in range(cols)]


def grid_from_corners(corners, rows, cols, gap):
    H = homography([[0, 0], [1, 0], [1, 1], [0, 1]], np.array(corners).reshape(4, 2))
    return transform(H, centres_unit(rows, cols, gap))


def mcc_grid(box, chart):
    """mcc's box -> (grid corners, patch centres) with mcc's chart model."""
    rows, cols = LAYOUT[chart]
    bw, bh = cols * 2.75 + 0.25, rows * 2.75 + 0.25
    H = homography([[0, 0], [bw, 0], [bw, bh], [0, bh]], box)
    corners = transform(H, [[0.25, 0.25], [bw - 0.25, 0.25], [bw - 0.25, bh - 0.25], [0.25, bh - 0.25]])
    centres = transform(H, [(0.25 + c * 2.75 + 1.25, 0.25 + r * 2.75 + 1.25) for r in range(rows) for c in range(cols)])
    return corners.reshape(-1), centres


def score(corners, truth, pitch):
    """(located, oriented, error in reported order)."""
    c = np.array(corners).reshape(4, 2)
    t = np.array(truth).reshape(4, 2)
    errs = [np.mean(np.linalg.norm(np.roll(c, -s, axis=0) - t, axis=1)) for s in range(4)]
    best = int(np.argmin(errs))
    located = errs[best] < 0.25 * pitch
    return located, located and best == 0, errs[0]


def summary(rows):
    out = {}
    for key in ("cc24", "passport", "sg140", "all"):
        sel = [r for r in rows if key == "all" or r["chart"] == key]
        if not sel:
            continue
        ok = [r for r in sel if r["oriented"]]
        e = np.array([r["error"] for r in ok]) if ok else np.array([np.nan])
        ce = np.array([r["centre_error"] for r in ok]) if ok else np.array([np.nan])
        out[key] = dict(n=len(sel), rate=len(ok) / len(sel), wrong=sum(r["located"] and not r["oriented"] for r in sel),
                        misplaced=sum(r["detected"] and not r["located"] for r in sel),
                        med=np.median(e), p95=np.percentile(e, 95), cmed=np.median(ce), cp95=np.percentile(ce, 95),
                        ms=np.median([r["ms"] for r in sel]))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--testset", required=True)
    ap.add_argument("--count", type=int, default=300)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--keep", help="write the images here and keep them")
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()
    tmp = None
    folder = a.keep
    if not folder:
        tmp = tempfile.TemporaryDirectory(prefix="tristim_detect_")
        folder = tmp.name
    os.makedirs(folder, exist_ok=True)
    run = subprocess.run([a.testset, "--count", str(a.count), "--seed", str(a.seed), "--write", folder],
                         capture_output=True, text=True)
    print(run.stdout, end="")
    if run.returncode != 0:
        print(run.stderr, file=sys.stderr)
        return 1
    tristim, mcc = [], []
    detector = cv2.mcc.CCheckerDetector_create()
    with open(os.path.join(folder, "truth.csv")) as f:
        for r in csv.DictReader(f):
            chart = r["chart"]
            rows, cols = LAYOUT[chart]
            truth = [float(r[k]) for k in ("x1", "y1", "x2", "y2", "x3", "y3", "x4", "y4")]
            pitch, gap = float(r["pitch"]), float(r["gap"])
            true_centres = grid_from_corners(truth, rows, cols, gap)
            # tristim (detected in the linear image by detect_testset)
            t = dict(chart=chart, detected=r["tristim_detected"] == "1", located=r["tristim_located"] == "1",
                     oriented=r["tristim_oriented"] == "1", error=float(r["tristim_error"]), ms=float(r["tristim_ms"]))
            if t["detected"]:
                tc = [float(r[k]) for k in ("tx1", "ty1", "tx2", "ty2", "tx3", "ty3", "tx4", "ty4")]
                cen = grid_from_corners(tc, rows, cols, float(r["tristim_gap"]))
                t["centre_error"] = float(np.mean(np.linalg.norm(cen - true_centres, axis=1)))
            tristim.append(t)
            # mcc on the 8-bit sRGB rendering
            img = cv2.imread(os.path.join(folder, r["file"]))
            t0 = time.perf_counter()
            found = detector.process(img, cv2.mcc.SG140 if chart == "sg140" else cv2.mcc.MCC24, 1)
            ms = 1000 * (time.perf_counter() - t0)
            m = dict(chart=chart, detected=False, located=False, oriented=False, error=np.nan, ms=ms)
            checkers = detector.getListColorChecker() if found else []
            if checkers:
                corners, centres = mcc_grid(np.array(checkers[0].getBox()), chart)
                located, oriented, err = score(corners, truth, pitch)
                m.update(detected=True, located=located, oriented=oriented, error=err,
                         centre_error=float(np.mean(np.linalg.norm(centres - true_centres, axis=1))))
            mcc.append(m)
    st, sm = summary(tristim), summary(mcc)
    print()
    print("tristim (linear image) vs OpenCV mcc (8-bit sRGB image), same %d scenes:" % len(tristim))
    print("%-9s %4s | %8s %8s %8s %5s %5s %8s | %8s %8s %8s %5s %5s %8s" % (
        "chart", "n", "rate", "med px", "p95 px", "wrong", "misp", "ctr med",
        "mcc rate", "med px", "p95 px", "wrong", "misp", "ctr med"))
    for key in st:
        a_, b_ = st[key], sm[key]
        print("%-9s %4d | %7.1f%% %8.2f %8.2f %5d %5d %8.2f | %7.1f%% %8.2f %8.2f %5d %5d %8.2f" % (
            key, a_["n"], 100 * a_["rate"], a_["med"], a_["p95"], a_["wrong"], a_["misplaced"], a_["cmed"],
            100 * b_["rate"], b_["med"], b_["p95"], b_["wrong"], b_["misplaced"], b_["cmed"]))
    print("median time per image: tristim %.0f ms (detect only), mcc %.0f ms" % (st["all"]["ms"], sm["all"]["ms"]))
    if a.check:
        s, m = st["all"], sm["all"]
        ok = s["rate"] >= m["rate"] and (np.isnan(m["med"]) or s["med"] <= m["med"]) and s["wrong"] == 0
        print("CHECK", "passed" if ok else "FAILED",
              "(tristim rate >= mcc rate, tristim median corner error <= mcc's, no wrong orientation)")
        return 0 if ok else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
