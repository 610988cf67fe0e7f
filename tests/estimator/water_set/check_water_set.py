#!/usr/bin/python3
# Self-check of the water-set generator: one clear pair rendered afresh must put every sphere where
# cv2.projectPoints says it is, and the shipped sample's manifest must be complete.
"""Exit 0 when the generator's geometry and the shipped sample are sound, 1 otherwise (with reasons)."""

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
import shutil  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402

import cv2  # noqa: E402
import numpy as np  # noqa: E402

import render_water_set as gen  # noqa: E402

DEFAULT_SAMPLE = os.path.normpath(os.path.join(HERE, "..", "..", "data", "water_set"))
TOLERANCE_PX = 1.5

# Hue windows (OpenCV's 0..180) for the segmentation; independent of how the generator draws.
HUES = {"red": [(0, 12), (165, 180)], "green": [(40, 90)], "blue": [(100, 135)]}


def check_pose():
    """A fixed, ordinary pose: 0.7 m ahead, turned a little, all spheres well inside both views."""
    R = gen.rot_y(math.radians(12)) @ gen.rot_x(math.radians(-9)) @ gen.rot_z(math.radians(5))
    return gen.Pose(R, [0.04, 0.03, 0.70])


def rotation_from_quat_wxyz(q_wxyz):
    """The manifest's unit quaternion as a matrix, written apart from the generator's inverse."""
    w, x, y, z = q_wxyz
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def projected_truth(K, D, R_cam, t_cam, q_wxyz, t_m):
    """Sphere centres through cv2.projectPoints with the calibration, from the manifest's truth only."""
    R = R_cam @ rotation_from_quat_wxyz(q_wxyz)
    t = R_cam @ np.asarray(t_m, np.float64) + t_cam
    rvec, _ = cv2.Rodrigues(R)
    pts = np.array([c for _, c, _ in gen.SPHERES], np.float64)
    uv, _ = cv2.projectPoints(pts, rvec, t, K, D)
    return uv.reshape(-1, 2), (R @ pts.T).T + t


def blob_centroid(img, name, centre, radius_px):
    """Centroid of the sphere's colour blob near where it should be (hole-filled, largest component)."""
    h, w = img.shape[:2]
    hsv = cv2.cvtColor(img, cv2.COLOR_BGR2HSV)
    mask = np.zeros((h, w), np.uint8)
    for lo, hi in HUES[name]:
        mask |= cv2.inRange(hsv, (lo, 90, 25), (hi, 255, 255))
    roi = np.zeros_like(mask)
    cv2.circle(roi, (int(round(centre[0])), int(round(centre[1]))), int(math.ceil(2.5 * radius_px + 4)), 255, -1)
    mask &= roi
    n, labels, stats, _ = cv2.connectedComponentsWithStats(mask, connectivity=8)
    if n < 2:
        return None, 0
    best = 1 + int(np.argmax(stats[1:, cv2.CC_STAT_AREA]))
    blob = (labels == best).astype(np.uint8) * 255
    contours, _ = cv2.findContours(blob, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_NONE)
    filled = np.zeros_like(blob)
    cv2.drawContours(filled, contours, -1, 255, -1)  # the specular highlight is unsaturated: fill it
    m = cv2.moments(filled, binaryImage=True)
    if m["m00"] == 0:
        return None, 0
    return np.array([m["m10"] / m["m00"], m["m01"] / m["m00"]]), int(m["m00"])


def open_set(folder, calibration=None):
    """(manifest path, manifest, calibration path) of a set, for the scripts that score one; exits
    naming the file when the manifest cannot be read. The calibration: the given one, else the set's
    own file if it has one, else deploy/config's."""
    manifest_path = os.path.join(folder, "manifest.json")
    try:
        with open(manifest_path) as f:
            manifest = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit("%s: cannot read: %s" % (manifest_path, e))
    if calibration is None:
        own = os.path.join(folder, manifest.get("calibration", ""))
        calibration = own if manifest.get("calibration") and os.path.isfile(own) else gen.DEFAULT_CALIBRATION
    return manifest_path, manifest, calibration


def read_cameras(calibration):
    """{view: (K, D, R, t)} from an OpenCV stereo calibration, x_view = R x_left + t; read apart from
    the generator. Exits naming the file when a node is missing."""
    nodes = ("K1", "D1", "K2", "D2", "R", "T")
    try:
        fs = cv2.FileStorage(calibration, cv2.FILE_STORAGE_READ)
    except (cv2.error, SystemError):  # a file OpenCV cannot parse raises rather than opening empty
        sys.exit("%s: not a stereo calibration (%s)" % (calibration, ", ".join(nodes)))
    if not fs.isOpened() or any(fs.getNode(n).empty() for n in nodes):
        sys.exit("%s: not a stereo calibration (%s)" % (calibration, ", ".join(nodes)))
    cams = {"left": (fs.getNode("K1").mat(), fs.getNode("D1").mat(), np.eye(3), np.zeros(3)),
            "right": (fs.getNode("K2").mat(), fs.getNode("D2").mat(), fs.getNode("R").mat(),
                      fs.getNode("T").mat().ravel())}
    fs.release()
    return cams


def check_render(calibration, keep):
    errors = []
    rig = gen.Rig(calibration)
    out = keep or tempfile.mkdtemp(prefix="water_check_")
    t0 = time.time()
    try:
        entry = gen.make_pair(rig, "clear", 0, 1, out, pose_override=check_pose())
        took = time.time() - t0
        cams = read_cameras(calibration)
        worst = 0.0
        for view, (K, D, Rc, tc) in cams.items():
            img = cv2.imread(os.path.join(out, entry[view]), cv2.IMREAD_COLOR)
            if img is None or img.shape != (480, 640, 3):
                errors.append("%s image missing or not 640x480 BGR" % view)
                continue
            uv, centres = projected_truth(K, D, Rc, tc, entry["q_cl_marker_wxyz"], entry["t_cl_marker_m"])
            for i, (name, _, _) in enumerate(gen.SPHERES):
                r_px = K[0, 0] * gen.SPHERE_RADIUS / centres[i][2]
                c, area = blob_centroid(img, name, uv[i], r_px)
                if c is None:
                    errors.append("%s view: no %s blob found near (%.1f, %.1f)" % (view, name, uv[i][0], uv[i][1]))
                    continue
                err = float(np.linalg.norm(c - uv[i]))
                worst = max(worst, err)
                expect_area = math.pi * r_px * r_px
                print("  %-5s %-5s truth (%7.2f, %7.2f)  blob (%7.2f, %7.2f)  error %.2f px  area %d / %.0f px"
                      % (view, name, uv[i][0], uv[i][1], c[0], c[1], err, area, expect_area))
                if err > TOLERANCE_PX:
                    errors.append("%s view: %s blob centroid is %.2f px from the projected truth (limit %.1f)"
                                  % (view, name, err, TOLERANCE_PX))
                if not 0.7 * expect_area < area < 1.3 * expect_area:
                    errors.append("%s view: %s blob area %d px, expected about %.0f" % (view, name, area,
                                                                                         expect_area))
        print("rendered one clear pair in %.1f s; worst centroid error %.2f px" % (took, worst))
    finally:
        if not keep:
            shutil.rmtree(out, ignore_errors=True)
    return errors


def check_manifest(folder):
    errors = []
    path = os.path.join(folder, "manifest.json")
    try:
        with open(path) as f:
            man = json.load(f)
    except (OSError, ValueError) as e:
        return ["cannot read %s: %s" % (path, e)]
    for key in ("calibration", "generator", "seed", "pairs"):
        if key not in man:
            errors.append("manifest lacks '%s'" % key)
    pairs = man.get("pairs", [])
    if not pairs:
        errors.append("manifest lists no pairs")
    seen = set()
    for n, p in enumerate(pairs):
        where = "pair %d (%s)" % (n, p.get("condition", "?"))
        if p.get("condition") not in gen.CONDITIONS:
            errors.append("%s: unknown condition" % where)
        seen.add(p.get("condition"))
        for view in ("left", "right"):
            rel = p.get(view)
            if not isinstance(rel, str):
                errors.append("%s: no %s image" % (where, view))
                continue
            img = cv2.imread(os.path.join(folder, rel), cv2.IMREAD_UNCHANGED)
            if img is None:
                errors.append("%s: %s missing or unreadable" % (where, rel))
            elif img.shape != (480, 640, 3) or img.dtype != np.uint8:
                errors.append("%s: %s is %s %s, not 640x480 8-bit BGR" % (where, rel, img.shape, img.dtype))
            vis = p.get("spheres_visible_" + view)
            if not isinstance(vis, dict) or any(not isinstance(vis.get(s), (int, float)) or not 0 <= vis[s] <= 1
                                                for s in ("red", "green", "blue")):
                errors.append("%s: spheres_visible_%s missing or out of 0..1" % (where, view))
        t = p.get("t_cl_marker_m")
        q = p.get("q_cl_marker_wxyz")
        if not (isinstance(t, list) and len(t) == 3 and all(isinstance(v, (int, float)) and math.isfinite(v) for v in t)):
            errors.append("%s: t_cl_marker_m is not three numbers" % where)
        elif not isinstance(p.get("range_m"), (int, float)) or abs(p["range_m"] - math.sqrt(sum(v * v for v in t))) > 1e-3:
            errors.append("%s: range_m missing or not |t|" % where)
        if not (isinstance(q, list) and len(q) == 4 and all(isinstance(v, (int, float)) for v in q)
                and abs(math.sqrt(sum(v * v for v in q)) - 1) < 1e-6):
            errors.append("%s: q_cl_marker_wxyz is not a unit quaternion" % where)
        if not isinstance(p.get("notes"), str):
            errors.append("%s: no notes" % where)
    missing = [c for c in gen.DEFAULT_CONDITIONS if c not in seen]
    if missing:
        errors.append("no pairs for: %s" % ", ".join(missing))
    print("sample manifest %s: %d pairs, %d conditions" % (path, len(pairs), len(seen)))
    return errors


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--sample", default=DEFAULT_SAMPLE, help="shipped sample folder (with manifest.json)")
    ap.add_argument("--calibration", default=gen.DEFAULT_CALIBRATION)
    ap.add_argument("--keep", help="render the check pair into this folder and keep it")
    args = ap.parse_args()
    if shutil.which("povray") is None:
        print("FAIL: povray not found (Debian package 'povray')")
        return 1
    errors = check_render(args.calibration, args.keep) + check_manifest(args.sample)
    for e in errors:
        print("FAIL: " + e)
    print("water set check: %s" % ("FAILED" if errors else "OK"))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
