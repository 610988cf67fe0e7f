#!/usr/bin/python3
# Scores a calibration `rovctl calibrate` wrote against the truth of a set rendered by
# render_calibration_set.py: the acceptance figures, and every planted bad view left out.
"""Compare an estimated stereo calibration with the set's true rig.

Figures: fx, fy (% off), principal point (px), baseline (% off), relative rotation (deg), and the
truth-vs-estimate reprojection of points at 0.5 m and 1 m seen over the left image inset by a tenth
on each side (both cameras; RMS and worst, px). With --report (rovctl calibrate --json), every
planted bad view must be left out with its reason. Exit 1 when a limit is broken.
"""

import argparse
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
if __name__ == "__main__":
    sys.dont_write_bytecode = True
    # The water set's helper: re-run under Debian's interpreter, where python3-opencv lives.
    sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "estimator", "water_set"))
    import debian_python

    debian_python.require_opencv()

import cv2  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, HERE)
from render_calibration_set import read_rig  # noqa: E402

LIMITS = {"focal_pct": 0.5, "centre_px": 3.0, "baseline_pct": 1.0, "rotation_deg": 0.2,
          "reproj_worst_px": 1.5, "reproj_rms_px": {"clear": 0.5, "cast": 1.0}}


def project(pts, R, t, K, D):
    p = pts @ R.T + t
    uv, _ = cv2.projectPoints(p.reshape(-1, 1, 3), np.zeros(3), np.zeros(3), K, D)
    return uv.reshape(-1, 2), p[:, 2]


def reprojection(truth, est):
    """Points at 0.5 m and 1 m on the true left camera's rays through the inset image, projected
    into both cameras by the truth and by the estimate; those the true right camera sees count."""
    w, h = truth["size"]
    us, vs = np.meshgrid(np.linspace(0.1 * w, 0.9 * w, 25), np.linspace(0.1 * h, 0.9 * h, 19))
    px = np.stack([us.ravel(), vs.ravel()], axis=1).reshape(-1, 1, 2)
    crit = (cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 50, 1e-12)
    n = cv2.undistortPointsIter(px, truth["K1"], truth["D1"], None, None, crit).reshape(-1, 2)
    errors = []
    for depth in (0.5, 1.0):
        pts = np.column_stack([n * depth, np.full(len(n), depth)])
        for cam in ("1", "2"):
            R, t = (np.eye(3), np.zeros(3)) if cam == "1" else (truth["R"], truth["T"])
            Re, te = (np.eye(3), np.zeros(3)) if cam == "1" else (est["R"], est["T"])
            uv_t, z = project(pts, R, t, truth["K" + cam], truth["D" + cam])
            uv_e, _ = project(pts, Re, te, est["K" + cam], est["D" + cam])
            seen = (z > 0) & (uv_t[:, 0] >= 0) & (uv_t[:, 0] < w) & (uv_t[:, 1] >= 0) & \
                (uv_t[:, 1] < h)
            errors.extend(np.linalg.norm(uv_t - uv_e, axis=1)[seen].tolist())
    e = np.array(errors)
    return float(np.sqrt(np.mean(e ** 2))), float(e.max())


def figures(truth, est):
    f = {}
    for cam in ("1", "2"):
        Kt, Ke = truth["K" + cam], est["K" + cam]
        f["fx%s_pct" % cam] = 100.0 * abs(Ke[0, 0] / Kt[0, 0] - 1.0)
        f["fy%s_pct" % cam] = 100.0 * abs(Ke[1, 1] / Kt[1, 1] - 1.0)
        f["centre%s_px" % cam] = float(math.hypot(Ke[0, 2] - Kt[0, 2], Ke[1, 2] - Kt[1, 2]))
    bt, be = np.linalg.norm(truth["T"]), np.linalg.norm(est["T"])
    f["baseline_pct"] = 100.0 * abs(be / bt - 1.0)
    dR = est["R"] @ truth["R"].T
    f["rotation_deg"] = math.degrees(math.acos(max(-1.0, min(1.0, (np.trace(dR) - 1) / 2))))
    f["reproj_rms_px"], f["reproj_worst_px"] = reprojection(truth, est)
    return f


def judge(f, water):
    lines = []
    for cam in ("1", "2"):
        lines.append(("fx%s" % cam, f["fx%s_pct" % cam], LIMITS["focal_pct"], "%"))
        lines.append(("fy%s" % cam, f["fy%s_pct" % cam], LIMITS["focal_pct"], "%"))
        lines.append(("principal point %s" % cam, f["centre%s_px" % cam], LIMITS["centre_px"],
                      "px"))
    lines.append(("baseline", f["baseline_pct"], LIMITS["baseline_pct"], "%"))
    lines.append(("relative rotation", f["rotation_deg"], LIMITS["rotation_deg"], "deg"))
    lines.append(("reprojection RMS", f["reproj_rms_px"], LIMITS["reproj_rms_px"][water], "px"))
    lines.append(("reprojection worst", f["reproj_worst_px"], LIMITS["reproj_worst_px"], "px"))
    ok = True
    for name, value, limit, unit in lines:
        good = value <= limit
        ok &= good
        print("%s  %-20s %.3f %s (limit %g)" % ("PASS" if good else "FAIL", name, value, unit, limit))
    return ok


def judge_views(truth_views, report):
    by_name = {v["name"]: v for v in report["views"]}
    ok = True
    for v in truth_views:
        got = by_name.get(v["name"])
        if v["kind"] == "good":
            if got is None or not got["kept"]:
                print("NOTE  good view %s left out: %s" % (v["name"], got and got["reason"]))
            continue
        good = got is not None and not got["kept"] and \
            got["reason"].startswith(v["expected_reason"])
        ok &= good
        print("%s  planted %-10s %s: %s" % ("PASS" if good else "FAIL", v["kind"], v["name"],
                                             got and got["reason"]))
    return ok


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--set", required=True, help="folder written by render_calibration_set.py")
    ap.add_argument("--calibration", required=True, help="the YAML rovctl calibrate wrote")
    ap.add_argument("--report", help="rovctl calibrate --json output, to check the views' reasons")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    with open(os.path.join(args.set, "truth.json")) as f:
        set_truth = json.load(f)
    truth = read_rig(set_truth["calibration"])
    est = read_rig(args.calibration)
    f = figures(truth, est)
    if args.json:
        print(json.dumps(f, indent=1))
    ok = judge(f, set_truth["water"])
    if args.report:
        with open(args.report) as fr:
            ok &= judge_views(set_truth["views"], json.load(fr))
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
