#!/usr/bin/python3
# The test behind `ctest -R CalibrationSet`: renders a small set (render_calibration_set.py), runs
# `rovctl calibrate` on it and scores the result against the truth (check_calibration.py), then
# feeds it each kind of bad input: exit 2, the reason on stderr, nothing written.
"""Render a small calibration set, calibrate it with rovctl, check figures and bad input."""

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
if __name__ == "__main__":
    sys.dont_write_bytecode = True
    # The water set's helper: re-run under Debian's interpreter, where python3-opencv lives.
    sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "estimator", "water_set"))
    import debian_python

    debian_python.require_opencv()

import cv2  # noqa: E402

BOARD = "chessboard:9x6:30"


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True)


def expect_refusal(rovctl, tmp, name, args, needle):
    """rovctl calibrate with `args` must exit 2 naming `needle` and write nothing."""
    out = os.path.join(tmp, name + ".yaml")
    r = run([rovctl, "calibrate", "--out", out] + args)
    ok = r.returncode == 2 and needle in r.stderr and not os.path.exists(out) and \
        not os.path.exists(out + ".tmp")
    print("%s  bad input %-14s exit %d: %s" % ("PASS" if ok else "FAIL", name, r.returncode,
                                                r.stderr.strip().splitlines()[-1:]))
    return ok


def bad_inputs(rovctl, tmp, good_set):
    ok = True
    not_rec = os.path.join(tmp, "not_a_recording")
    os.makedirs(not_rec)
    ok &= expect_refusal(rovctl, tmp, "not_recording", ["--pairs", not_rec, "--board", BOARD],
                         "not a recording")
    ok &= expect_refusal(rovctl, tmp, "bad_board", ["--pairs", good_set, "--board",
                                                    "chessboard:9x6mm:30"], "--board")
    # Two sizes: the first pair's right image at half size.
    two = os.path.join(tmp, "two_sizes")
    shutil.copytree(good_set, two)
    first = os.path.join(two, "right", "000000.png")
    img = cv2.imread(first)
    cv2.imwrite(first, cv2.resize(img, (img.shape[1] // 2, img.shape[0] // 2)))
    ok &= expect_refusal(rovctl, tmp, "two_sizes", ["--pairs", two, "--board", BOARD],
                         "one calibration holds for one image size")
    # Too few views: the index cut to its first six pairs.
    few = os.path.join(tmp, "few")
    shutil.copytree(good_set, few)
    with open(os.path.join(few, "frames.csv")) as f:
        lines = f.read().splitlines()
    with open(os.path.join(few, "frames.csv"), "w") as f:
        f.write("\n".join(lines[:7]) + "\n")
    ok &= expect_refusal(rovctl, tmp, "too_few", ["--pairs", few, "--board", BOARD],
                         "too few views")
    return ok


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--rovctl", required=True)
    ap.add_argument("--pairs", type=int, default=16)
    ap.add_argument("--water", choices=["clear", "cast"], default="clear")
    ap.add_argument("--seed", type=int, default=2)
    args = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="rovctl_calibration_set_")
    try:
        rec = os.path.join(tmp, "set")
        r = run([sys.executable, os.path.join(HERE, "render_calibration_set.py"), "--out", rec,
                 "--pairs", str(args.pairs), "--water", args.water, "--seed", str(args.seed)])
        if r.returncode != 0:
            sys.exit("render failed: " + r.stderr)
        out = os.path.join(tmp, "calibration.yaml")
        r = run([args.rovctl, "calibrate", "--pairs", rec, "--board", BOARD, "--out", out,
                 "--json"])
        if r.returncode != 0:
            sys.exit("rovctl calibrate exit %d: %s" % (r.returncode, r.stderr))
        report = os.path.join(tmp, "report.json")
        with open(report, "w") as f:
            f.write(r.stdout)
        summary = json.loads(r.stdout)
        print("views %d used of %d, RMS %.3f px, uncertain: %s" % (
            summary["views_used"], summary["views_total"], summary["rms_reprojection_px"],
            [u["why"] for u in summary["uncertain"]]))
        ok = os.path.exists(os.path.join(tmp, "calibration.coverage.png"))
        print("%s  coverage picture written" % ("PASS" if ok else "FAIL"))
        again = run([args.rovctl, "calibrate", "--pairs", rec, "--board", BOARD, "--out", out])
        kept = again.returncode == 2 and "--force" in again.stderr
        print("%s  an existing file is not overwritten without --force" % (
            "PASS" if kept else "FAIL"))
        ok &= kept
        r = run([sys.executable, os.path.join(HERE, "check_calibration.py"), "--set", rec,
                 "--calibration", out, "--report", report])
        print(r.stdout, end="")
        ok &= r.returncode == 0
        ok &= bad_inputs(args.rovctl, tmp, rec)
    finally:
        shutil.rmtree(tmp)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
