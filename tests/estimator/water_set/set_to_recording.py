#!/usr/bin/python3
# A rendered water set's pairs as a recording in `rovctl record`'s format (deploy/recording-format.md),
# so commands that read recordings (`rovctl tune-marker --pairs DIR`) can run on them.
"""Copy one condition's pairs of a water set into DIR/frames.csv, DIR/left/, DIR/right/.

DIR also gets the calibration the set was rendered with (stereo_calibration.yaml) and a manifest.json
that names the copied images, so the same folder is a validation set for `rovctl bench --set DIR`.
Stamps are 33 ms apart, sequence numbers count from 0. Never writes into an existing, non-empty DIR.
"""

import argparse
import json
import os
import shutil
import sys


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--set", required=True, help="a water set (DIR/manifest.json)")
    ap.add_argument("--condition", required=True)
    ap.add_argument("--out", required=True, help="the recording folder to write")
    ap.add_argument("--pairs", default="", help="comma-separated indices among the condition's pairs, in "
                    "the manifest's order (default: all)")
    ap.add_argument("--calibration", default=os.path.normpath(os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "deploy", "config",
        "stereo_calibration.yaml")))
    args = ap.parse_args(argv)
    with open(os.path.join(args.set, "manifest.json")) as f:
        manifest = json.load(f)
    pairs = [p for p in manifest["pairs"] if p["condition"] == args.condition]
    if args.pairs:
        pairs = [pairs[int(i)] for i in args.pairs.split(",")]
    if not pairs:
        raise SystemExit("%s: no pairs of condition %r" % (args.set, args.condition))
    if os.path.isdir(args.out) and os.listdir(args.out):
        raise SystemExit("%s exists and is not empty" % args.out)
    for side in ("left", "right"):
        os.makedirs(os.path.join(args.out, side), exist_ok=True)
    rows = ["sequence,left_stamp_ns,right_stamp_ns,left_file,right_file"]
    entries = []
    for i, p in enumerate(pairs):
        entry = dict(p)
        for side in ("left", "right"):
            rel = "%s/%06d.png" % (side, i)
            shutil.copyfile(os.path.join(args.set, p[side]), os.path.join(args.out, rel))
            entry[side] = rel
        stamp = 1000000000 + i * 33000000
        rows.append("%d,%d,%d,%s,%s" % (i, stamp, stamp, entry["left"], entry["right"]))
        entries.append(entry)
    shutil.copyfile(args.calibration, os.path.join(args.out, "stereo_calibration.yaml"))
    with open(os.path.join(args.out, "manifest.json"), "w") as f:
        json.dump({"calibration": "stereo_calibration.yaml", "generator": manifest.get("generator"),
                   "seed": manifest.get("seed"), "pairs": entries}, f, indent=1)
        f.write("\n")
    with open(os.path.join(args.out, "frames.csv"), "w") as f:
        f.write("\n".join(rows) + "\n")
    print("%d pairs of %s into %s" % (len(entries), args.condition, args.out))


if __name__ == "__main__":
    sys.exit(main())
