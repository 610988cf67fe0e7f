#!/usr/bin/python3
# Self-check of the rendered sequences: the committed sample is a recording the replay reads (header,
# stamps, files), its truth is consistent, every whole sphere's blob sits on its projected true centre,
# every hidden sphere has no blob, and one frame rendered afresh gives the same images and truth.
"""Exit 0 when the sequence generator and the shipped sequence sample are sound, 1 otherwise (with reasons)."""

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

import check_water_set as chk  # noqa: E402
import render_sequence as seqgen  # noqa: E402
import render_water_set as gen  # noqa: E402

DEFAULT_SAMPLE = os.path.normpath(os.path.join(HERE, "..", "..", "data", "water_sequences"))
WHOLE = 0.999  # a sphere this visible (and with no bubble on its sight line) must show where the truth says
FRAME_PERIOD_NS = 1e9 / seqgen.FRAME_RATE_HZ


def read_frames_csv(folder):
    """Rows of a recording's frames.csv, read apart from the generator; (rows, errors)."""
    path = os.path.join(folder, "frames.csv")
    with open(path) as f:
        lines = f.read().split("\n")
    if lines[0] != seqgen.FRAMES_CSV_HEADER:
        return [], ["%s: header is %r" % (path, lines[0])]
    rows, errors = [], []
    for n, line in enumerate(lines[1:], 2):
        if not line:
            continue
        fields = line.split(",")
        if len(fields) != 6:
            errors.append("%s:%d: %d fields, not 6" % (path, n, len(fields)))
            continue
        rows.append({"sequence": int(fields[0]), "left_ns": int(fields[1]), "right_ns": int(fields[2]),
                     "left": fields[3], "right": fields[4]})
    return rows, errors


def check_recording(folder, seq):
    rows, errors = read_frames_csv(folder)
    frames = seq.get("frames", [])
    if len(rows) != len(frames):
        errors.append("%s: frames.csv has %d rows, sequence.json %d frames" % (folder, len(rows), len(frames)))
    last = None
    for row, fr in zip(rows, frames):
        where = "%s frame %d" % (os.path.basename(folder), fr["frame"])
        if row["sequence"] != fr["frame"] or row["left"] != fr["left"] or row["right"] != fr["right"]:
            errors.append("%s: frames.csv row and sequence.json disagree" % where)
        due_ns = seqgen.FIRST_STAMP_NS + fr["frame"] * FRAME_PERIOD_NS
        if row["left_ns"] != row["right_ns"] or abs(row["left_ns"] - due_ns) > 1:
            errors.append("%s: stamps %d/%d are not the 30 Hz frame's" % (where, row["left_ns"], row["right_ns"]))
        if last is not None and row["left_ns"] <= last:
            errors.append("%s: stamp goes backwards" % where)
        last = row["left_ns"]
        for rel in (row["left"], row["right"]):
            if rel.startswith("/") or ".." in rel.split("/") or not os.path.isfile(os.path.join(folder, rel)):
                errors.append("%s: %s missing or not a plain relative path" % (where, rel))
    return errors


def check_truth(seq):
    """T_cl_marker and the world pose of the camera say the same thing; quaternions are unit."""
    errors = []
    for fr in seq["frames"]:
        R_cm = chk.rotation_from_quat_wxyz(fr["q_cl_marker_wxyz"])
        R_wc = chk.rotation_from_quat_wxyz(fr["q_world_cam_wxyz"])
        t = -R_wc.T @ np.asarray(fr["p_world_cam_m"])
        if np.abs(R_cm - R_wc.T).max() > 1e-6 or np.abs(t - np.asarray(fr["t_cl_marker_m"])).max() > 1e-6:
            errors.append("frame %d: T_cl_marker and the camera's world pose disagree" % fr["frame"])
        if not 0.3 < fr["range_m"] < 1.5 or len(fr["omega_cam_radps"]) != 3:
            errors.append("frame %d: range or angular rate out of shape" % fr["frame"])
    return errors


def check_blobs(folder, seq, cams):
    """Whole spheres: blob centroid within chk.TOLERANCE_PX of the projected truth; hidden: no blob."""
    errors, worst, n_whole, n_hidden = [], 0.0, 0, 0
    for fr in seq["frames"]:
        for view, (K, D, Rc, tc) in cams.items():
            img = cv2.imread(os.path.join(folder, fr[view]), cv2.IMREAD_COLOR)
            if img is None or img.shape != (480, 640, 3):
                errors.append("frame %d: %s image missing or not 640x480 BGR" % (fr["frame"], view))
                continue
            uv, centres = chk.projected_truth(K, D, Rc, tc, fr["q_cl_marker_wxyz"], fr["t_cl_marker_m"])
            vis = fr["visible_fraction_" + view]
            for i, (name, _, _) in enumerate(gen.SPHERES):
                r_px = K[0, 0] * gen.SPHERE_RADIUS / centres[i][2]
                c, area = chk.blob_centroid(img, name, uv[i], r_px)
                where = "frame %d %s %s" % (fr["frame"], view, name)
                if fr.get("hidden_sphere") == name and vis[name] != 0.0:
                    errors.append("%s: flagged hidden but %.3f visible" % (where, vis[name]))
                if vis[name] == 0.0:
                    n_hidden += 1
                    if c is not None and area > 0.05 * math.pi * r_px * r_px:
                        errors.append("%s: hidden, yet a %d px blob shows" % (where, area))
                elif vis[name] >= WHOLE and fr.get("bubbles_on_sight_lines", 0) == 0:
                    n_whole += 1
                    err = float("inf") if c is None else float(np.linalg.norm(c - uv[i]))
                    worst = max(worst, err)
                    if err > chk.TOLERANCE_PX:
                        errors.append("%s: blob centroid %.2f px from the projected truth (limit %.1f)"
                                      % (where, err, chk.TOLERANCE_PX))
    print("  %d whole sphere views within %.2f px of the projected truth, %d hidden ones without a blob"
          % (n_whole, worst, n_hidden))
    return errors


def check_rerender(folder, man, seq, frame):
    """Frame `frame` rendered afresh from (seed, kind, index, frame) alone: the same pixels and truth."""
    if man.get("draft"):
        gen.RENDER.update(gen.DRAFT_RENDER)
    rig = gen.Rig(os.path.join(folder, seq["calibration"]))
    old = next(fr for fr in seq["frames"] if fr["frame"] == frame)
    out = tempfile.mkdtemp(prefix="water_seq_check_")
    errors = []
    try:
        for side in ("left", "right"):
            os.makedirs(os.path.join(out, side))
        t0 = time.time()
        s = seqgen.Sequence(rig, seq["kind"], seq["index"], seq["seed"], seq["trajectory_frames"])
        new = seqgen.render_frame(s, frame, old["row"], out)
        print("  re-rendered %s frame %d in %.1f s" % (os.path.basename(folder), frame, time.time() - t0))
        for view in ("left", "right"):
            a = cv2.imread(os.path.join(folder, old[view]), cv2.IMREAD_UNCHANGED)
            b = cv2.imread(os.path.join(out, new[view]), cv2.IMREAD_UNCHANGED)
            if a is None or b is None or a.shape != b.shape or not np.array_equal(a, b):
                diff = "unreadable" if a is None or b is None else "%d px differ" % int((a != b).any(axis=2).sum())
                errors.append("frame %d %s: re-rendered image differs from the sample (%s)" % (frame, view, diff))
        if json.loads(json.dumps(new)) != old:
            errors.append("frame %d: re-rendered truth differs from the sample's" % frame)
    finally:
        shutil.rmtree(out, ignore_errors=True)
    return errors


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--sample", default=DEFAULT_SAMPLE, help="shipped sample folder (with sequences.json)")
    ap.add_argument("--frame", type=int, help="frame of the first sequence to re-render (default: its first frame "
                    "with a hidden sphere, else its first)")
    args = ap.parse_args()
    if shutil.which("povray") is None:
        print("FAIL: povray not found (Debian package 'povray')")
        return 1
    path = os.path.join(args.sample, "sequences.json")
    try:
        with open(path) as f:
            man = json.load(f)
    except (OSError, ValueError) as e:
        print("FAIL: cannot read %s: %s" % (path, e))
        return 1
    errors = []
    seqs = []
    for entry in man.get("sequences", []):
        folder = os.path.join(args.sample, entry["path"])
        with open(os.path.join(folder, "sequence.json")) as f:
            seq = json.load(f)
        seqs.append((folder, seq))
        if len(seq["frames"]) != entry["frames"] or entry["frames_done"] != entry["frames"]:
            errors.append("%s: %d of %d frames" % (folder, len(seq["frames"]), entry["frames"]))
        print("%s: %s, %d frames" % (entry["path"], seq["kind"], len(seq["frames"])))
        errors += check_recording(folder, seq)
        errors += check_truth(seq)
        errors += check_blobs(folder, seq, chk.read_cameras(os.path.join(folder, seq["calibration"])))
    if not seqs:
        errors.append("%s lists no sequences" % path)
    else:
        folder, seq = seqs[0]
        frame = args.frame
        if frame is None:
            frame = next((fr["frame"] for fr in seq["frames"] if fr.get("hidden_sphere")), seq["frames"][0]["frame"])
        errors += check_rerender(folder, man, seq, frame)
    for e in errors:
        print("FAIL: " + e)
    print("water sequence check: %s" % ("FAILED" if errors else "OK"))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
