#!/usr/bin/env bash
# The estimator's cost on an arm64 board, from a figure no machine's speed changes: the arm64
# instructions one frame executes, counted under Debian's qemu-user by a small plugin
# (deploy/qemu_insn_count.c), on still pairs of the committed water set. Prints instructions per
# frame per pair and the ms per frame they take on a Cortex-A72 at 1.5 GHz and a Cortex-A76 at
# 2.4 GHz for the range of instructions per cycle docs/estimator.md ("On an arm64 board") argues.
# Needs the arm64 build: bash deploy/setup.sh --arch arm64 --build-only
# Usage: bash deploy/arm64-budget.sh [FRAMES] (frames per pair, default 10)
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=${ROVCTL_ARM64_BUILD:-build-arm64}
frames=${1:-10}
root=$PWD/$build_dir/sysroot
if ! command -v qemu-aarch64 >/dev/null; then
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  # qemu-user's dynamic qemu-aarch64 loads plugins; the static one in qemu-user-static cannot.
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends qemu-user
fi
plugin=$build_dir/qemu_insn_count.so
gcc -shared -fPIC -O2 -Wall -Wextra -Werror -o "$plugin" deploy/qemu_insn_count.c

# The instructions of one run of `rovctl estimate` over N frames of one pair (one thread, so the
# count is the estimator's alone and the same on every run).
count() {
  OPENCV_FOR_THREADS_NUM=1 qemu-aarch64 -L "$root" -plugin "$PWD/$plugin" "$build_dir/rovctl" \
    estimate --config deploy/config/sim.yaml --left "$1" --right "$2" --frames "$3" --seed 1 \
    2>&1 >/dev/null | sed -n 's/^guest instructions: //p'
}

# Instructions per cycle assumed (low, high): docs/estimator.md says where they come from.
a72=(0.7 1.3)
a76=(1.2 2.2)
printf '%-24s %14s %22s %22s\n' pair "insns/frame" "A72@1.5GHz ms" "A76@2.4GHz ms"
for pair in clear/000 clear/001 clear/002 side_light/000 occlusion/000 motion_blur/000; do
  left=tests/data/water_set/${pair}_left.png
  right=tests/data/water_set/${pair}_right.png
  [ -f "$left" ] || continue
  one=$(count "$left" "$right" 1)
  many=$(count "$left" "$right" $((frames + 1)))
  per=$(((many - one) / frames))
  awk -v n="$per" -v p="$pair" -v a="${a72[*]}" -v b="${a76[*]}" 'BEGIN {
    split(a, x, " "); split(b, y, " ");
    printf "%-24s %14.0f %10.1f - %-9.1f %10.1f - %-9.1f\n", p, n,
      n / (x[2] * 1.5e6), n / (x[1] * 1.5e6), n / (y[2] * 2.4e6), n / (y[1] * 2.4e6) }'
done
