#!/usr/bin/env bash
# Runs the commands behind the README's headline figures and prints the table the README shows;
# with --write it also replaces the table in README.md (between the results markers).
# Usage: bash deploy/results.sh [--write] [--trials N] [--jobs J]   (after bash deploy/setup.sh)
set -euo pipefail
cd "$(dirname "$0")/.."

write=0
trials=100
jobs=$(nproc)
while [ $# -gt 0 ]; do
  case $1 in
    --write) write=1 ;;
    --trials) trials=${2:?--trials takes a number}; shift ;;
    --jobs) jobs=${2:?--jobs takes a number}; shift ;;
    *) echo "deploy/results.sh: unknown option '$1' (--write, --trials N, --jobs J)" >&2; exit 2 ;;
  esac
  shift
done
rovctl=./build/rovctl
if [ ! -x "$rovctl" ]; then
  echo "deploy/results.sh: no $rovctl (build it first: bash deploy/setup.sh)" >&2
  exit 2
fi
recharge_trials=$(( trials / 2 > 0 ? trials / 2 : 1 ))
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# Each row: a name, the command as the README prints it (rovctl for ./build/rovctl), its JSON.
run() {
  local name=$1; shift
  echo "deploy/results.sh: $*" >&2
  "$rovctl" "$@" >"$out/$name.json"
  printf '%s\n' "$*" >"$out/$name.cmd"
}
run clear sim --trials "$trials" --seed 1 --jobs "$jobs" --json
run recharge sim --mission recharge --trials "$recharge_trials" --seed 1 --jobs "$jobs" --json
run ardusub sim --trials "$trials" --seed 1 --jobs "$jobs" --config deploy/config/sim-ardusub.yaml --json
run water_set bench --set tests/data/water_set --frames 10 --seed 0 --json
run cpu bench --json

table=$(python3 - "$out" <<'PY'
import json, os, sys
out = sys.argv[1]
def load(name):
    with open(os.path.join(out, name + ".json")) as f:
        return json.load(f)
def cmd(name):
    with open(os.path.join(out, name + ".cmd")) as f:
        return "`rovctl " + f.read().strip() + "`"
def docking(d):
    return (f"{d['docked']} of {d['trials']} docked; lateral error p95 "
            f"{d['final_lateral_error_mm_p95']:.1f} mm, yaw p95 {d['final_yaw_error_deg_p95']:.2f} deg; "
            f"time to dock median {d['time_to_dock_s_median']:.1f} s; "
            f"{d['touched_off_centre']} touched over 20 mm off the axis")
rows = []
d = load("clear")
rows.append((f"docking in clear water, {d['trials']} randomised trials (start 0.6-1.5 m out, "
             "current up to 0.1 m/s)", docking(d), cmd("clear")))
d = load("recharge"); r = d["recharge"]
rows.append((f"recharging mission, {d['trials']} trials (current up to 0.15 m/s turning, gusts)",
             f"{r['recharged']} of {d['trials']} docked, charged and departed; holding the seat took a "
             f"median {r['hold_wh_median']:.1f} Wh of {r['charged_wh_median']:.0f} Wh charged",
             cmd("recharge")))
d = load("ardusub")
rows.append((f"hardware in the loop: the ArduSub driver over MAVLink against a mock ArduSub, "
             f"{d['trials']} trials", docking(d), cmd("ardusub")))
d = load("water_set")
c = [x for x in d["conditions"] if x["condition"] != "all"]
pairs = sum(x["pairs"] for x in c); right = sum(x["success"] for x in c)
false_ok = sum(x["false_ok"] for x in c)
rows.append((f"estimator on the committed POV-Ray water-set sample, {len(c)} conditions",
             f"{right} of {pairs} pairs right and ok; {false_ok} ok but wrong", cmd("water_set")))
d = load("cpu")
rows.append(("estimator CPU per frame, one core, 100 cold-started rendered pairs",
             f"mean {d['estimator_ms_per_frame']:.1f} ms, p95 {d['estimator_ms_per_frame_p95']:.1f} ms "
             "(of the 33 ms tick)", cmd("cpu")))
print("| what | figure | command |")
print("|---|---|---|")
for r in rows:
    print("| " + " | ".join(r) + " |")
PY
)
echo "$table"

if [ "$write" -eq 1 ]; then
  python3 - README.md "$table" <<'PY'
import re, sys
path, table = sys.argv[1], sys.argv[2]
text = open(path, encoding="utf-8").read()
block = re.compile(r"(<!-- results:begin -->\n).*?(<!-- results:end -->)", re.S)
if not block.search(text):
    sys.exit(f"deploy/results.sh: {path} has no <!-- results:begin --> ... <!-- results:end --> block")
text = block.sub(lambda m: m.group(1) + table + "\n" + m.group(2), text)
with open(path + ".tmp", "w", encoding="utf-8") as f:
    f.write(text)
import os
os.replace(path + ".tmp", path)
print(f"deploy/results.sh: wrote the table into {path}", file=sys.stderr)
PY
fi
