#!/usr/bin/python3
# How precisely a set's images fix each sphere's image centre, read three plain ways against the true
# silhouette: what any estimator can start from in a condition, measured apart from rovctl's code.
"""Per condition: each whole sphere's centre error (px) from its label centroid and from rims found on
its colour contrast and on its brightness, each against the true silhouette.

The rims are read along 48 rays from the true silhouette's centre, with the sphere's and the water's
colour taken from the true disc's core and a ring outside it: the placement is the truth's, so the
figures are the images' own precision, not a search's. A rim's centre error is the first harmonic of
its points' signed distances from the true outline (the zeroth, the mean, is a size offset, and a
pose fit takes one for all spheres). Exit 0, or 1 when an --expect line is not met.
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

import render_water_set as gen  # noqa: E402  (the marker's geometry and the default rig only)
from check_water_set import blob_centroid, open_set, read_cameras, rotation_from_quat_wxyz  # noqa: E402

RAYS = 48
STEP_PX = 0.1
SEARCH_PX = 2.0  # a brightness edge is looked for this close to the colour rim
MIN_GRADIENT = 2.0  # grey levels per pixel, after a 5x5 Gaussian (sigma 1)
METHODS = ("labels", "colour_rim", "brightness_rim")


def true_outline(C, K, D, n=200):
    """The sphere's silhouette: its tangent circle seen from the camera, through cv2.projectPoints."""
    d = float(np.linalg.norm(C))
    axis = C / d
    centre = C * (1 - (gen.SPHERE_RADIUS / d) ** 2)
    radius = gen.SPHERE_RADIUS * math.sqrt(1 - (gen.SPHERE_RADIUS / d) ** 2)
    a = np.cross(axis, [0.0, 1.0, 0.0])
    a /= np.linalg.norm(a)
    b = np.cross(axis, a)
    th = np.linspace(0, 2 * math.pi, n, endpoint=False)
    pts = centre + radius * (np.cos(th)[:, None] * a + np.sin(th)[:, None] * b)
    uv, _ = cv2.projectPoints(pts, np.zeros(3), np.zeros(3), K, D)
    return uv.reshape(-1, 2).astype(np.float32)


def along(field, cx, cy, angle, ts):
    xs = (cx + ts * math.cos(angle)).astype(np.float32).reshape(1, -1)
    ys = (cy + ts * math.sin(angle)).astype(np.float32).reshape(1, -1)
    return cv2.remap(field, xs, ys, cv2.INTER_LINEAR).ravel()


def harmonic_centre_error(devs):
    """|first harmonic| of (signed distance, angle) pairs; None with too few points to fit it."""
    if len(devs) < 8:
        return None
    d = np.array(devs)
    A = np.stack([np.ones(len(d)), np.cos(d[:, 1]), np.sin(d[:, 1])], 1)
    c, *_ = np.linalg.lstsq(A, d[:, 0], rcond=None)
    return float(math.hypot(c[1], c[2]))


def measure_sphere(img, grey, chroma, outline, name):
    """{method: centre error px or None} for one sphere in one view."""
    m = cv2.moments(outline)
    cx, cy = m["m10"] / m["m00"], m["m01"] / m["m00"]
    r = math.sqrt(m["m00"] / math.pi)
    out = dict.fromkeys(METHODS)
    c, _ = blob_centroid(img, name, (cx, cy), r)
    if c is not None:
        out["labels"] = float(math.hypot(c[0] - cx, c[1] - cy))
    h, w = grey.shape
    x0, x1 = max(0, int(cx - 1.6 * r - 8)), min(w, int(cx + 1.6 * r + 9))
    y0, y1 = max(0, int(cy - 1.6 * r - 8)), min(h, int(cy + 1.6 * r + 9))
    yy, xx = np.mgrid[y0:y1, x0:x1]
    rho = np.hypot(xx - cx, yy - cy)
    box = chroma[y0:y1, x0:x1]
    core, ring = box[rho < 0.6 * r], box[(rho > r + 2.5) & (rho < r + 5)]
    if len(core) < 5 or len(ring) < 5:
        return out
    sphere, water = np.median(core, 0), np.median(ring, 0)
    axis = sphere - water
    if float(axis @ axis) < 0.03 ** 2:
        return out
    # Only the box is needed: the rays end 0.6 r + 4 px inside it, beyond the blur's reach.
    contrast = cv2.GaussianBlur(((box - water) @ axis / (axis @ axis)).astype(np.float32), (5, 5), 1.0)
    ts = np.arange(0.5 * r, r + 4.0, STEP_PX)
    colour_devs, bright_devs = [], []
    for angle in np.linspace(0, 2 * math.pi, RAYS, endpoint=False):
        v = along(contrast, cx - x0, cy - y0, angle, ts)
        falls = [ts[j] + (v[j] - 0.5) / (v[j] - v[j + 1]) * STEP_PX
                 for j in range(len(ts) - 1) if v[j] >= 0.5 > v[j + 1]]
        if not falls:
            continue
        t_colour = falls[-1]
        g = np.abs(np.gradient(along(grey, cx, cy, angle, ts), STEP_PX))
        near = np.abs(ts - t_colour) < SEARCH_PX
        t_bright = float(ts[near][np.argmax(g[near])]) if near.any() and g[near].max() >= MIN_GRADIENT else None
        for t, devs in ((t_colour, colour_devs), (t_bright, bright_devs)):
            if t is not None:
                p = (float(cx + t * math.cos(angle)), float(cy + t * math.sin(angle)))
                devs.append((-cv2.pointPolygonTest(outline, p, True), angle))
    out["colour_rim"] = harmonic_centre_error(colour_devs)
    out["brightness_rim"] = harmonic_centre_error(bright_devs)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--set", required=True, help="folder with manifest.json (render_water_set.py's output)")
    ap.add_argument("--calibration", default=None,
                    help="the rig (default: the set's own file if it has one, else deploy/config's)")
    ap.add_argument("--conditions", default="", help="comma-separated; default every condition in the set")
    ap.add_argument("--expect", action="append", default=[], metavar="CONDITION:METHOD:MAX_PX",
                    help="exit 1 unless the condition's median centre error by the method (%s) is at most "
                         "MAX_PX (repeatable)" % ", ".join(METHODS))
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    expects = []
    for e in args.expect:
        parts = e.split(":")
        try:
            cond, method, limit = parts[0], parts[1], float(parts[2])
        except (IndexError, ValueError):
            sys.exit("--expect %s: want CONDITION:METHOD:MAX_PX" % e)
        if len(parts) != 3 or method not in METHODS:
            sys.exit("--expect %s: want CONDITION:METHOD:MAX_PX with METHOD one of %s" % (e, ", ".join(METHODS)))
        expects.append((cond, method, limit))

    manifest_path, manifest, calibration = open_set(args.set, args.calibration)
    cams = read_cameras(calibration)
    wanted = [c for c in args.conditions.split(",") if c]
    pairs = manifest.get("pairs", [])
    unknown = [c for c in wanted if c not in {p["condition"] for p in pairs}]
    if unknown:
        sys.exit("--conditions: not in %s: %s" % (manifest_path, ", ".join(unknown)))

    errors = {}  # condition -> method -> [px]
    for i, pair in enumerate(pairs):
        if wanted and pair["condition"] not in wanted:
            continue
        R = rotation_from_quat_wxyz(pair["q_cl_marker_wxyz"])
        t = np.asarray(pair["t_cl_marker_m"], np.float64)
        for view, (K, D, Rc, tc) in cams.items():
            path = os.path.join(args.set, pair[view])
            img = cv2.imread(path, cv2.IMREAD_COLOR)
            if img is None:
                sys.exit("%s: pair %d: cannot read %s" % (manifest_path, i, path))
            f = img.astype(np.float32)
            grey = cv2.GaussianBlur(cv2.cvtColor(img, cv2.COLOR_BGR2GRAY).astype(np.float32), (5, 5), 1.0)
            chroma = f / (f.sum(2, keepdims=True) + 10.0)  # the 10 keeps dark pixels' noise bounded
            for name, centre_m, _ in gen.SPHERES:
                if pair["spheres_visible_" + view][name] < 0.99:
                    continue  # whole spheres only: a hidden part moves every reading
                C = Rc @ (R @ np.asarray(centre_m, np.float64) + t) + tc
                got = measure_sphere(img, grey, chroma, true_outline(C, K, D), name)
                per = errors.setdefault(pair["condition"], {m: [] for m in METHODS + ("spheres",)})
                per["spheres"].append(1)
                for method, e in got.items():
                    if e is not None:
                        per[method].append(e)

    rows = []
    for cond, per in errors.items():
        row = {"condition": cond, "spheres": len(per["spheres"])}
        for method in METHODS:
            v = per[method]
            row[method] = {"read": len(v), "median_px": float(np.median(v)) if v else None,
                           "p90_px": float(np.percentile(v, 90)) if v else None}
        rows.append(row)
    failed = []
    by_condition = {row["condition"]: row for row in rows}
    for cond, method, limit in expects:
        median = by_condition.get(cond, {}).get(method, {}).get("median_px")
        if median is None:
            failed.append("%s: no sphere read by %s" % (cond, method))
        elif median > limit:
            failed.append("%s: %s centre error median %.3f px, over %g px" % (cond, method, median, limit))
    if args.json:
        print(json.dumps({"set": args.set, "conditions": rows}))
    else:
        print_table(args.set, rows)
    for line in failed:
        print("expected: " + line, file=sys.stderr)
    sys.exit(1 if failed else 0)


def print_table(set_dir, rows):
    print("sphere centre error against the true silhouette on %s (px: median / p90, spheres read)" % set_dir)
    print("%-14s %7s  %-22s %-22s %-22s" % ("condition", "spheres", *METHODS))
    for row in rows:
        cells = []
        for method in METHODS:
            m = row[method]
            cells.append("%.2f / %.2f  (%d)" % (m["median_px"], m["p90_px"], m["read"]) if m["read"] else "-")
        print("%-14s %7d  %-22s %-22s %-22s" % (row["condition"], row["spheres"], *cells))


if __name__ == "__main__":
    main()
