#!/usr/bin/python3
# Rendered stereo sequences for scoring a pose filter frame by frame: a docking approach at 30 Hz through
# the water set's scene, water, lamps and real lenses, written as `rovctl record` recordings with the truth.
"""Render docking-approach stereo sequences (POV-Ray) as recordings, with per-frame truth.

Each sequence is a camera trajectory relative to the marker: the left camera comes in from about 1.3 m to
about 0.45 m with a few cm of sway and 1-3 deg of yaw/pitch wobble, and one event per kind: `hidden` (a bar
slides in front of one sphere and hides it wholly in both views for 30 frames), `bubbles` (a rising bubble
cloud crosses the lines of sight), `turbid` (Jerlov 5C water plus a hidden sphere), `clear` (no event).
Scene, water, lighting, lenses, bars and visibility are render_water_set.py's. See README.md beside this file.
"""

import argparse
import concurrent.futures
import json
import math
import os
import shutil
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
if __name__ == "__main__":
    sys.dont_write_bytecode = True  # importing the helpers must not leave __pycache__ in the tree
    sys.path.insert(0, HERE)
    import debian_python

    debian_python.require_opencv()

import cv2  # noqa: E402
import numpy as np  # noqa: E402

import render_water_set as gen  # noqa: E402

KINDS = ["clear", "hidden", "bubbles", "turbid"]
FRAME_RATE_HZ = 30.0
FIRST_STAMP_NS = 1000000000
# Frames the bar holds still in front of the sphere: with the end of its slide in and the start of its slide out,
# the sphere is wholly hidden in both views for 31-33 frames, about 1 s (frames with a hidden sphere are flagged
# from the sphere-ID renders, not from this plan).
HIDE_FRAMES = 28
SWEEP_FRAMES = 8  # frames the bar takes to slide in front of the sphere, and to slide away
BUBBLE_SECONDS = 1.0  # about how long the cloud sits on the lines of sight
IN_VIEW_MARGIN_PX = 6.0  # every sphere's outline at least this far inside both images at every frame
AIM_MARKER = np.array([0.0, 0.0, -0.0133])  # the spheres' centroid: what the rig's midpoint looks at
FRAMES_CSV_HEADER = "sequence,left_stamp_ns,right_stamp_ns,left_file,right_file,exposure_ns"
SEQUENCE_GENERATOR = "render_sequence.py"


def sequence_rng(seed, kind, index):
    return np.random.default_rng([int(seed), 46, KINDS.index(kind), int(index)])


def frame_stamp_ns(frame):
    return FIRST_STAMP_NS + int(round(frame * 1e9 / FRAME_RATE_HZ))


def smooth_step(x):
    """0 below 0, 1 above 1, a half cosine between: the bar's slide, with no jolt at either end."""
    x = min(1.0, max(0.0, x))
    return 0.5 - 0.5 * math.cos(math.pi * x)


def draw_wave(rng, amplitude, frequency_hz, unit=float):
    amp = unit(rng.uniform(*amplitude))
    return amp, float(rng.uniform(*frequency_hz)), float(rng.uniform(0, 2 * math.pi))


class Trajectory:
    """The left camera's pose in the marker (world) frame over time: x_world = R_wc(t) x_cam + c(t).

    An approach along a line that looks at the spheres' centroid from a little off the marker's axis, the
    range eased from d0 to d1 (mostly constant speed, gentle at both ends), a slow lateral sway of a few cm
    and a yaw/pitch wobble of 1-3 deg at 0.5-1.5 Hz (plus a little roll), as of a vehicle in a current.
    """

    def __init__(self, rig, rng, frames):
        self.duration_s = (frames - 1) / FRAME_RATE_HZ
        self.d0 = float(rng.uniform(1.2, 1.4))
        self.d1 = float(rng.uniform(0.40, 0.50))
        self.R_base = gen.rot_y(math.radians(rng.uniform(-10, 10))) @ gen.rot_x(math.radians(rng.uniform(-7, 7)))
        # Waves as (amplitude, frequency Hz, phase): the sway across x and y of the approach in metres, then
        # the yaw, pitch and roll wobble in radians.
        self.sway = [draw_wave(rng, (0.015, 0.035), (0.2, 0.5)) for _ in range(2)]
        self.wobble = [draw_wave(rng, (1.0, 3.0), (0.5, 1.5), math.radians) for _ in range(2)]
        self.roll = draw_wave(rng, (0.3, 1.0), (0.3, 0.8), math.radians)
        # Half the baseline: the rig's midpoint, not the left camera, is aimed at the marker.
        self.mid_cam = 0.5 * (-rig.right.R.T @ rig.right.t)

    @staticmethod
    def _wave(p, t):
        a, f, ph = p
        return a * math.sin(2 * math.pi * f * t + ph)

    def range_m(self, t):
        x = min(1.0, max(0.0, t / self.duration_s)) if self.duration_s > 0 else 0.0
        s = 0.7 * x + 0.3 * (0.5 - 0.5 * math.cos(math.pi * x))
        return self.d0 + (self.d1 - self.d0) * s

    def R_wc(self, t):
        yaw, pitch, roll = (self._wave(p, t) for p in (self.wobble[0], self.wobble[1], self.roll))
        return self.R_base @ gen.rot_y(yaw) @ gen.rot_x(pitch) @ gen.rot_z(roll)

    def c_world(self, t):
        sx, sy = (self._wave(p, t) for p in self.sway)
        mid = AIM_MARKER - self.range_m(t) * self.R_base[:, 2] + self.R_base @ np.array([sx, sy, 0.0])
        return mid - self.R_wc(t) @ self.mid_cam

    def pose(self, t):
        """The marker in the left camera (gen.Pose: x_left = R x_marker + t)."""
        R = self.R_wc(t)
        return gen.Pose(R.T, -R.T @ self.c_world(t))

    def omega_cam_radps(self, t, h=1e-4):
        """Angular rate of the camera in its own frame, as a gyro on it reads it."""
        dR = self.R_wc(t - h).T @ self.R_wc(t + h)
        rvec, _ = cv2.Rodrigues(dR)
        return rvec.ravel() / (2 * h)


def frame_time(frame):
    return frame / FRAME_RATE_HZ


# ----------------------------------------------------------------------------------------------------
# Events


class HiddenSphere:
    """A horizontal bar in front of one sphere, coming in from that sphere's outer side: its rounded tip
    slides over the sphere in SWEEP_FRAMES, stays HIDE_FRAMES with the sphere wholly behind it in both
    views (ray casts), and slides back out. Placed by ray casts (gen.occluded_fraction) over every frame of the
    trajectory; the images' visible fractions are then measured from sphere-ID renders."""

    def __init__(self, rig, rng, traj, frames):
        lo, hi = SWEEP_FRAMES + 2, frames - HIDE_FRAMES - SWEEP_FRAMES - 2
        if hi < lo:
            raise SystemExit("a hidden-sphere sequence needs at least %d frames" % (HIDE_FRAMES + 2 * SWEEP_FRAMES + 4))
        self.rig, self.traj = rig, traj
        self.poses = [traj.pose(frame_time(f)) for f in range(frames)]
        for _ in range(300):
            self.start = int(rng.integers(lo, hi + 1))  # first frame of the hold
            self.target = int(rng.integers(3))
            S = np.asarray(gen.SPHERES[self.target][1])
            out = [-1.0, 1.0, float(rng.choice([-1.0, 1.0]))][self.target]
            phi = math.radians(rng.uniform(-10, 10))
            self.w = np.array([out * math.cos(phi), math.sin(phi), 0.0])
            self.rho = float(rng.uniform(0.028, 0.036))
            self.gap = float(rng.uniform(0.035, 0.06))
            self.centre = np.array([S[0], S[1], S[2] - self.gap])
            self.reach_in = float(rng.uniform(0.0, 0.012))
            self.reach_out = -(gen.SPHERE_RADIUS + self.rho + 0.07)
            if self._planned_ok(frames):
                return
        raise RuntimeError("hidden: no bar layout found")

    def reach(self, frame):
        """How far past the sphere's centre (inwards) the tip's centre is at `frame`."""
        a = smooth_step((frame - (self.start - SWEEP_FRAMES)) / SWEEP_FRAMES)
        b = smooth_step((frame - (self.start + HIDE_FRAMES)) / SWEEP_FRAMES)
        return self.reach_out + (self.reach_in - self.reach_out) * (a - b)

    def bar(self, frame, grow=0.0):
        return {"p0": self.centre - self.w * self.reach(frame), "w": self.w, "rho": self.rho + grow, "length": 1.2}

    def planned(self, frame, cam, sphere, grow=0.0):
        pc = self.poses[frame].in_cam(cam)
        return gen.occluded_fraction(cam, gen.sphere_centres(pc)[sphere], gen.bars_in_cam(pc, [self.bar(frame, grow)]),
                                     n=61)

    def _planned_ok(self, frames):
        hold = range(self.start, self.start + HIDE_FRAMES)
        moving = set(range(self.start - SWEEP_FRAMES, self.start + HIDE_FRAMES + SWEEP_FRAMES))
        for f in hold:  # wholly hidden in both views, with some bar to spare
            if any(self.planned(f, cam, self.target, -0.004) < 1.0 for cam in self.rig.cams):
                return False
        for f in range(frames):
            for cam in self.rig.cams:
                for s in range(3):
                    if (s != self.target or f not in moving) and self.planned(f, cam, s, 0.004) > 0.0:
                        return False
        return True

    def spec_items(self, frame):
        return {"bars": [self.bar(frame)]}

    def needs_masks(self, frame, cam):
        """Whether the bar comes near any sphere in this view (else nothing is hidden, by the ray casts)."""
        return any(self.planned(frame, cam, s, 0.004) > 0.0 for s in range(3))

    def describe(self):
        return {"type": "hidden_sphere", "sphere": gen.SPHERES[self.target][0],
                "bar_hold_frames": [self.start, self.start + HIDE_FRAMES - 1],
                "sweep_frames": SWEEP_FRAMES, "bar_radius_m": round(self.rho, 4),
                "bar_gap_in_front_m": round(self.gap, 4)}


class BubbleCloud:
    """A cloud of air bubbles (render_water_set's bubble material) between the camera and the station,
    rising at 0.2-0.3 m/s with a little zig-zag, centred on the lines of sight to the spheres at its
    middle frame, so it crosses them in about BUBBLE_SECONDS."""

    def __init__(self, rig, rng, traj, frames):
        self.rig, self.traj = rig, traj
        self.mid = int(rng.integers(int(0.35 * frames), int(0.6 * frames) + 1))
        t_mid = frame_time(self.mid)
        cam_mid = traj.c_world(t_mid) + traj.R_wc(t_mid) @ traj.mid_cam
        toward = (cam_mid - AIM_MARKER) / np.linalg.norm(cam_mid - AIM_MARKER)
        self.centre = AIM_MARKER + toward * float(rng.uniform(0.13, 0.25))
        self.rise_mps = float(rng.uniform(0.2, 0.3))
        height = self.rise_mps * BUBBLE_SECONDS * 0.6
        n = int(rng.integers(90, 150))
        self.bubbles = []  # (position at the middle frame, radius, speed factor, zig-zag amplitude, Hz, phase)
        for _ in range(n):
            p = self.centre + np.array([rng.uniform(-0.12, 0.12), rng.uniform(-height / 2, height / 2),
                                        rng.uniform(-0.03, 0.03)])
            r = float(min(0.004, rng.lognormal(math.log(0.0015), 0.5)))  # a vent's cloud: coarser than the set's
            self.bubbles.append((p, r, float(rng.uniform(0.85, 1.15)), float(rng.uniform(0.001, 0.003)),
                                 float(rng.uniform(2.0, 4.0)), float(rng.uniform(0, 2 * math.pi))))

    def positions(self, frame):
        dt = frame_time(frame) - frame_time(self.mid)
        out = []
        for p, r, k, a, f, ph in self.bubbles:
            wig = a * math.sin(2 * math.pi * f * dt + ph)
            out.append((p + np.array([wig, -self.rise_mps * k * dt, 0.0]), r))  # marker frame: -y is up
        return out

    def spec_items(self, frame):
        return {"bubbles": [(p, r) for p, r in self.positions(frame) if gen.far_from_spheres(p, r)]}

    def on_sight_lines(self, frame):
        """Bubbles that cut the cone from either camera to any sphere."""
        pose = self.traj.pose(frame_time(frame))
        count = 0
        bubbles = self.positions(frame)
        for cam in self.rig.cams:
            pc = pose.in_cam(cam)
            o = -pc.R.T @ pc.t  # this camera's centre in the marker frame
            for p, r in bubbles:
                for _, s, _ in gen.SPHERES:
                    axis = np.asarray(s) - o
                    length = np.linalg.norm(axis)
                    u = float((p - o) @ axis) / length
                    if 0 < u < length:
                        perp = np.linalg.norm((p - o) - u * axis / length)
                        if perp < r + gen.SPHERE_RADIUS * u / length:
                            count += 1
                            break
        return count

    def needs_masks(self, frame, cam):
        return False

    def describe(self):
        return {"type": "bubble_cloud", "middle_frame": self.mid, "bubbles": len(self.bubbles),
                "rise_mps": round(self.rise_mps, 3), "cloud_centre_marker_m": [round(float(v), 4) for v in self.centre]}


class Sequence:
    """Everything a frame needs, drawn only from (seed, kind, index): frames of the same sequence rendered
    in any order, subset or run come out the same."""

    def __init__(self, rig, kind, index, seed, frames):
        self.rig, self.kind, self.index, self.seed, self.frames = rig, kind, index, seed, frames
        rng = sequence_rng(seed, kind, index)
        for _ in range(200):
            self.traj = Trajectory(rig, rng, frames)
            if all(gen.all_in_view(rig, self.traj.pose(frame_time(f)), IN_VIEW_MARGIN_PX) for f in range(frames)):
                break
        else:
            raise RuntimeError("%s %d: no trajectory keeps the spheres in both views" % (kind, index))
        self.water_name = "coastal" if kind == "turbid" else "clear"
        self.event = None
        if kind in ("hidden", "turbid"):
            self.event = HiddenSphere(rig, rng, self.traj, frames)
        elif kind == "bubbles":
            self.event = BubbleCloud(rig, rng, self.traj, frames)

    def name(self):
        return "%s_%03d" % (self.kind, self.index)

    def spec(self, frame):
        spec = gen.base_spec(self.water_name)
        if self.event is not None:
            spec.update(self.event.spec_items(frame))
        return spec


# ----------------------------------------------------------------------------------------------------
# One frame


def frame_files(row):
    return "left/%06d.png" % row, "right/%06d.png" % row


def write_png(path, img):
    """As `rovctl record` writes: a hidden temporary name, renamed into place once complete."""
    ok, buf = cv2.imencode(".png", img, [cv2.IMWRITE_PNG_COMPRESSION, 9])
    if not ok:
        raise RuntimeError("cannot encode %s" % path)
    tmp = os.path.join(os.path.dirname(path), "." + os.path.basename(path) + ".tmp")
    with open(tmp, "wb") as f:
        f.write(buf.tobytes())
    os.replace(tmp, path)


def render_frame(seq, frame, row, seq_dir):
    """Render one stereo pair of a sequence into seq_dir and return its truth entry."""
    t = frame_time(frame)
    pose = seq.traj.pose(t)
    spec = seq.spec(frame)
    files = frame_files(row)
    entry = {"frame": frame, "row": row, "stamp_ns": frame_stamp_ns(frame), "left": files[0], "right": files[1]}
    work = tempfile.mkdtemp(prefix="water_seq_", dir="/tmp" if os.path.isdir("/tmp") else None)
    try:
        for cam, rel in zip(seq.rig.cams, files):
            tag = "%s_%04d_%s" % (seq.name(), frame, cam.name)
            img8 = gen.render_camera_image(cam, pose, spec, {}, work, tag, None)
            write_png(os.path.join(seq_dir, rel), img8)
            masks = seq.event is not None and seq.event.needs_masks(frame, cam)
            vis_spec = spec if masks else {k: v for k, v in spec.items() if k != "bars"}
            vis, _ = gen.sphere_visibility(cam, pose, vis_spec, work, tag)
            entry["visible_fraction_" + cam.name] = vis
    finally:
        shutil.rmtree(work, ignore_errors=True)
    R_wc = seq.traj.R_wc(t)
    entry["t_cl_marker_m"] = [round(float(v), 7) for v in pose.t]
    entry["q_cl_marker_wxyz"] = [round(float(v), 9) for v in gen.quat_wxyz(pose.R)]
    entry["range_m"] = round(float(np.linalg.norm(pose.t)), 4)
    entry["p_world_cam_m"] = [round(float(v), 7) for v in seq.traj.c_world(t)]
    entry["q_world_cam_wxyz"] = [round(float(v), 9) for v in gen.quat_wxyz(R_wc)]
    entry["omega_cam_radps"] = [round(float(v), 7) for v in seq.traj.omega_cam_radps(t)]
    # As measured: a sphere none of whose image area shows in either view.
    entry["hidden_sphere"] = next((name for name, _, _ in gen.SPHERES if entry["visible_fraction_left"][name] == 0.0
                                   and entry["visible_fraction_right"][name] == 0.0), None)
    entry["bubbles_on_sight_lines"] = seq.event.on_sight_lines(frame) if isinstance(seq.event, BubbleCloud) else 0
    return entry


# ----------------------------------------------------------------------------------------------------
# Files


def write_atomic(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def sequence_header(seq, args):
    w = seq.spec(0)["water"]
    head = {"generator": SEQUENCE_GENERATOR, "kind": seq.kind, "index": seq.index, "seed": seq.seed,
            "frame_rate_hz": FRAME_RATE_HZ, "trajectory_frames": seq.frames, "frame_step": args.frame_step,
            "draft": bool(args.draft), "calibration": "stereo_calibration.yaml",
            "water": {"jerlov_type": w["jerlov"], "extinction_rgb_per_m": [round(v, 4) for v in w["extinction"]]},
            "conventions": "T_cl_marker as t_cl_marker_m + q_cl_marker_wxyz: x_left = R(q) x_marker + t, metres, "
                           "left camera in OpenCV axes (x right, y down, z forward). World = marker frame (x right, "
                           "y down, z into the station): x_world = R(q_world_cam_wxyz) x_left + p_world_cam_m. "
                           "omega_cam_radps: the left camera's angular rate in its own frame (a gyro's reading). "
                           "visible_fraction_<view>: per sphere, share of its image area on the sensor and not "
                           "behind the bar (sphere-ID renders). hidden_sphere: a sphere with none of its image "
                           "area visible in either view at that frame, else null. bubbles_on_sight_lines: bubbles "
                           "cutting the cone from a camera to any sphere, counted per view (a bubble on both views' "
                           "lines counts twice)."}
    if seq.event is not None:
        head["event"] = seq.event.describe()
    return head


def write_sequence_files(seq_dir, head, entries):
    frames = [entries[f] for f in sorted(entries)]
    write_atomic(os.path.join(seq_dir, "sequence.json"), json.dumps(dict(head, frames=frames), indent=1) + "\n")
    rows = [FRAMES_CSV_HEADER] + ["%d,%d,%d,%s,%s,0" % (e["frame"], e["stamp_ns"], e["stamp_ns"], e["left"], e["right"])
                                  for e in frames]
    write_atomic(os.path.join(seq_dir, "frames.csv"), "\n".join(rows) + "\n")


def finished_frames(seq_dir, head):
    """The frames an earlier run of the same sequence (same header) left complete in seq_dir."""
    path = os.path.join(seq_dir, "sequence.json")
    with open(path) as f:
        old = json.load(f)
    for key in ("kind", "index", "seed", "trajectory_frames", "frame_step", "draft"):
        if old.get(key) != head[key]:
            raise SystemExit("%s: %s is %r, this run's %r; --resume needs the same"
                             % (path, key, old.get(key), head[key]))
    return {e["frame"]: e for e in old.get("frames", [])
            if all(os.path.exists(os.path.join(seq_dir, e[v])) for v in ("left", "right"))}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, help="output folder: one recording folder per sequence + sequences.json")
    ap.add_argument("--kinds", default=",".join(KINDS), help="comma-separated subset of: " + ", ".join(KINDS))
    ap.add_argument("--sequences-per-kind", type=int, default=1)
    ap.add_argument("--frames", type=int, default=90, help="trajectory length in 30 Hz frames (default 90 = 3 s)")
    ap.add_argument("--frame-step", type=int, default=1, help="render every K-th frame of the trajectory (stamps "
                    "and truth stay those of the 30 Hz frame; frames.csv's sequence column is the frame index)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--jobs", type=int, default=2, help="frames rendered at once (one POV-Ray thread each)")
    ap.add_argument("--calibration", default=gen.DEFAULT_CALIBRATION)
    ap.add_argument("--draft", action="store_true", help="render at the real sampling with 2x2 lamp samples")
    ap.add_argument("--resume", action="store_true", help="keep the frames an earlier run with the same "
                    "options already wrote to --out")
    args = ap.parse_args(argv)
    if args.draft:
        gen.RENDER.update(gen.DRAFT_RENDER)
    if shutil.which("povray") is None:
        raise SystemExit("povray not found (Debian package 'povray')")
    kinds = [k.strip() for k in args.kinds.split(",") if k.strip()]
    bad = [k for k in kinds if k not in KINDS]
    if bad:
        raise SystemExit("unknown kind(s): %s (known: %s)" % (", ".join(bad), ", ".join(KINDS)))
    if args.frames < 2 or args.frame_step < 1 or args.sequences_per_kind < 1:
        raise SystemExit("--frames must be at least 2, --frame-step and --sequences-per-kind at least 1")
    rig = gen.Rig(args.calibration)
    for cam in rig.cams:
        cam.ideal(gen.RENDER["ideal_scale"])
    os.makedirs(args.out, exist_ok=True)

    seqs = [Sequence(rig, k, i, args.seed, args.frames) for i in range(args.sequences_per_kind) for k in kinds]
    rendered = list(range(0, args.frames, args.frame_step))
    heads, entries = {}, {}
    for seq in seqs:
        seq_dir = os.path.join(args.out, seq.name())
        heads[seq.name()] = sequence_header(seq, args)
        entries[seq.name()] = {}
        if os.path.exists(os.path.join(seq_dir, "sequence.json")):
            if not args.resume:
                raise SystemExit("%s already holds a sequence (--resume keeps its frames)" % seq_dir)
            done = finished_frames(seq_dir, heads[seq.name()])
            entries[seq.name()] = {f: e for f, e in done.items() if f in rendered}
        for side in ("left", "right"):
            os.makedirs(os.path.join(seq_dir, side), exist_ok=True)
        shutil.copyfile(args.calibration, os.path.join(seq_dir, "stereo_calibration.yaml"))

    def write_manifest():
        listing = [{"name": s.name(), "kind": s.kind, "index": s.index, "seed": s.seed, "path": s.name(),
                    "trajectory_frames": s.frames, "frames": len(rendered), "frames_done": len(entries[s.name()])}
                   for s in seqs]
        man = {"generator": SEQUENCE_GENERATOR, "seed": args.seed, "frame_rate_hz": FRAME_RATE_HZ,
               "frame_step": args.frame_step, "draft": bool(args.draft),
               "calibration": os.path.basename(args.calibration), "sequences": listing}
        write_atomic(os.path.join(args.out, "sequences.json"), json.dumps(man, indent=1) + "\n")

    for seq in seqs:
        write_sequence_files(os.path.join(args.out, seq.name()), heads[seq.name()], entries[seq.name()])
    write_manifest()
    # Frame-major, so a run stopped early has the start of every sequence.
    jobs = [(seq, f) for f in rendered for seq in seqs if f not in entries[seq.name()]]
    start = time.time()
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futs = {pool.submit(render_frame, seq, f, f // args.frame_step, os.path.join(args.out, seq.name())): (seq, f)
                for seq, f in jobs}
        for n, fut in enumerate(concurrent.futures.as_completed(futs), 1):
            seq, f = futs[fut]
            entries[seq.name()][f] = fut.result()
            write_sequence_files(os.path.join(args.out, seq.name()), heads[seq.name()], entries[seq.name()])
            write_manifest()
            print("[%d/%d] %s frame %03d  %.0f s" % (n, len(jobs), seq.name(), f, time.time() - start), flush=True)
    took = time.time() - start
    print("rendered %d frames in %.1f s (%.1f s a frame) into %s"
          % (len(jobs), took, took / max(1, len(jobs)), args.out))


if __name__ == "__main__":
    main()
