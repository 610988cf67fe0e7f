#!/usr/bin/python3
# A plain OpenCV pose pipeline scored on a water set, as the reference the estimator is measured
# against: what fixed HSV windows, enclosing circles, triangulation and Kabsch get from the same pairs.
"""Scores the plain pipeline per condition (and per band of true range) on a set's manifest.json.

It has no confidence: every pose it finds is its answer, so its wrong answers are what a pipeline
without an honest `ok` would hand the servo. Exit 0, or 1 when an --expect line is not met.
"""

import os
import sys

sys.dont_write_bytecode = True  # importing the generator must not leave __pycache__ in the tree

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import debian_python  # noqa: E402

debian_python.require_opencv()

import argparse  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402

import cv2  # noqa: E402
import numpy as np  # noqa: E402

import render_water_set as gen  # noqa: E402  (the calibration reader and the marker's geometry only)
from check_water_set import HUES, open_set, rotation_from_quat_wxyz  # noqa: E402  (read apart from gen)

RIGHT_MM, RIGHT_DEG = 10.0, 5.0  # as rovctl bench --set
# The self-check's hue windows (OpenCV's 0..180) and floors: a plain pipeline's fixed thresholds.
SAT_MIN, VAL_MIN = 90, 25
MIN_AREA_PX = 12
ROUND_FILL = 0.6  # least share of its enclosing circle a sphere's blob fills


def sphere_centre_px(hsv, name):
    """Centre of the enclosing circle of the colour's largest round blob; None if there is none."""
    mask = np.zeros(hsv.shape[:2], np.uint8)
    for lo, hi in HUES[name]:
        mask |= cv2.inRange(hsv, (lo, SAT_MIN, VAL_MIN), (hi, 255, 255))
    contours, _ = cv2.findContours(mask, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_NONE)
    best, best_area = None, MIN_AREA_PX
    for c in contours:
        area = cv2.contourArea(c)
        if area < best_area:
            continue
        centre, r = cv2.minEnclosingCircle(c)
        # Round blobs only: the open water and the seabed fall in the green and blue windows too.
        if area >= ROUND_FILL * math.pi * r * r:
            best, best_area = centre, area
    return None if best is None else np.array(best, np.float64)


def kabsch(model, measured):
    """R, t with measured ~ R model + t (least squares, proper rotation)."""
    cm, cd = model.mean(0), measured.mean(0)
    H = (model - cm).T @ (measured - cd)
    U, _, Vt = np.linalg.svd(H)
    d = np.sign(np.linalg.det(Vt.T @ U.T))
    R = Vt.T @ np.diag([1.0, 1.0, d]) @ U.T
    return R, cd - R @ cm


def estimate(rig, left, right):
    """T_cl_marker (R, t) from one pair, or None when a sphere is missing in a view."""
    centres = []
    for img, cam in ((left, rig.left), (right, rig.right)):
        hsv = cv2.cvtColor(img, cv2.COLOR_BGR2HSV)
        px = [sphere_centre_px(hsv, name) for name, _, _ in gen.SPHERES]
        if any(p is None for p in px):
            return None
        centres.append(cam.undistort(np.array(px)))
    P1 = np.hstack([np.eye(3), np.zeros((3, 1))])
    P2 = np.hstack([rig.right.R, rig.right.t.reshape(3, 1)])
    X = cv2.triangulatePoints(P1, P2, centres[0].T, centres[1].T)
    measured = (X[:3] / X[3]).T
    model = np.array([c for _, c, _ in gen.SPHERES], np.float64)
    return kabsch(model, measured)


def percentile(values, q):
    return float(np.percentile(values, q)) if values else float("nan")


def summarise(rows):
    found = [r for r in rows if r["found"]]
    right = [r for r in found if r["mm"] < RIGHT_MM and r["deg"] < RIGHT_DEG]
    mm = [r["mm"] for r in found]
    deg = [r["deg"] for r in found]
    return {"pairs": len(rows), "found": len(found), "right": len(right), "wrong": len(found) - len(right),
            "success_rate": len(right) / len(rows) if rows else float("nan"),
            "translation_mm_median": percentile(mm, 50), "translation_mm_p95": percentile(mm, 95),
            "rotation_deg_median": percentile(deg, 50), "rotation_deg_p95": percentile(deg, 95)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--set", required=True, help="folder with manifest.json (render_water_set.py's output)")
    ap.add_argument("--calibration", default=None,
                    help="the rig (default: the set's own file if it has one, else deploy/config's)")
    ap.add_argument("--range-bands-m", default="0.5,1.0,1.3", help="band edges of the true range (m)")
    ap.add_argument("--expect", action="append", default=[], metavar="CONDITION:MIN_RIGHT",
                    help="exit 1 unless the condition has at least this many right pairs (repeatable)")
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--verbose", action="store_true", help="one line per pair")
    args = ap.parse_args()

    manifest_path, manifest, calibration = open_set(args.set, args.calibration)
    rig = gen.Rig(calibration)
    try:
        edges = [float(x) for x in args.range_bands_m.split(",") if x]
    except ValueError:
        sys.exit("--range-bands-m: not a list of numbers: %s" % args.range_bands_m)
    expects = []
    for e in args.expect:
        cond, _, n = e.partition(":")
        if not n.isdigit():
            sys.exit("--expect %s: want CONDITION:MIN_RIGHT" % e)
        expects.append((cond, int(n)))

    rows = []
    for i, pair in enumerate(manifest.get("pairs", [])):
        images = []
        for view in ("left", "right"):
            path = os.path.join(args.set, pair[view])
            img = cv2.imread(path, cv2.IMREAD_COLOR)
            if img is None:
                sys.exit("%s: pair %d: cannot read %s" % (manifest_path, i, path))
            images.append(img)
        row = {"condition": pair["condition"], "image": pair["left"], "range_m": float(pair["range_m"]),
               "found": False, "mm": float("nan"), "deg": float("nan")}
        pose = estimate(rig, *images)
        if pose is not None:
            R, t = pose
            R_true = rotation_from_quat_wxyz(pair["q_cl_marker_wxyz"])
            t_true = np.asarray(pair["t_cl_marker_m"], np.float64)
            row["found"] = True
            row["mm"] = float(np.linalg.norm(t - t_true) * 1000.0)
            cos = (np.trace(R.T @ R_true) - 1.0) / 2.0
            row["deg"] = math.degrees(math.acos(max(-1.0, min(1.0, cos))))
        rows.append(row)
        if args.verbose:
            print("%-34s %s" % (row["image"], "%7.1f mm %6.2f deg" % (row["mm"], row["deg"]) if row["found"]
                                else "  not found"))

    conditions = []
    for c in dict.fromkeys(r["condition"] for r in rows):
        conditions.append(dict(condition=c, **summarise([r for r in rows if r["condition"] == c])))
    conditions.append(dict(condition="all", **summarise(rows)))
    bands = []
    bounds = [0.0] + edges + [None]
    for c in dict.fromkeys(r["condition"] for r in rows):
        for lo, hi in zip(bounds[:-1], bounds[1:]):
            sel = [r for r in rows if r["condition"] == c and r["range_m"] >= lo and (hi is None or r["range_m"] < hi)]
            if sel:
                bands.append(dict(condition=c, range_from_m=lo, range_to_m=hi, **summarise(sel)))

    if args.json:
        print(json.dumps({"set": args.set, "pipeline": "opencv_baseline", "right_translation_mm": RIGHT_MM,
                          "right_rotation_deg": RIGHT_DEG, "conditions": conditions, "by_range": bands}))
    else:
        print("plain OpenCV pipeline on %s: %d pairs; right = within %g mm and %g deg; it has no ok, so "
              "every pose found is its answer" % (args.set, len(rows), RIGHT_MM, RIGHT_DEG))
        print("%-14s %5s %6s %6s %6s  %-13s %-13s" % ("condition", "pairs", "found", "right", "wrong",
                                                      "mm med/p95", "deg med/p95"))
        for s in conditions:
            print("%-14s %5d %6d %6d %6d  %5.1f/%-7.1f %5.2f/%-7.2f" % (
                s["condition"], s["pairs"], s["found"], s["right"], s["wrong"], s["translation_mm_median"],
                s["translation_mm_p95"], s["rotation_deg_median"], s["rotation_deg_p95"]))
        print("\nby the marker's true range from the left camera:")
        for s in bands:
            hi = "" if s["range_to_m"] is None else "%.2f" % s["range_to_m"]
            print("%-14s %.2f-%-5s %5d %6d %6d %6d" % (s["condition"], s["range_from_m"], hi, s["pairs"],
                                                     s["found"], s["right"], s["wrong"]))

    failed = []
    for cond, n in expects:
        got = next((s["right"] for s in conditions if s["condition"] == cond), None)
        if got is None:
            failed.append("%s: no such condition in %s" % (cond, manifest_path))
        elif got < n:
            failed.append("%s: %d right, expected at least %d" % (cond, got, n))
    for f in failed:
        print("opencv_baseline: " + f, file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
