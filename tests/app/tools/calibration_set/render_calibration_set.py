#!/usr/bin/python3
# Independent validation set for `rovctl calibrate`: stereo pairs of a chessboard drawn through a
# known rig (OpenCV's lens model), with planted bad views, written as `rovctl record` writes.
"""Render a chessboard calibration set with known truth.

Each real pixel is looked up per 3x3 sub-pixel sample: cv2.undistortPointsIter(K, D) gives its ray,
the ray meets the board plane, and the board's square there (computed, not a texture) gives the
grey level; the nine samples are averaged. Nothing is shared with rovctl's code. See README.md.
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

DEFAULT_CALIBRATION = os.path.normpath(os.path.join(HERE, "..", "..", "..", "..", "deploy",
                                                    "config", "stereo_calibration.yaml"))
SUPERSAMPLE = 3
# Planted bad views: kind -> the reason rovctl must give (a prefix of it).
BAD_KINDS = {
    "one_image": "board not in the right image",
    "edge": "board cut by the image edge",
    "smeared": "too blurred",
    "absent": "no board",
}


def read_rig(path):
    fs = cv2.FileStorage(path, cv2.FILE_STORAGE_READ)
    rig = {k: fs.getNode(k).mat() for k in ("K1", "D1", "K2", "D2", "R", "T")}
    size = fs.getNode("image_size")
    rig["size"] = (int(size.at(0).real()), int(size.at(1).real()))
    fs.release()
    rig["T"] = rig["T"].reshape(3)
    rig["D1"] = rig["D1"].reshape(-1)
    rig["D2"] = rig["D2"].reshape(-1)
    return rig


def camera_rays(K, D, size):
    """Normalised rays (x, y) of every sub-pixel sample, shape (H*S, W*S)."""
    w, h = size
    s = SUPERSAMPLE
    offsets = (np.arange(s) + 0.5) / s - 0.5
    us = (np.arange(w)[:, None] + offsets[None, :]).reshape(-1)
    vs = (np.arange(h)[:, None] + offsets[None, :]).reshape(-1)
    uu, vv = np.meshgrid(us, vs)
    pts = np.stack([uu.ravel(), vv.ravel()], axis=1).astype(np.float64).reshape(-1, 1, 2)
    crit = (cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 50, 1e-12)
    n = cv2.undistortPointsIter(pts, K, D, None, None, crit).reshape(h * s, w * s, 2)
    return n[..., 0], n[..., 1]


def background(rng, size):
    """A low-contrast blotchy scene behind the board (left and right differ: it is far away)."""
    w, h = size
    small = rng.uniform(70, 150, (6, 8)).astype(np.float32)
    return cv2.resize(small, (w, h), interpolation=cv2.INTER_CUBIC)


def render_board(rays, R_cb, t_cb, board, bg, lighting):
    """Grey image of the board at pose (R_cb, t_cb) in this camera; bg where it is not."""
    xs, ys = rays
    cols, rows, sq = board
    n = R_cb[:, 2]
    denom = n[0] * xs + n[1] * ys + n[2]
    with np.errstate(divide="ignore", invalid="ignore"):
        s = float(n @ t_cb) / denom
    px, py, pz = s * xs - t_cb[0], s * ys - t_cb[1], s - t_cb[2]
    X = R_cb[0, 0] * px + R_cb[1, 0] * py + R_cb[2, 0] * pz
    Y = R_cb[0, 1] * px + R_cb[1, 1] * py + R_cb[2, 1] * pz
    i = np.floor(X / sq)
    j = np.floor(Y / sq)
    on_paper = (s > 0) & (i >= -2) & (i <= cols) & (j >= -2) & (j <= rows)
    in_squares = (i >= -1) & (i <= cols - 1) & (j >= -1) & (j <= rows - 1)
    black = in_squares & (((i + j) % 2) == 0)
    grey = np.where(black, 35.0, 215.0) * lighting
    h, w = bg.shape
    big_bg = np.repeat(np.repeat(bg, SUPERSAMPLE, axis=0), SUPERSAMPLE, axis=1)
    img = np.where(on_paper, grey, big_bg)
    return img.reshape(h, SUPERSAMPLE, w, SUPERSAMPLE).mean(axis=(1, 3)).astype(np.float32)


def rotation(axis_angle):
    R, _ = cv2.Rodrigues(np.asarray(axis_angle, dtype=np.float64).reshape(3, 1))
    return R


def board_corners(board):
    cols, rows, sq = board
    return np.array([[c * sq, r * sq, 0.0] for r in range(rows) for c in range(cols)])


def project(pts_left, rig, cam):
    if cam == "left":
        R, t, K, D = np.eye(3), np.zeros(3), rig["K1"], rig["D1"]
    else:
        R, t, K, D = rig["R"], rig["T"], rig["K2"], rig["D2"]
    p = pts_left @ R.T + t
    uv, _ = cv2.projectPoints(p.reshape(-1, 1, 3), np.zeros(3), np.zeros(3), K, D)
    return uv.reshape(-1, 2), p[:, 2]


def inside(uv, z, size, margin):
    w, h = size
    return (z > 0) & (uv[:, 0] >= margin) & (uv[:, 0] <= w - 1 - margin) & \
        (uv[:, 1] >= margin) & (uv[:, 1] <= h - 1 - margin)


def sample_pose(rng, rig, board, kind):
    """Board pose (R_lb, t_lb) in the left camera: whole in both images, or cut for 'edge'."""
    cols, rows, sq = board
    centre = np.array([(cols - 1) * sq / 2, (rows - 1) * sq / 2, 0.0])
    # The squares (the outer ones included) must be whole in both images; the white margin around
    # them may be cut, as it is when a board is held near the image's corners.
    outline = np.array([[-sq, -sq, 0], [cols * sq, -sq, 0], [-sq, rows * sq, 0],
                        [cols * sq, rows * sq, 0]])
    corners = board_corners(board)
    K = rig["K1"]
    w, h = rig["size"]
    for _ in range(10000):
        z = rng.uniform(0.33, 1.0)
        u = rng.uniform(0.0, w)
        v = rng.uniform(0.0, h)
        tilt = math.radians(rng.uniform(0.0, 50.0))
        axis_dir = rng.uniform(0.0, 2 * math.pi)
        roll = math.radians(rng.uniform(-25.0, 25.0))
        R = rotation([tilt * math.cos(axis_dir), tilt * math.sin(axis_dir), 0.0]) @ \
            rotation([0.0, 0.0, roll])
        target = np.array([(u - K[0, 2]) / K[0, 0] * z, (v - K[1, 2]) / K[1, 1] * z, z])
        t = target - R @ centre
        paper = outline @ R.T + t
        pts = corners @ R.T + t
        uvl, zl = project(pts, rig, "left")
        uvr, zr = project(pts, rig, "right")
        pl, zpl = project(paper, rig, "left")
        pr, zpr = project(paper, rig, "right")
        if np.any(zl < 0.2) or np.any(zr < 0.2):
            continue
        if kind == "edge":
            share = inside(uvl, zl, (w, h), 0).mean()
            if 0.4 <= share <= 0.75:
                return R, t
            continue
        if inside(pl, zpl, (w, h), 2).all() and inside(pr, zpr, (w, h), 2).all():
            return R, t
    raise RuntimeError("no pose found")


def water(img_grey, rng, condition, z_m):
    """BGR image of a grey render under the condition's water."""
    if condition == "clear":
        bgr = np.repeat(img_grey[..., None], 3, axis=2)
        bgr = cv2.GaussianBlur(bgr, (0, 0), 0.5)
        noise = 2.0
    else:
        # Underwater cast: red absorbed, a blue-green veil of backscatter that grows with range,
        # lower contrast, optical blur and more sensor noise.
        gains = np.array([0.95, 0.80, 0.35]) * math.exp(-0.4 * z_m)
        veil = np.array([70.0, 60.0, 12.0]) * (1.0 - math.exp(-0.4 * z_m))
        bgr = img_grey[..., None] * gains[None, None, :] + veil[None, None, :]
        bgr = cv2.GaussianBlur(bgr.astype(np.float32), (0, 0), 1.0)
        noise = 4.0
    bgr = bgr + rng.normal(0.0, noise, bgr.shape)
    return np.clip(np.rint(bgr), 0, 255).astype(np.uint8)


def smear(img, length_px):
    k = np.zeros((length_px, length_px), np.float32)
    np.fill_diagonal(k, 1.0)
    return cv2.filter2D(img, -1, k / k.sum())


def plan(pairs, seed):
    """Which views are planted bad ones: two of each kind spread over 40 pairs, one each below."""
    kinds = list(BAD_KINDS)
    per_kind = 2 if pairs >= 32 else 1
    bad = [k for k in kinds for _ in range(per_kind)]
    rng = np.random.default_rng(seed + 1000)
    slots = sorted(rng.choice(np.arange(1, pairs), size=len(bad), replace=False))
    order = rng.permutation(len(bad))
    kinds_at = {int(slots[i]): bad[order[i]] for i in range(len(bad))}
    return [kinds_at.get(i, "good") for i in range(pairs)]


def render_pair(index, kind, rig, rays, board, condition, seed):
    rng = np.random.default_rng([seed, index])
    bg_l = background(rng, rig["size"])
    bg_r = background(rng, rig["size"])
    lighting = rng.uniform(0.8, 1.1)
    if kind == "absent":
        grey_l, grey_r, z, R, t = bg_l, bg_r, 1.0, None, None
    else:
        R, t = sample_pose(rng, rig, board, kind)
        z = float(t[2])
        grey_l = render_board(rays["left"], R, t, board, bg_l, lighting)
        grey_r = bg_r if kind == "one_image" else render_board(
            rays["right"], rig["R"] @ R, rig["R"] @ t + rig["T"], board, bg_r, lighting)
    left = water(grey_l, rng, condition, z)
    right = water(grey_r, rng, condition, z)
    if kind == "smeared":
        left, right = smear(left, 25), smear(right, 25)
    truth = {"index": index, "kind": kind}
    if R is not None:
        truth["rvec_left"] = cv2.Rodrigues(R)[0].reshape(3).tolist()
        truth["t_left_m"] = t.tolist()
    if kind != "good":
        truth["expected_reason"] = BAD_KINDS[kind]
    return left, right, truth


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", required=True, help="recording folder to write (must not exist)")
    ap.add_argument("--pairs", type=int, default=40)
    ap.add_argument("--water", choices=["clear", "cast"], default="clear")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--calibration", default=DEFAULT_CALIBRATION, help="the true rig")
    ap.add_argument("--board", default="9x6:30", help="COLSxROWS:SQUARE_MM, inner corners")
    args = ap.parse_args()
    size_text, square_text = args.board.split(":")
    cols, rows = (int(x) for x in size_text.split("x"))
    board = (cols, rows, float(square_text) / 1000.0)
    if os.path.exists(args.out):
        sys.exit(f"{args.out}: exists")
    rig = read_rig(args.calibration)
    rays = {"left": camera_rays(rig["K1"], rig["D1"], rig["size"]),
            "right": camera_rays(rig["K2"], rig["D2"], rig["size"])}
    os.makedirs(os.path.join(args.out, "left"))
    os.makedirs(os.path.join(args.out, "right"))
    views = []
    rows_csv = ["sequence,left_stamp_ns,right_stamp_ns,left_file,right_file"]
    for index, kind in enumerate(plan(args.pairs, args.seed)):
        left, right, truth = render_pair(index, kind, rig, rays, board, args.water, args.seed)
        name = f"{index:06d}.png"
        cv2.imwrite(os.path.join(args.out, "left", name), left)
        cv2.imwrite(os.path.join(args.out, "right", name), right)
        stamp = 1_000_000_000 + index * 500_000_000
        rows_csv.append(f"{index},{stamp},{stamp + 1_000_000},left/{name},right/{name}")
        truth["name"] = "left/" + name
        views.append(truth)
    with open(os.path.join(args.out, "frames.csv"), "w") as f:
        f.write("\n".join(rows_csv) + "\n")
    truth = {"calibration": os.path.abspath(args.calibration), "board": f"chessboard:{args.board}",
             "water": args.water, "seed": args.seed, "views": views}
    with open(os.path.join(args.out, "truth.json"), "w") as f:
        json.dump(truth, f, indent=1)
    print(f"{args.out}: {args.pairs} pairs ({args.water}), "
          f"{sum(v['kind'] != 'good' for v in views)} planted bad views")


if __name__ == "__main__":
    main()
