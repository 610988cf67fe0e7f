#!/usr/bin/python3
# Independent validation set for the marker pose estimator: POV-Ray renders underwater stereo pairs of
# the three-sphere marker, OpenCV maps them into the real distorted cameras, and the truth goes to a manifest.
"""Render underwater stereo pairs of the docking marker with ground truth.

Nothing here is shared with hal/mock/scene_renderer.cpp on purpose: the images come from a real ray
tracer and the lens model is OpenCV's, so they are evidence against the project's own camera code.
See README.md beside this file for the conditions and the file format.
"""

import argparse
import concurrent.futures
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
if __name__ == "__main__":
    sys.dont_write_bytecode = True  # importing the helper must not leave __pycache__ in the tree
    sys.path.insert(0, HERE)
    import debian_python

    debian_python.require_opencv()

import cv2  # noqa: E402
import numpy as np  # noqa: E402

DEFAULT_CALIBRATION = os.path.normpath(os.path.join(HERE, "..", "..", "..", "deploy", "config",
                                                    "stereo_calibration.yaml"))

# Marker frame: x right, y down, z into the station (OpenCV-like, right-handed), metres.
SPHERE_RADIUS = 0.020
SPHERES = [  # name, centre, albedo (linear RGB)
    ("red", (-0.060, 0.030, 0.0), (0.85, 0.08, 0.06)),
    ("green", (0.060, 0.030, 0.0), (0.08, 0.75, 0.12)),
    ("blue", (0.0, -0.060, -0.040), (0.06, 0.12, 0.85)),
]
SOCKET = (0.0, 0.12, 0.0)
PLATE_Z = 0.05
SEABED_Y = 0.60

CONDITIONS = ["clear", "turbid_near", "turbid_far", "side_light", "bubbles", "occlusion", "edge",
              "noise_jpeg", "distortion", "overexposed", "underexposed", "motion_blur", "cast",
              "noise_yuyv", "noise_mjpg90"]
# Rendered only when named (--conditions): not part of the validation set the docs' figures are read on.
ON_DEMAND_CONDITIONS = ["cast"]
DEFAULT_CONDITIONS = [c for c in CONDITIONS if c not in ON_DEMAND_CONDITIONS]
# Conditions that draw their poses (and every other random draw) as another condition does, so their pairs
# are that condition's pairs in other water: `cast` pair i of seed s is `clear` pair i of seed s.
POSE_TWIN = {"cast": "clear", "noise_yuyv": "noise_jpeg", "noise_mjpg90": "noise_jpeg"}
# The shipped camera's streams: noise + JPEG's pairs (poses, light and sensor noise) as a camera that
# sends YUYV, or MJPG at quality 90, delivers them; noise_jpeg's draws of quality 40-70 are the stress rows.
CONDITION_STREAMS = {"noise_yuyv": "yuyv", "noise_mjpg90": "mjpg:90"}  # as --stream reads them

# Jerlov (1976) Marine Optics, Table XXVII: downwelling diffuse attenuation Kd (1/m) at 450..650 nm in
# 25 nm steps. Camera channels are taken as band means: B 450-500, G 525-575, R 600-650 nm.
JERLOV_KD = {
    "II": [0.068, 0.062, 0.070, 0.076, 0.089, 0.115, 0.260, 0.335, 0.400],
    "3C": [0.39, 0.29, 0.22, 0.20, 0.19, 0.21, 0.33, 0.40, 0.46],
    "5C": [0.56, 0.43, 0.36, 0.31, 0.30, 0.33, 0.40, 0.48, 0.54],
    "7C": [0.89, 0.71, 0.58, 0.49, 0.46, 0.46, 0.48, 0.54, 0.63],
    "9C": [1.60, 1.23, 0.99, 0.78, 0.63, 0.58, 0.60, 0.65, 0.76],
}


def jerlov_rgb(water_type):
    k = JERLOV_KD[water_type]
    return (float(np.mean(k[6:9])), float(np.mean(k[3:6])), float(np.mean(k[0:3])))


# Water per condition: attenuation per channel from Jerlov; b_inf = radiance of open water at infinity
# (linear RGB, in units of lamp-lit white), which the veil approaches with range; ambient = downwelling
# light, already tinted by the water column above the station. b_inf and ambient are our choices.
CAST_EXTINCTION_RGB = (0.54, 0.24, 0.95)
WATERS = {
    "clear": {"jerlov": "II", "b_inf": (0.004, 0.030, 0.050), "ambient": (0.10, 0.15, 0.17)},
    "coastal": {"jerlov": "5C", "b_inf": (0.050, 0.220, 0.170), "ambient": (0.07, 0.14, 0.12)},
    # Not a Jerlov type: green, algae-laden lake or harbour water. Chlorophyll absorbs blue and red, so
    # green carries furthest and the veil is yellow-green; the extinction is given directly (1/m, R G B).
    # The shipped hue windows were chosen in clear water; in this one the blue sphere turns cyan and the
    # red one orange, out of those windows (the `cast` condition, for `rovctl tune-marker`).
    "green_cast": {"jerlov": "none (algal lake)", "extinction": CAST_EXTINCTION_RGB,
                   "b_inf": (0.055, 0.110, 0.022), "ambient": (0.098, 0.158, 0.052)},
}

# Linear renders are made this much darker than the scene so highlights up to 1/HEADROOM survive the
# 16-bit file, which POV-Ray clips at 1.0; exposure conditions then scale without fake clipping.
HEADROOM = 0.25
# The camera's nominal exposure: lamp-lit white would sit near 1.0, the lit plate near 0.2 and the
# brightest sphere channel near 0.5-0.8. The exposure conditions multiply this.
BASE_EXPOSURE = 1.3
# POV-Ray renders at this multiple of the real sampling, with this many lamp samples per axis; --draft
# lowers both (1x, 2x2) for sets that need many pairs more than the finest shading.
RENDER = {"ideal_scale": 2.0, "lamp_samples": 4}
DRAFT_RENDER = {"ideal_scale": 1.0, "lamp_samples": 2}
SUPERSAMPLE = 3  # sub-samples per axis and real pixel when mapping the ideal render into the real camera
OVERHEAD_LAMP = (0.25, -1.4, -0.55)  # marker frame, above and in front of the station
SIDE_LIGHT_PATH = 1.0  # metres of water the side light crosses before the station
WATER_BOX = 30.0  # half size of the water volume; beyond it the background is the open-water colour
MOTION_SUBFRAMES = 32  # warps averaged over the exposure; keeps steps under ~2 px for the longest blur
MOTION_MARGIN = 64  # real px of extra ideal field for the warps to draw from


# ----------------------------------------------------------------------------------------------------
# Calibration and the ideal-to-real camera mapping


class Camera:
    def __init__(self, name, K, D, size, R_from_left, t_from_left):
        self.name = name
        self.K = np.asarray(K, np.float64).reshape(3, 3)
        self.D = np.asarray(D, np.float64).ravel()
        self.W, self.H = int(size[0]), int(size[1])
        self.R = np.asarray(R_from_left, np.float64).reshape(3, 3)  # x_cam = R x_left + t
        self.t = np.asarray(t_from_left, np.float64).ravel()
        self._ideal = {}
        self._lock = threading.Lock()

    def undistort(self, px):
        """Pixels (N,2) -> normalized undistorted coordinates, iterated to convergence."""
        crit = (cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 30, 1e-11)  # round trip < 1e-9 px
        return cv2.undistortPointsIter(np.asarray(px, np.float64).reshape(-1, 1, 2), self.K, self.D,
                                       None, None, crit).reshape(-1, 2)

    def project(self, pts_cam):
        pts = np.asarray(pts_cam, np.float64).reshape(-1, 3)
        uv, _ = cv2.projectPoints(pts, np.zeros(3), np.zeros(3), self.K, self.D)
        return uv.reshape(-1, 2)

    def ideal(self, scale=2.0, margin=0):
        with self._lock:
            if (scale, margin) not in self._ideal:
                self._ideal[(scale, margin)] = IdealView(self, scale, margin)
            return self._ideal[(scale, margin)]


class IdealView:
    """Ideal pinhole POV-Ray renders for one real camera: `scale` times its sampling, principal point
    centred, wide enough to hold every undistorted ray of the real image plus the bilinear taps (plus
    `margin` real pixels all round, for the motion-blur warps)."""

    def __init__(self, cam, scale, margin=0):
        self.cam = cam
        self.fi = scale * max(cam.K[0, 0], cam.K[1, 1])
        W, H = cam.W, cam.H
        border = np.concatenate([
            np.stack([np.arange(W), np.full(W, -0.5)], 1), np.stack([np.arange(W), np.full(W, H - 0.5)], 1),
            np.stack([np.full(H, -0.5), np.arange(H)], 1), np.stack([np.full(H, W - 0.5), np.arange(H)], 1)])
        n = cam.undistort(border.astype(np.float64))
        self.Wi = 2 * int(math.ceil(self.fi * np.abs(n[:, 0]).max() + (3 + margin) * scale))
        self.Hi = 2 * int(math.ceil(self.fi * np.abs(n[:, 1]).max() + (3 + margin) * scale))
        # For every real pixel, SUPERSAMPLE^2 sub-pixel positions: undistort with (K, D), then through the
        # ideal K. POV-Ray samples pixel centres, so ideal pixel (i, j) sees fi * x + (Wi - 1) / 2.
        offs = (np.arange(SUPERSAMPLE) + 0.5) / SUPERSAMPLE - 0.5
        u, v = np.meshgrid(np.arange(W, dtype=np.float64), np.arange(H, dtype=np.float64))
        self.maps = []
        for dy in offs:
            for dx in offs:
                n = cam.undistort(np.stack([(u + dx).ravel(), (v + dy).ravel()], 1))
                mx = (self.fi * n[:, 0] + (self.Wi - 1) / 2.0).reshape(H, W)
                my = (self.fi * n[:, 1] + (self.Hi - 1) / 2.0).reshape(H, W)
                self.maps.append((mx.astype(np.float32), my.astype(np.float32)))

    def to_real(self, ideal):
        """Ideal linear image (Hi,Wi,3) -> real distorted camera image (H,W,3), box-filtered."""
        acc = None
        for mx, my in self.maps:
            s = cv2.remap(ideal, mx, my, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)
            acc = s if acc is None else acc + s
        return acc / float(len(self.maps))


class Rig:
    def __init__(self, path):
        fs = cv2.FileStorage(path, cv2.FILE_STORAGE_READ)
        if not fs.isOpened():
            raise SystemExit(f"cannot open calibration {path}")
        node = fs.getNode("image_size")
        size = [int(node.at(0).real()), int(node.at(1).real())] if node.isSeq() else node.mat().ravel()
        R = fs.getNode("R").mat()
        T = fs.getNode("T").mat().ravel()
        self.path = path
        self.left = Camera("left", fs.getNode("K1").mat(), fs.getNode("D1").mat(), size, np.eye(3), np.zeros(3))
        self.right = Camera("right", fs.getNode("K2").mat(), fs.getNode("D2").mat(), size, R, T)
        fs.release()
        self.cams = (self.left, self.right)


# ----------------------------------------------------------------------------------------------------
# Poses and analytic geometry (used to place things and to report visibility, never to draw)


def rot_x(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def rot_y(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def quat_wxyz(R):
    R = np.asarray(R, np.float64)
    tr = np.trace(R)
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        q = [0.25 * s, (R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s, (R[1, 0] - R[0, 1]) / s]
    elif R[0, 0] > R[1, 1] and R[0, 0] > R[2, 2]:
        s = math.sqrt(1.0 + R[0, 0] - R[1, 1] - R[2, 2]) * 2
        q = [(R[2, 1] - R[1, 2]) / s, 0.25 * s, (R[0, 1] + R[1, 0]) / s, (R[0, 2] + R[2, 0]) / s]
    elif R[1, 1] > R[2, 2]:
        s = math.sqrt(1.0 + R[1, 1] - R[0, 0] - R[2, 2]) * 2
        q = [(R[0, 2] - R[2, 0]) / s, (R[0, 1] + R[1, 0]) / s, 0.25 * s, (R[1, 2] + R[2, 1]) / s]
    else:
        s = math.sqrt(1.0 + R[2, 2] - R[0, 0] - R[1, 1]) * 2
        q = [(R[1, 0] - R[0, 1]) / s, (R[0, 2] + R[2, 0]) / s, (R[1, 2] + R[2, 1]) / s, 0.25 * s]
    q = np.array(q)
    q /= np.linalg.norm(q)
    return q if q[0] >= 0 else -q


class Pose:
    """Pose of the marker in the left camera: x_left = R x_marker + t."""

    def __init__(self, R, t):
        self.R = np.asarray(R, np.float64)
        self.t = np.asarray(t, np.float64).ravel()

    def in_cam(self, cam):
        return Pose(cam.R @ self.R, cam.R @ self.t + cam.t)

    def apply(self, p):
        return (self.R @ np.asarray(p, np.float64).reshape(-1, 3).T).T + self.t

    def moved(self, rvec, tvec):
        """The marker seen after the vehicle moved: a small rigid motion applied in the camera frame."""
        dR, _ = cv2.Rodrigues(np.asarray(rvec, np.float64))
        return Pose(dR @ self.R, dR @ self.t + np.asarray(tvec, np.float64))


def sphere_outline(cam, centre_cam, r=SPHERE_RADIUS, n=96):
    """Image of the sphere's silhouette (tangent circle) in the real camera, (n,2) pixels."""
    c = np.asarray(centre_cam, np.float64)
    d = np.linalg.norm(c)
    if c[2] <= r or d <= r:
        return None
    a = c / d
    k = r * r / (d * d)
    mid = c * (1.0 - k)
    rad = r * math.sqrt(1.0 - k)
    e1 = np.cross(a, [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(a, e1)
    ang = np.linspace(0, 2 * math.pi, n, endpoint=False)
    pts = mid + rad * (np.cos(ang)[:, None] * e1 + np.sin(ang)[:, None] * e2)
    if np.any(pts[:, 2] <= 1e-3):
        return None
    return cam.project(pts)


def poly_area(p):
    x, y = p[:, 0], p[:, 1]
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def clip_rect(poly, x0, y0, x1, y1):
    """Sutherland-Hodgman clip of a polygon by an axis-aligned rectangle."""
    def clip(pts, inside, cross):
        out = []
        for i in range(len(pts)):
            cur, prev = pts[i], pts[i - 1]
            ci, pi = inside(cur), inside(prev)
            if ci:
                if not pi:
                    out.append(cross(prev, cur))
                out.append(cur)
            elif pi:
                out.append(cross(prev, cur))
        return out

    def xcross(xc):
        return lambda p, q: (xc, p[1] + (q[1] - p[1]) * (xc - p[0]) / (q[0] - p[0]))

    def ycross(yc):
        return lambda p, q: (p[0] + (q[0] - p[0]) * (yc - p[1]) / (q[1] - p[1]), yc)

    pts = [tuple(p) for p in poly]
    for inside, cross in ((lambda p: p[0] >= x0, xcross(x0)), (lambda p: p[0] <= x1, xcross(x1)),
                          (lambda p: p[1] >= y0, ycross(y0)), (lambda p: p[1] <= y1, ycross(y1))):
        if not pts:
            break
        pts = clip(pts, inside, cross)
    return np.array(pts, np.float64).reshape(-1, 2)


def in_image_fraction(cam, centre_cam):
    """Share of the sphere's image area that falls on the sensor (0..1)."""
    o = sphere_outline(cam, centre_cam)
    if o is None:
        return 0.0
    full = poly_area(o)
    c = clip_rect(o, -0.5, -0.5, cam.W - 0.5, cam.H - 0.5)
    return 0.0 if len(c) < 3 else float(min(1.0, poly_area(c) / full))


def outline_margin(cam, centre_cam):
    """Smallest distance (px) from the sphere's image to the image border; negative if it crosses."""
    o = sphere_outline(cam, centre_cam)
    if o is None:
        return -1e9
    return float(min(o[:, 0].min(), o[:, 1].min(), cam.W - 1 - o[:, 0].max(), cam.H - 1 - o[:, 1].max()))


def sphere_centres(pose):
    return pose.apply([s[1] for s in SPHERES])


def cameras_in_water(rig, pose):
    """Both cameras in front of the plate and above the seabed (a camera looking up at a marker near the
    top of its image can otherwise end up under the seabed, which then hides everything)."""
    for cam in rig.cams:
        pc = pose.in_cam(cam)
        c_m = -pc.R.T @ pc.t
        if c_m[1] > SEABED_Y - 0.15 or c_m[2] > -0.10:
            return False
    return True


def all_in_view(rig, pose, margin=4.0, skip=None):
    if not cameras_in_water(rig, pose):
        return False
    for cam in rig.cams:
        cs = sphere_centres(pose.in_cam(cam))
        for i, c in enumerate(cs):
            if skip is not None and skip == (cam.name, i):
                continue
            if outline_margin(cam, c) < margin:
                return False
    return True


def ray_sphere(d, c, r):
    """Nearest positive hit distance along unit rays d (N,3) from the origin; inf where missed."""
    b = d @ c
    disc = b * b - (c @ c - r * r)
    t = np.where(disc >= 0, b - np.sqrt(np.maximum(disc, 0)), np.inf)
    return np.where(t > 0, t, np.inf)


def ray_bar(d, p0, w, rho, length):
    """Hits of rays from the origin with a bar: cylinder from p0 along unit w, rounded at p0."""
    dw = d @ w
    dp = d - dw[:, None] * w
    a = p0 - (p0 @ w) * w
    A = np.einsum("ij,ij->i", dp, dp)
    B = -2 * dp @ a
    C = a @ a - rho * rho
    disc = B * B - 4 * A * C
    with np.errstate(invalid="ignore", divide="ignore"):
        t = (-B - np.sqrt(np.maximum(disc, 0))) / (2 * A)
    h = t * dw - p0 @ w
    t = np.where((disc >= 0) & (t > 0) & (h >= 0) & (h <= length), t, np.inf)
    return np.minimum(t, ray_sphere(d, p0, rho))


def occluded_fraction(cam, centre_cam, bars_cam, n=41):
    """Share of the sphere's silhouette hidden by bars (analytic, rays through a grid on the disc)."""
    c = np.asarray(centre_cam)
    dist = np.linalg.norm(c)
    half = math.asin(min(0.999, SPHERE_RADIUS / dist))
    a = c / dist
    e1 = np.cross(a, [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(a, e1)
    g = np.linspace(-1, 1, n)
    gx, gy = np.meshgrid(g, g)
    keep = gx * gx + gy * gy <= 1.0
    s = math.tan(half)
    d = a + s * (gx[keep][:, None] * e1 + gy[keep][:, None] * e2)
    d /= np.linalg.norm(d, axis=1)[:, None]
    ts = ray_sphere(d, c, SPHERE_RADIUS)
    hit = np.isfinite(ts)
    if not hit.any():
        return 0.0
    hidden = np.zeros(len(d), bool)
    for p0, w, rho, length in bars_cam:
        hidden |= ray_bar(d, p0, w, rho, length) < ts
    return float((hidden & hit).sum() / hit.sum())


def bars_in_cam(pose_cam, bars):
    return [(pose_cam.apply(b["p0"])[0], pose_cam.R @ np.asarray(b["w"], np.float64), b["rho"], b["length"])
            for b in bars]


# ----------------------------------------------------------------------------------------------------
# Pose sampling


def random_rotation(rng, yaw_deg=25.0, pitch_deg=25.0, roll_deg=10.0):
    yaw = math.radians(rng.uniform(-yaw_deg, yaw_deg))
    pitch = math.radians(rng.uniform(-pitch_deg, pitch_deg))
    roll = math.radians(rng.uniform(-roll_deg, roll_deg))
    return rot_y(yaw) @ rot_x(pitch) @ rot_z(roll), (yaw, pitch, roll)


def anchored_pose(rig, view, R_m, anchor_marker, pixel, dist):
    """Pose that puts a marker point on a given pixel of one view at a given distance from that camera."""
    cam = rig.cams[view]
    ray = np.append(cam.undistort([pixel])[0], 1.0)
    ray /= np.linalg.norm(ray)
    p_cam = ray * dist
    p_left = cam.R.T @ (p_cam - cam.t)
    return Pose(R_m, p_left - R_m @ np.asarray(anchor_marker, np.float64))


def sample_standard_pose(rig, rng, lo, hi, margin=4.0, tries=20000):
    cam = rig.left
    for _ in range(tries):
        R_m, angles = random_rotation(rng)
        d = rng.uniform(lo, hi)
        px = (rng.uniform(0.08, 0.92) * cam.W, rng.uniform(0.08, 0.92) * cam.H)
        pose = anchored_pose(rig, 0, R_m, (0, 0, 0), px, d)
        if not lo <= np.linalg.norm(pose.t) <= hi:
            continue
        if all_in_view(rig, pose, margin):
            return pose, angles
    raise RuntimeError(f"no pose with all spheres in view at {lo}-{hi} m")


# ----------------------------------------------------------------------------------------------------
# Scene description -> POV-Ray


def pv(p, scale=1.0):
    """Marker-frame point to POV-Ray's left-handed y-up convention (flip y)."""
    return "<%.6f, %.6f, %.6f>" % (p[0] * scale, -p[1] * scale, p[2] * scale)


def rgb(c):
    return "rgb <%.6f, %.6f, %.6f>" % tuple(c)


FLIP = np.diag([1.0, -1.0, 1.0])


def pov_matrix(pose_cam):
    """POV-Ray matrix taking flipped marker coordinates to flipped camera coordinates."""
    A = FLIP @ pose_cam.R @ FLIP
    t = FLIP @ pose_cam.t
    vals = [A[0, 0], A[1, 0], A[2, 0], A[0, 1], A[1, 1], A[2, 1], A[0, 2], A[1, 2], A[2, 2], t[0], t[1], t[2]]
    return "matrix <" + ", ".join("%.9f" % v for v in vals) + ">"


def scene_pov(iv, pose, spec, mode):
    """POV-Ray SDL for one ideal view.

    mode "beauty": the lit scene as it leaves the surfaces (J), no water on the view path.
    mode "transmittance": every surface shows T = exp(-c d) per channel, d its distance from the camera,
    for the same rays. The water is composed in Python from the two passes as J T + B_inf (1 - T): the
    attenuation-plus-backscatter model of underwater imaging, exact for uniform in-scattered light.
    (POV-Ray media gave the same T but cost more, and its emission integral overshoots on long rays.)
    modes "mask_with" / "mask_without": sphere-ID pass with or without the occluding bars.
    """
    pc = pose.in_cam(iv.cam)
    M = pov_matrix(pc)
    H = HEADROOM
    beauty = mode == "beauty"
    out = ["#version 3.7;",
           "global_settings { assumed_gamma 1.0 max_trace_level 12 ambient_light %s }"
           % rgb(np.asarray(spec["ambient"]) * H if beauty else (1, 1, 1)),
           "camera { perspective location <0,0,0> direction <0,0,1> right <%.9f,0,0> up <0,%.9f,0> }"
           % (iv.Wi / iv.fi, iv.Hi / iv.fi),
           "background { rgb 0 }"]
    objs = []
    if mode.startswith("mask"):
        for (name, c, _), col in zip(SPHERES, ((1, 0, 0), (0, 1, 0), (0, 0, 1))):
            objs.append("sphere { %s, %.6f pigment { %s } finish { ambient 1 diffuse 0 } }"
                        % (pv(c), SPHERE_RADIUS, rgb(col)))
        if mode == "mask_with":
            for b in spec.get("bars", []):
                objs.append(bar_pov(b, "pigment { rgb 0 } finish { ambient 0 diffuse 0 }"))
        out.append("union {\n  " + "\n  ".join(objs) + "\n  %s\n}" % M)
        return "\n".join(out) + "\n"

    def mat(m):
        return m if beauty else ""  # the transmittance texture is applied to the whole union

    ext = np.asarray(spec["water"]["extinction"])
    # Marker spheres: painted, mildly glossy; dark stalks to the plate.
    for name, c, alb in SPHERES:
        objs.append("sphere { %s, %.6f %s }" % (pv(c), SPHERE_RADIUS, mat(
            "pigment { %s } finish { ambient 1 diffuse 0.85 specular 0.25 roughness 0.01 }" % rgb(alb))))
        objs.append("cylinder { %s, %s, 0.005 %s }" % (pv(c), pv((c[0], c[1], PLATE_Z + 0.005)), mat(
            "pigment { rgb 0.04 } finish { ambient 1 diffuse 0.8 }")))
    # Station: matte backplate with the charging socket opening, a pedestal and the seabed below.
    sx, sy = SOCKET[0], SOCKET[1]
    objs.append("difference { box { %s, %s } cylinder { %s, %s, 0.026 } %s }"
                % (pv((-0.25, -0.17, PLATE_Z)), pv((0.25, 0.23, PLATE_Z + 0.02)),
                   pv((sx, sy, PLATE_Z - 0.01)), pv((sx, sy, PLATE_Z + 0.03)),
                   mat("pigment { rgb <0.33,0.33,0.32> } finish { ambient 1 diffuse 0.8 }")))
    objs.append("difference { cylinder { %s, %s, 0.036 } cylinder { %s, %s, 0.026 } %s }"
                % (pv((sx, sy, SOCKET[2])), pv((sx, sy, PLATE_Z + 0.01)),
                   pv((sx, sy, SOCKET[2] - 0.01)), pv((sx, sy, PLATE_Z + 0.02)),
                   mat("pigment { rgb 0.03 } finish { ambient 1 diffuse 0.8 specular 0.1 roughness 0.05 }")))
    objs.append("cylinder { %s, %s, 0.027 %s }" % (pv((sx, sy, PLATE_Z + 0.03)), pv((sx, sy, PLATE_Z + 0.035)),
                                                   mat("pigment { rgb 0.005 } finish { ambient 1 diffuse 0.5 }")))
    objs.append("box { %s, %s %s }" % (pv((-0.05, 0.23, PLATE_Z)), pv((0.05, SEABED_Y + 0.01, PLATE_Z + 0.10)),
                                       mat("pigment { rgb <0.26,0.26,0.25> } finish { ambient 1 diffuse 0.8 }")))
    objs.append("plane { <0,1,0>, %.6f clipped_by { box { <-%g,-1,-%g>, <%g,1,%g> } } %s }"
                % ((-SEABED_Y,) + (WATER_BOX - 1,) * 4 + (mat(
                    "pigment { bozo color_map { [0 rgb <0.25,0.23,0.20>] [1 rgb <0.44,0.41,0.35>] } "
                    "turbulence 0.4 scale 0.03 } finish { ambient 1 diffuse 0.8 }"),)))
    for b in spec.get("bars", []):
        objs.append(bar_pov(b, mat("pigment { rgb <0.12,0.12,0.11> } finish { ambient 1 diffuse 0.8 "
                                   "specular 0.15 roughness 0.03 }")))
    # Air bubbles refract with n_air / n_water = 0.752 and reflect by Fresnel, with total internal
    # reflection at grazing angles; the transmittance pass follows the same refracted rays.
    bubble = ("pigment { rgbf <1,1,1,1> } finish { ambient 0 diffuse 0 specular 0.9 roughness 0.001 "
              "reflection { 0.02, 1.0 fresnel on } conserve_energy } interior { ior 0.752 }" if beauty else
              "pigment { rgbf <1,1,1,1> } finish { ambient 0 diffuse 0 } interior { ior 0.752 }")
    for (p, r) in spec.get("bubbles", []):
        objs.append("sphere { %s, %.6f %s }" % (pv(p), r, bubble))
    for (p, r, e) in spec.get("particles", []):
        objs.append("sphere { %s, %.6f %s no_shadow }" % (pv(p), r, mat(
            "pigment { rgb <0.9,0.9,0.85> } finish { ambient 1 diffuse 0.9 emission %.4f }" % (e * H))))
    if beauty:
        # Lights (marker frame: -y is up). The water between a lamp and the station is one Beer-Lambert
        # tint over the lamp's distance to the marker (tracing every shadow ray through media tripled
        # the render time); the view path is exact.
        ov = spec.get("overhead", 1.0)
        if ov > 0:
            lamp = np.array(OVERHEAD_LAMP)
            tint = np.exp(-ext * np.linalg.norm(lamp))
            objs.append("light_source { %s color %s area_light <0.9,0,0>, <0,0,0.9>, %d, %d adaptive 0 "
                        "jitter circular orient }" % (pv(lamp), rgb(tint * ov * H), RENDER["lamp_samples"],
                                                     RENDER["lamp_samples"]))
        if "side_light" in spec:
            sl = spec["side_light"]
            tint = np.exp(-ext * SIDE_LIGHT_PATH)
            objs.append("light_source { %s color %s parallel point_at <0,0,0> }"
                        % (pv(np.asarray(sl["dir"]) * 3.0), rgb(tint * sl["power"] * H)))
    tex = ""
    if not beauty:
        # After the matrix, so the pattern stays in camera coordinates: distance from the pinhole.
        pig = ["pigment { function { exp(-%.8f * sqrt(x*x + y*y + z*z)) } color_map { [0 rgb 0] [1 rgb %s] } }"
               % (ext[k], "<%d,%d,%d>" % tuple(3 if j == k else 0 for j in range(3))) for k in range(3)]
        out += ["#declare T%d = %s;" % (k, p) for k, p in enumerate(pig)]
        tex = "  pigment { average pigment_map { [1 T0] [1 T1] [1 T2] } } finish { ambient 1 diffuse 0 }\n"
    out.append("union {\n  " + "\n  ".join(objs) + "\n  %s\n%s}" % (M, tex))
    return "\n".join(out) + "\n"


def bar_pov(b, material):
    p0 = np.asarray(b["p0"], np.float64)
    p1 = p0 + np.asarray(b["w"], np.float64) * b["length"]
    return "merge { cylinder { %s, %s, %.6f } sphere { %s, %.6f } %s }" % (
        pv(p0), pv(p1), b["rho"], pv(p0), b["rho"], material)


# ----------------------------------------------------------------------------------------------------
# Rendering


def povray_render(sdl, iv, workdir, tag, quality):
    pov = os.path.join(workdir, tag + ".pov")
    ppm = os.path.join(workdir, tag + ".ppm")
    with open(pov, "w") as f:
        f.write(sdl)
    # Beauty passes need no POV-Ray anti-aliasing: the 2x ideal render is box-filtered by the remap.
    # The sphere-ID pass is anti-aliased because its pixel sums are read as areas.
    aa = ["+A0.002", "+AM2", "+R3"] if quality == "mask" else ["-A"]
    cmd = ["povray", "+I" + pov, "+O" + ppm, "+W%d" % iv.Wi, "+H%d" % iv.Hi, "-J", "+WT1", "-D", "-P",
           "+Q9", "Output_File_Type=P", "Bits_Per_Color=16", "File_Gamma=1.0", "-V", "-GS", "-GR"] + aa
    # On a loaded machine POV-Ray now and then gives up "waiting for worker thread startup": try again.
    for _attempt in range(3):
        res = subprocess.run(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        img = cv2.imread(ppm, cv2.IMREAD_UNCHANGED) if res.returncode == 0 else None
        if img is not None or "worker thread startup" not in res.stderr:
            break
    if res.returncode != 0 or img is None:
        raise RuntimeError("povray failed for %s (exit %d):\n%s" % (pov, res.returncode, res.stderr[-3000:]))
    os.remove(ppm)
    os.remove(pov)
    return img.astype(np.float32) / 65535.0  # BGR, linear


def render_view(cam, pose, spec, workdir, tag, motion=None):
    """Linear BGR image of one view in the real distorted camera, scene units (1.0 = lamp-lit white)."""
    iv = cam.ideal(RENDER["ideal_scale"], MOTION_MARGIN if motion else 0)
    J = povray_render(scene_pov(iv, pose, spec, "beauty"), iv, workdir, tag + "_j", "beauty") / HEADROOM
    T = povray_render(scene_pov(iv, pose, spec, "transmittance"), iv, workdir, tag + "_t", "beauty")
    binf = np.asarray(spec["water"]["b_inf"], np.float32)[::-1]  # BGR
    lin = J * T + binf * (1.0 - T)
    if motion:
        lin = motion_blur(iv, lin, T, np.asarray(spec["water"]["extinction"]), motion)
    return iv.to_real(lin)


def motion_in_cam(cam, rvec, tvec):
    """A rig motion given in the left camera frame, expressed in `cam`'s frame."""
    dR, _ = cv2.Rodrigues(np.asarray(rvec, np.float64))
    Rc = cam.R @ dR @ cam.R.T
    return Rc, cam.R @ np.asarray(tvec, np.float64) + cam.t - Rc @ cam.t


def motion_blur(iv, lin, T, ext, motion):
    """Average of the mid-exposure ideal image warped to MOTION_SUBFRAMES poses along the motion.

    Each warp moves every pixel by the rigid motion of the 3-D point it shows, at the distance read back
    from the transmittance pass (d = -ln T / c), so near things smear more than far ones under
    translation. The depth used is the one at the output pixel, which is off only where the motion
    uncovers something (a few px at the plate's outline; the spheres sit 5-9 cm in front of it).
    """
    k = int(np.argmin(ext))  # the clearest channel reads distance most precisely
    Tk = T[:, :, 2 - k].astype(np.float64)
    d = np.where(Tk > 1e-6, -np.log(np.maximum(Tk, 1e-300)) / ext[k], 1e4)
    H, W = Tk.shape
    cx, cy = (W - 1) / 2.0, (H - 1) / 2.0
    x, y = np.meshgrid((np.arange(W) - cx) / iv.fi, (np.arange(H) - cy) / iv.fi)
    scale = d / np.sqrt(x * x + y * y + 1.0)
    X = np.stack([x * scale, y * scale, scale])
    acc = np.zeros_like(lin)
    n = motion["subframes"]
    for i in range(n):
        s = (i + 0.5) / n - 0.5
        dR, dt = motion_in_cam(iv.cam, motion["rvec"] * s, motion["tvec"] * s)
        # The point seen at this pixel at time s was at dR^T (X - dt) at mid-exposure.
        Xm = np.einsum("ji,jhw->ihw", dR, X - dt[:, None, None])
        z = np.maximum(Xm[2], 1e-6)
        mx = (iv.fi * Xm[0] / z + cx).astype(np.float32)
        my = (iv.fi * Xm[1] / z + cy).astype(np.float32)
        acc += cv2.remap(lin, mx, my, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)
    return acc / n


def render_mask(cam, pose, spec, workdir, tag, with_bars):
    iv = cam.ideal(RENDER["ideal_scale"])
    return iv.to_real(povray_render(scene_pov(iv, pose, spec, "mask_with" if with_bars else "mask_without"), iv,
                                    workdir, tag, "mask"))


def srgb_encode(lin):
    lin = np.clip(lin, 0.0, 1.0)
    return np.where(lin <= 0.0031308, 12.92 * lin, 1.055 * np.power(lin, 1 / 2.4) - 0.055)


def to_8bit(lin):
    return np.clip(np.round(srgb_encode(lin) * 255.0), 0, 255).astype(np.uint8)


def sensor_noise_jpeg(lin, rng, post):
    """Shot + read noise on the linear signal, 8-bit sRGB, then a JPEG round trip."""
    fw = post["full_well_e"]
    e = np.clip(lin, 0, 1) * fw
    e = e + rng.normal(0.0, 1.0, e.shape) * np.sqrt(np.maximum(e, 0)) + rng.normal(0.0, post["read_noise_e"], e.shape)
    img = to_8bit(e / fw)
    if post.get("stream") == "yuyv":
        return yuyv_round_trip(img)
    ok, buf = cv2.imencode(".jpg", img, [cv2.IMWRITE_JPEG_QUALITY, int(post["jpeg_quality"])])
    return cv2.imdecode(buf, cv2.IMREAD_COLOR)


def yuyv_round_trip(img):
    """What a camera streaming YUYV delivers once rovctl's V4L2 driver has decoded it
    (cv2.COLOR_YUV2BGR_YUYV): BT.601 video-range luma per pixel, chroma averaged over each pixel pair."""
    rgb = img[:, :, ::-1].astype(np.float64) / 255.0
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    y = 16.0 + 65.481 * r + 128.553 * g + 24.966 * b
    cb = 128.0 - 37.797 * r - 74.203 * g + 112.0 * b
    cr = 128.0 + 112.0 * r - 93.786 * g - 18.214 * b
    yuyv = np.empty(img.shape[:2] + (2,), np.uint8)
    yuyv[:, :, 0] = np.clip(np.round(y), 0, 255)
    yuyv[:, 0::2, 1] = np.clip(np.round((cb[:, 0::2] + cb[:, 1::2]) / 2.0), 0, 255)
    yuyv[:, 1::2, 1] = np.clip(np.round((cr[:, 0::2] + cr[:, 1::2]) / 2.0), 0, 255)
    return cv2.cvtColor(yuyv, cv2.COLOR_YUV2BGR_YUYV)


# ----------------------------------------------------------------------------------------------------
# Conditions: each returns (pose, spec, post, extra truth fields, notes)


def water(name):
    w = dict(WATERS[name])
    if "extinction" not in w:
        w["extinction"] = jerlov_rgb(w["jerlov"])
    return w


def base_spec(water_name="clear"):
    w = water(water_name)
    return {"water": w, "ambient": w["ambient"], "overhead": 1.0}


def angles_note(angles):
    return "yaw %.1f pitch %.1f roll %.1f deg" % tuple(math.degrees(a) for a in angles)


def cond_standard(rig, rng, lo=0.3, hi=1.5, water_name="clear"):
    pose, angles = sample_standard_pose(rig, rng, lo, hi)
    return pose, base_spec(water_name), {}, {}, angles_note(angles)


def cond_clear(rig, rng, index):
    return cond_standard(rig, rng)


def cond_turbid_near(rig, rng, index):
    pose, spec, post, extra, notes = cond_standard(rig, rng, 0.3, 0.7, "coastal")
    return pose, spec, post, extra, notes + "; Jerlov 5C water"


def cond_turbid_far(rig, rng, index):
    pose, spec, post, extra, notes = cond_standard(rig, rng, 0.8, 1.5, "coastal")
    return pose, spec, post, extra, notes + "; Jerlov 5C water"


def cond_cast(rig, rng, index):
    pose, spec, post, extra, notes = cond_standard(rig, rng, 0.3, 1.5, "green_cast")
    return pose, spec, post, extra, notes + "; green algal water (strong colour cast)"


def cond_side_light(rig, rng, index):
    for _ in range(500):
        pose, angles = sample_standard_pose(rig, rng, 0.35, 1.3)
        side = rng.choice([-1.0, 1.0])
        el = math.radians(rng.uniform(10, 35))
        az = math.radians(rng.uniform(20, 50))  # towards the camera side so the spheres face the light
        L = np.array([side * math.cos(el) * math.cos(az), -math.sin(el), -math.cos(el) * math.sin(az)])
        target = int(rng.integers(3))
        S = np.asarray(SPHERES[target][1])
        axis = np.array([0.0, 1.0, 0.0])
        nS = np.cross(axis, L)
        nS /= np.linalg.norm(nS)
        rho = rng.uniform(0.010, 0.018)
        # One edge of the shadow crosses the sphere within half a radius of its centre.
        delta = float(rng.choice([-1.0, 1.0])) * (rho + rng.uniform(-0.5, 0.5) * SPHERE_RADIUS)
        centre = S + L * rng.uniform(0.12, 0.25) + nS * delta
        p0 = np.array([centre[0], -0.45, centre[2]])
        bar = {"p0": p0, "w": axis, "rho": rho, "length": SEABED_Y + 0.45}
        # Only the target sphere may lie in the bar's shadow slab.
        clear_others = all(abs((np.asarray(SPHERES[i][1]) - p0) @ nS) > SPHERE_RADIUS + rho + 0.01
                           for i in range(3) if i != target)
        if not clear_others:
            continue
        # The pole must not hide any sphere from either camera.
        if any(occluded_fraction(cam, c, bars_in_cam(pose.in_cam(cam), [bar])) > 0.0
               for cam in rig.cams for c in sphere_centres(pose.in_cam(cam))):
            continue
        spec = base_spec("clear")
        spec["ambient"] = tuple(np.asarray(spec["ambient"]) * 0.25)
        spec["overhead"] = 0.12
        spec["side_light"] = {"dir": L, "power": 1.6}
        spec["bars"] = [bar]
        extra = {"shadowed_sphere": SPHERES[target][0],
                 "light_dir_marker": [round(float(v), 4) for v in L]}
        notes = "%s; light from the %s, pole shadow across %s" % (
            angles_note(angles), "left" if side < 0 else "right", SPHERES[target][0])
        return pose, spec, {}, extra, notes
    raise RuntimeError("side_light: no layout found")


def scatter_in_view(rng, pose, n, lam_lo, lam_hi, spread):
    """Points between the left camera and the station, spread through the visible volume."""
    Rm, t = pose.R, pose.t
    cam_m = -Rm.T @ t
    pts = []
    for _ in range(n):
        X = np.array([rng.uniform(-spread, spread), rng.uniform(-spread * 0.8, spread), rng.uniform(-0.05, 0.03)])
        lam = rng.uniform(lam_lo, lam_hi)
        pts.append(cam_m + lam * (X - cam_m) + rng.normal(0, 0.01, 3))
    return pts


def far_from_spheres(p, r, gap=0.002):
    return all(np.linalg.norm(np.asarray(p) - np.asarray(s[1])) > SPHERE_RADIUS + r + gap for s in SPHERES)


def cond_bubbles(rig, rng, index):
    pose, angles = sample_standard_pose(rig, rng, 0.35, 1.5)
    spec = base_spec("clear")
    bubbles = []
    for p in scatter_in_view(rng, pose, int(rng.integers(120, 220)), 0.12, 0.97, 0.35):
        r = float(min(0.004, rng.lognormal(math.log(0.0012), 0.5)))
        if far_from_spheres(p, r):
            bubbles.append((p, r))
    # A few right on the lines of sight to the spheres.
    cam_m = -pose.R.T @ pose.t
    n_front = int(rng.integers(6, 12))
    for _ in range(n_front):
        s = np.asarray(SPHERES[int(rng.integers(3))][1]) + rng.normal(0, 0.012, 3)
        p = cam_m + rng.uniform(0.45, 0.93) * (s - cam_m)
        r = float(rng.uniform(0.0015, 0.0035))
        if far_from_spheres(p, r):
            bubbles.append((p, r))
    particles = []
    for p in scatter_in_view(rng, pose, int(rng.integers(300, 600)), 0.08, 1.0, 0.45):
        r = float(rng.uniform(0.0002, 0.0006))
        if far_from_spheres(p, r):
            particles.append((p, r, float(rng.uniform(0.1, 0.6))))
    spec["bubbles"] = bubbles
    spec["particles"] = particles
    return pose, spec, {}, {"bubbles": len(bubbles), "particles": len(particles)}, \
        "%s; %d bubbles (%d aimed at the spheres), %d particles" % (angles_note(angles), len(bubbles), n_front,
                                                                   len(particles))


def cond_occlusion(rig, rng, index):
    for _ in range(400):
        pose, angles = sample_standard_pose(rig, rng, 0.4, 1.5)
        target = int(rng.integers(3))
        S = np.asarray(SPHERES[target][1])
        if target == 0:
            out = -1.0
        elif target == 1:
            out = 1.0
        else:
            out = float(rng.choice([-1.0, 1.0]))
        phi = math.radians(rng.uniform(-20, 20))
        w = np.array([out * math.cos(phi), math.sin(phi), 0.0])
        nrm = np.array([-math.sin(phi), math.cos(phi), 0.0])
        rho = rng.uniform(0.010, 0.016)
        gap = rng.uniform(0.05, 0.14)
        reach = rng.uniform(0.02, 0.035)
        side = float(rng.choice([-1.0, 1.0]))
        goal = rng.uniform(0.35, 0.55)

        def make(delta):
            p0 = np.array([S[0], S[1], S[2] - gap]) + nrm * delta - w * reach
            return {"p0": p0, "w": w, "rho": rho, "length": 1.2}

        def frac(bar, cam_i, sphere_i):
            cam = rig.cams[cam_i]
            pc = pose.in_cam(cam)
            return occluded_fraction(cam, sphere_centres(pc)[sphere_i], bars_in_cam(pc, [bar]))

        lo, hi = side * (SPHERE_RADIUS + rho) * 1.6, 0.0
        if frac(make(hi), 0, target) < goal:
            continue
        for _ in range(30):
            mid = 0.5 * (lo + hi)
            if frac(make(mid), 0, target) < goal:
                lo = mid
            else:
                hi = mid
        bar = make(hi)
        fr = [frac(bar, ci, target) for ci in (0, 1)]
        if not all(0.32 <= f <= 0.58 for f in fr):
            continue
        if any(frac(bar, ci, si) > 0.0 for ci in (0, 1) for si in range(3) if si != target):
            continue
        spec = base_spec("clear")
        spec["bars"] = [bar]
        extra = {"occluded_sphere": SPHERES[target][0], "occluder_planned_fraction": [round(f, 3) for f in fr]}
        return pose, spec, {}, extra, "%s; bar %.0f mm in front of %s" % (angles_note(angles), gap * 1000,
                                                                           SPHERES[target][0])
    raise RuntimeError("occlusion: no layout found")


# (view, sphere, edge): the ones where the other two spheres, and this one in the other view, can stay
# in. The rig looks across, so only the right image's left edge and the left image's right edge qualify;
# the left camera sees a little less above (cy 236 of 480) and more below than the right one (cy 245), so
# the top edge works in the left image and the bottom edge in the right; blue is the only sphere on top.
LEFT, RIGHT = 0, 1
EDGE_COMBOS = [(RIGHT, 0, 0), (LEFT, 1, 1), (LEFT, 2, 2), (RIGHT, 0, 3), (RIGHT, 1, 3)]


def cond_edge(rig, rng, index):
    for attempt in range(len(EDGE_COMBOS) * 1500):
        view, target, edge = EDGE_COMBOS[(index + attempt // 1500) % len(EDGE_COMBOS)]
        cam = rig.cams[view]
        R_m, angles = random_rotation(rng)
        d = rng.uniform(0.4, 1.5)
        rpx = cam.K[0, 0] * SPHERE_RADIUS / d
        s = rng.uniform(-1.3, 0.8) * rpx  # sphere centre from the edge, negative = outside
        along = rng.uniform(0.15, 0.85)
        if edge == 0:
            px = (-0.5 + s, along * cam.H)
        elif edge == 1:
            px = (cam.W - 0.5 - s, along * cam.H)
        elif edge == 2:
            px = (along * cam.W, -0.5 + s)
        else:
            px = (along * cam.W, cam.H - 0.5 - s)
        pose = anchored_pose(rig, view, R_m, SPHERES[target][1], px, d)
        if not 0.35 <= np.linalg.norm(pose.t) <= 1.5:
            continue
        if not all_in_view(rig, pose, 3.0, skip=(cam.name, target)):
            continue
        f = in_image_fraction(cam, sphere_centres(pose.in_cam(cam))[target])
        if f > 0.9:
            continue
        notes = "%s; %s sphere %s past the %s edge of the %s image" % (
            angles_note(angles), SPHERES[target][0], "wholly" if f == 0 else "partly",
            ["left", "right", "top", "bottom"][edge], cam.name)
        return pose, base_spec("clear"), {}, {"edge_sphere": SPHERES[target][0], "edge_view": cam.name}, notes
    raise RuntimeError("edge: no layout found")


def cond_noise_jpeg(rig, rng, index):
    pose, spec, _, extra, notes = cond_standard(rig, rng)
    post = {"noise": True, "full_well_e": float(rng.uniform(800, 3000)), "read_noise_e": float(rng.uniform(3, 12)),
            "jpeg_quality": int(rng.integers(40, 71))}
    extra = {"jpeg_quality": post["jpeg_quality"], "full_well_e": round(post["full_well_e"]),
             "read_noise_e": round(post["read_noise_e"], 1)}
    return pose, spec, post, extra, notes + "; shot+read noise, JPEG q%d" % post["jpeg_quality"]


def cond_distortion(rig, rng, index):
    for _ in range(20000):
        view = int(rng.integers(2))
        cam = rig.cams[view]
        corner = int(rng.integers(4))
        R_m, angles = random_rotation(rng)
        d = rng.uniform(0.5, 1.5)
        f = cam.K[0, 0]
        hx, hy = 0.085 * f / d, 0.085 * f / d
        ox, oy = hx + rng.uniform(4, 45), hy + rng.uniform(4, 45)
        px = (ox if corner in (0, 2) else cam.W - 1 - ox, oy if corner in (0, 1) else cam.H - 1 - oy)
        pose = anchored_pose(rig, view, R_m, (0.0, -0.015, -0.013), px, d)
        if not 0.5 <= np.linalg.norm(pose.t) <= 1.5:
            continue
        if not all_in_view(rig, pose, 2.0):
            continue
        # Near the corner: the marker's spheres reach within 60 px of both corner edges.
        o = np.concatenate([sphere_outline(cam, c) for c in sphere_centres(pose.in_cam(cam))])
        dx = o[:, 0].min() if corner in (0, 2) else cam.W - 1 - o[:, 0].max()
        dy = o[:, 1].min() if corner in (0, 1) else cam.H - 1 - o[:, 1].max()
        if dx > 60 or dy > 60:
            continue
        name = ["top-left", "top-right", "bottom-left", "bottom-right"][corner]
        return pose, base_spec("clear"), {}, {"corner": name, "corner_view": cam.name}, \
            "%s; marker in the %s corner of the %s image" % (angles_note(angles), name, cam.name)
    raise RuntimeError("distortion: no layout found")


def cond_overexposed(rig, rng, index):
    pose, spec, _, _, notes = cond_standard(rig, rng)
    g = float(rng.uniform(2.5, 4.0))
    return pose, spec, {"exposure": g}, {"exposure": round(g, 3)}, notes + "; exposure x%.2f" % g


def cond_underexposed(rig, rng, index):
    pose, spec, _, _, notes = cond_standard(rig, rng)
    g = float(rng.uniform(0.15, 0.30))
    return pose, spec, {"exposure": g}, {"exposure": round(g, 3)}, notes + "; exposure x%.2f" % g


def cond_motion_blur(rig, rng, index):
    pose, spec, _, _, notes = cond_standard(rig, rng, 0.35, 1.5)
    tdir = rng.normal(size=3)
    tdir /= np.linalg.norm(tdir)
    # Mostly yaw/pitch: a vehicle's roll about the optical axis hardly blurs the marker.
    rdir = np.array([rng.normal(), rng.normal(), 0.3 * rng.normal()])
    rdir /= np.linalg.norm(rdir)
    dist = float(rng.uniform(0.005, 0.020))
    ang = math.radians(rng.uniform(1.0, 3.0))
    motion = {"tvec": tdir * dist, "rvec": rdir * ang, "subframes": MOTION_SUBFRAMES}
    # Length of each sphere's smear in the left image, start to end of the exposure.
    c0 = rig.left.project(sphere_centres(pose.moved(-0.5 * motion["rvec"], -0.5 * motion["tvec"])))
    c1 = rig.left.project(sphere_centres(pose.moved(0.5 * motion["rvec"], 0.5 * motion["tvec"])))
    smear = np.linalg.norm(c1 - c0, axis=1)
    blur = float(smear.max())
    # The smear against each sphere's own image size (its outline's longer extent at mid-exposure):
    # a far sphere is lost to a shorter smear than a near one.
    diameters = [float((o.max(axis=0) - o.min(axis=0)).max())
                 for o in (sphere_outline(rig.left, c) for c in sphere_centres(pose))]
    extra = {"motion_translation_m": round(dist, 4), "motion_rotation_deg": round(math.degrees(ang), 3),
             "motion_blur_px": round(blur, 1),
             "motion_blur_diameters": round(max(s / d for s, d in zip(smear, diameters)), 2)}
    return pose, spec, {"motion": motion}, extra, notes + "; %.1f mm / %.2f deg during exposure (%.0f px smear), " \
        "truth at mid-exposure" % (dist * 1000, math.degrees(ang), blur)


CONDITION_BUILDERS = {
    "clear": cond_clear, "turbid_near": cond_turbid_near, "turbid_far": cond_turbid_far,
    "side_light": cond_side_light, "bubbles": cond_bubbles, "occlusion": cond_occlusion, "edge": cond_edge,
    "noise_jpeg": cond_noise_jpeg, "distortion": cond_distortion, "overexposed": cond_overexposed,
    "underexposed": cond_underexposed, "motion_blur": cond_motion_blur, "cast": cond_cast,
    "noise_yuyv": cond_noise_jpeg, "noise_mjpg90": cond_noise_jpeg,
}


# ----------------------------------------------------------------------------------------------------
# One pair


def render_camera_image(cam, pose, spec, post, workdir, tag, noise_rng):
    """8-bit BGR image of one view as the camera delivers it: the water render at the exposure `post`
    asks for, then the sensor noise and stream when it asks for them (drawn from noise_rng)."""
    lin = render_view(cam, pose, spec, workdir, tag, post.get("motion"))
    lin = lin * (BASE_EXPOSURE * post.get("exposure", 1.0))
    if post.get("noise"):
        return sensor_noise_jpeg(lin, noise_rng, post)
    return to_8bit(lin)


def sphere_visibility(cam, pose, spec, workdir, tag):
    """({sphere: visible share}, {sphere: share hidden by bars}) in one view: the share of each sphere's
    image area on the sensor, less what the bars hide as measured from sphere-ID renders with and without
    them (the second dict is empty when the scene has no bars)."""
    centres = sphere_centres(pose.in_cam(cam))
    vis = {}
    hidden = {}
    if spec.get("bars"):
        with_b = render_mask(cam, pose, spec, workdir, tag + "_mw", True)
        without_b = render_mask(cam, pose, spec, workdir, tag + "_mo", False)
    for i, (name, _, _) in enumerate(SPHERES):
        f = in_image_fraction(cam, centres[i])
        if spec.get("bars"):
            ch = 2 - i  # BGR
            a_with = float(with_b[:, :, ch].sum())
            a_without = float(without_b[:, :, ch].sum())
            h = 0.0 if a_without < 1.0 else max(0.0, 1.0 - a_with / a_without)
            hidden[name] = round(h, 3)
            f *= 1.0 - h
        vis[name] = round(f, 3)
    return vis, hidden


def pair_rng(seed, condition, index):
    return np.random.default_rng([int(seed), CONDITIONS.index(POSE_TWIN.get(condition, condition)), int(index)])


def make_pair(rig, condition, index, seed, out_dir, pose_override=None, stream=None):
    """Render pair `index` of `condition` into out_dir/<condition>/ and return its manifest entry.

    stream, where given (see stream_arg), replaces how a noisy pair reaches the estimator (its drawn
    JPEG quality); every draw stays as it was, so the pair differs only in that.
    """
    rng = pair_rng(seed, condition, index)
    pose, spec, post, extra, notes = CONDITION_BUILDERS[condition](rig, rng, index)
    if condition in CONDITION_STREAMS:
        stream = stream_arg(CONDITION_STREAMS[condition])
    if stream is not None and post.get("noise"):
        post["stream"] = stream["stream"]
        extra["stream"] = stream["stream"]
        if stream["stream"] == "yuyv":
            del post["jpeg_quality"], extra["jpeg_quality"]
            notes = re.sub(r"JPEG q\d+", "YUYV 4:2:2", notes)
        else:
            post["jpeg_quality"] = extra["jpeg_quality"] = stream["jpeg_quality"]
            notes = re.sub(r"JPEG q\d+", "JPEG q%d" % stream["jpeg_quality"], notes)
    if pose_override is not None:
        pose = pose_override
        notes = "pose given by the caller"
    noise_rng = np.random.default_rng([int(seed), CONDITIONS.index(POSE_TWIN.get(condition, condition)), int(index),
                                       7])
    entry = {"condition": condition}
    os.makedirs(os.path.join(out_dir, condition), exist_ok=True)
    # Debian's povray.conf lets POV-Ray write only under /tmp.
    work = tempfile.mkdtemp(prefix="water_set_", dir="/tmp" if os.path.isdir("/tmp") else None)
    try:
        for cam in rig.cams:
            tag = "%s_%03d_%s" % (condition, index, cam.name)
            img8 = render_camera_image(cam, pose, spec, post, work, tag, noise_rng)
            rel = "%s/%03d_%s.png" % (condition, index, cam.name)
            cv2.imwrite(os.path.join(out_dir, rel), img8, [cv2.IMWRITE_PNG_COMPRESSION, 9])
            entry[cam.name] = rel
            vis, hidden = sphere_visibility(cam, pose, spec, work, tag)
            entry["spheres_visible_" + cam.name] = vis
            if hidden and condition == "occlusion":
                entry["occluded_fraction_" + cam.name] = hidden[extra["occluded_sphere"]]
    finally:
        shutil.rmtree(work, ignore_errors=True)

    entry["t_cl_marker_m"] = [round(float(v), 6) for v in pose.t]
    entry["q_cl_marker_wxyz"] = [round(float(v), 8) for v in quat_wxyz(pose.R)]
    entry["range_m"] = round(float(np.linalg.norm(pose.t)), 4)
    w = spec["water"]
    entry["water"] = {"jerlov_type": w["jerlov"], "extinction_rgb_per_m": [round(v, 4) for v in w["extinction"]]}
    entry.update(extra)
    entry["notes"] = notes
    return entry


# ----------------------------------------------------------------------------------------------------


def finished_pairs(out_dir, seed, stream, jobs):
    """The manifest entries of out_dir that this run would render again: same seed and stream, images
    on disk."""
    path = os.path.join(out_dir, "manifest.json")
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        manifest = json.load(f)
    if manifest.get("seed") != seed:
        raise SystemExit("%s: seed %s, not %d; --resume needs the same seed" % (path, manifest.get("seed"), seed))
    spec = stream["spec"] if stream else None
    if manifest.get("stream") != spec:
        raise SystemExit("%s: rendered with --stream %s, this run with %s; --resume needs the same" %
                         (path, manifest.get("stream") or "none", spec or "none"))
    index = {}
    for entry in manifest["pairs"]:
        rel = entry.get("left", "")
        try:
            i = int(os.path.basename(rel).split("_")[0])
        except ValueError:
            continue
        if all(os.path.exists(os.path.join(out_dir, entry[k])) for k in ("left", "right")):
            index[(entry["condition"], i)] = entry
    return {k: index[k] for k in jobs if k in index}


def stream_arg(text):
    """`yuyv`, or `mjpg:Q` with a JPEG quality Q from 1 to 100."""
    if text == "yuyv":
        return {"stream": "yuyv", "spec": text}
    kind, _, q = text.partition(":")
    if kind == "mjpg" and q.isdigit() and 1 <= int(q) <= 100:
        return {"stream": "mjpg", "jpeg_quality": int(q), "spec": text}
    raise argparse.ArgumentTypeError("%r is neither yuyv nor mjpg:Q with a JPEG quality Q from 1 to 100" % text)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, help="output folder")
    ap.add_argument("--pairs-per-condition", type=int, default=30)
    ap.add_argument("--conditions", default=",".join(DEFAULT_CONDITIONS), help="comma-separated subset of: "
                    + ", ".join(CONDITIONS) + " (default: all but " + ", ".join(ON_DEMAND_CONDITIONS) + ")")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--jobs", type=int, default=2, help="pairs rendered at once (one POV-Ray thread each)")
    ap.add_argument("--calibration", default=DEFAULT_CALIBRATION)
    ap.add_argument("--stream", type=stream_arg, default=None,
                    help="how noise + JPEG's pairs reach the estimator, in place of each pair's JPEG quality "
                    "drawn from 40-70: mjpg:Q (quality Q) or yuyv (uncompressed 4:2:2, as the V4L2 driver "
                    "decodes it); every other draw is kept, so the same poses and noise show what the "
                    "stream alone costs")
    ap.add_argument("--resume", action="store_true", help="keep the pairs an earlier run of the same seed "
                    "already wrote to --out (pairs are deterministic per seed, condition and index)")
    ap.add_argument("--draft", action="store_true", help="render at the real sampling with 2x2 lamp samples "
                    "(about 4x cheaper; softer sphere rims, noisier lamp shadows)")
    args = ap.parse_args(argv)
    if args.draft:
        RENDER.update(DRAFT_RENDER)

    if shutil.which("povray") is None:
        raise SystemExit("povray not found (Debian package 'povray')")
    conds = [c.strip() for c in args.conditions.split(",") if c.strip()]
    bad = [c for c in conds if c not in CONDITIONS]
    if bad:
        raise SystemExit("unknown condition(s): %s" % ", ".join(bad))
    rig = Rig(args.calibration)
    for cam in rig.cams:
        cam.ideal(RENDER["ideal_scale"])
    os.makedirs(args.out, exist_ok=True)

    # Index-major, so a run stopped early covers every condition evenly.
    jobs = [(c, i) for i in range(args.pairs_per_condition) for c in conds]
    start = time.time()
    entries = {}
    if args.resume:
        entries = finished_pairs(args.out, args.seed, args.stream, jobs)
        print("resuming: %d of %d pairs already rendered" % (len(entries), len(jobs)), flush=True)

    def write_manifest():
        # Rewritten after every pair, so a run that is stopped keeps what it finished.
        manifest = {"calibration": os.path.basename(args.calibration), "generator": "render_water_set.py",
                    "seed": args.seed, "pairs": [entries[k] for k in jobs if k in entries]}
        if args.stream is not None:
            manifest["stream"] = args.stream["spec"]
        tmp = os.path.join(args.out, "manifest.json.tmp")
        with open(tmp, "w") as f:
            json.dump(manifest, f, indent=1)
            f.write("\n")
        os.replace(tmp, os.path.join(args.out, "manifest.json"))

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futs = {pool.submit(make_pair, rig, c, i, args.seed, args.out, None, args.stream): (c, i)
                for c, i in jobs
                if (c, i) not in entries}
        for n, fut in enumerate(concurrent.futures.as_completed(futs), 1):
            c, i = futs[fut]
            entries[(c, i)] = fut.result()
            write_manifest()
            print("[%d/%d] %s %03d  %.0f s" % (n, len(futs), c, i, time.time() - start), flush=True)
    took = time.time() - start
    print("rendered %d pairs in %.1f s (%.1f min) into %s" % (len(futs), took, took / 60, args.out))


if __name__ == "__main__":
    main()
