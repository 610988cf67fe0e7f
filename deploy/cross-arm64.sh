#!/usr/bin/env bash
# The arm64 (aarch64) build, test and package, run from an amd64 Debian bookworm machine:
# Debian's cross compiler, an arm64 Debian root with the -dev packages rovctl links, the unit and
# integration tests and `rovctl bench` under qemu-aarch64-static, and rovctl_<version>_arm64.deb.
# Usage: bash deploy/setup.sh --arch arm64 [--ci | --build-only] [--target T ...] [extra cmake args...]
#   (none)         everything: build, the tests unit by unit, `rovctl params`, `rovctl sim --trials 2`
#                  and `rovctl bench` under qemu, the .deb, its contents and its dependencies
#   --ci           the part fit for CI: cross-compile rovctl and run `rovctl params` under qemu
#   --build-only   cross-compile only (no emulated tests, bench or .deb)
#   --target T     build only target T (repeatable; implies --build-only)
#   --host-only    install the host's packages and stop
#   --root-only    install the host's packages, make the arm64 root and stop (CI makes it while
#                  the native build runs)
# Environment: ROVCTL_ARM64_JOBS (default nproc), ROVCTL_ARM64_BUILD (default build-arm64).
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=${ROVCTL_ARM64_BUILD:-build-arm64}
jobs=${ROVCTL_ARM64_JOBS:-$(nproc)}
build_only=0
ci=0
stop_after=""
targets=()
cmake_args=()
while [ $# -gt 0 ]; do
  case $1 in
    --build-only) build_only=1 ;;
    --ci) ci=1 ;;
    --host-only) stop_after=host ;;
    --root-only) stop_after=root ;;
    --target) targets+=("$2"); build_only=1; shift ;;
    *) cmake_args+=("$1") ;;
  esac
  shift
done

# Host tools: the cross compiler, the emulator, the root builder, and what the tests and the .deb
# use on the host (Python for the Modbus peer, dpkg-dev for the package's dependencies).
host_packages=(crossbuild-essential-arm64 qemu-user-static mmdebstrap cmake ninja-build pkg-config
  dpkg-dev file python3 python3-pymodbus python3-serial python3-serial-asyncio socat nodejs)
# npm comes with some nodejs builds (NodeSource's) and is its own package in Debian's.
command -v npm >/dev/null 2>&1 || host_packages+=(npm)
# The arm64 packages rovctl links, plus the test libraries. OpenCV: only the modules the top
# CMakeLists.txt asks find_package for, read from it so the two lists cannot drift apart; OpenCV's
# CMake package comes from libopencv-dev, unpacked alone (see opencv_cmake_package).
opencv_modules=$(sed -n 's/^find_package(OpenCV [0-9]* REQUIRED COMPONENTS \([a-z0-9 ]*\)).*/\1/p' CMakeLists.txt)
[ -n "$opencv_modules" ] || { echo "setup arm64: CMakeLists.txt: no find_package(OpenCV ... COMPONENTS ...)" >&2; exit 2; }
root_packages=(libc6-dev libstdc++-12-dev libeigen3-dev libyaml-cpp-dev libmodbus-dev libcpp-httplib-dev
  libgtest-dev libgmock-dev libbenchmark-dev)
for m in $opencv_modules; do root_packages+=("libopencv-$m-dev"); done
mirror=http://deb.debian.org/debian
security_mirror=http://deb.debian.org/debian-security
root=$PWD/$build_dir/sysroot

install_host_packages() {
  local missing=() p
  for p in "${host_packages[@]}"; do
    [[ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)" == "install ok installed" ]] || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return
  echo "setup arm64: installing ${missing[*]}"
  local sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# OpenCV's CMake package (OpenCVConfig.cmake) ships only in libopencv-dev, which depends on every
# OpenCV module (VTK, Qt, ...). Unpack that one package without its dependencies, and drop the
# existence checks of the modules that are not in the root: rovctl's COMPONENTS are checked by
# find_package itself.
opencv_cmake_package() {
  local deb
  deb=$(ls "$root"/var/cache/rovctl-opencv-dev/libopencv-dev_*_arm64.deb)
  dpkg-deb -x "$deb" "$root/var/cache/rovctl-opencv-dev/x"
  cp -r "$root/var/cache/rovctl-opencv-dev/x/usr/lib/aarch64-linux-gnu/cmake" "$root/usr/lib/aarch64-linux-gnu/"
  cp "$root/var/cache/rovctl-opencv-dev/x/usr/lib/aarch64-linux-gnu/pkgconfig/opencv4.pc" \
    "$root/usr/lib/aarch64-linux-gnu/pkgconfig/"
  local modules=$root/usr/lib/aarch64-linux-gnu/cmake/opencv4/OpenCVModules-release.cmake lib module
  for lib in $(grep -o 'libopencv_[a-z0-9_]*\.so\.[0-9.]*[0-9]' "$modules" | sort -u); do
    [ -e "$root/usr/lib/aarch64-linux-gnu/$lib" ] && continue
    module=${lib#lib}
    module=${module%%.so*}
    sed -i "/_cmake_import_check_targets ${module} )/d; /_cmake_import_check_files_for_${module} /d" "$modules"
  done
  rm -rf "$root/var/cache/rovctl-opencv-dev"
}

# An unpacked root runs no maintainer scripts, so the alternatives they would register are made
# here: the reference BLAS and LAPACK that OpenCV's core links.
link_alternatives() {
  local lib=$root/usr/lib/aarch64-linux-gnu
  ln -sfn blas/libblas.so.3 "$lib/libblas.so.3"
  ln -sfn lapack/liblapack.so.3 "$lib/liblapack.so.3"
}

# The arm64 root: unpacked Debian packages (no maintainer scripts, so no emulation needed), made
# again when the package list changes. The .debs stay in var/cache/apt/archives: the package's
# dependencies are read from them.
make_root() {
  local stamp=$root/.rovctl-packages
  [ -f "$stamp" ] && [ "$(cat "$stamp")" == "${root_packages[*]}" ] && return
  rm -rf "$root"
  mkdir -p "$(dirname "$root")"
  echo "setup arm64: making the arm64 root $root"
  local list
  list=$(
    IFS=,
    echo "${root_packages[*]}"
  )
  mmdebstrap --variant=extract --arch=arm64 --include="$list" --skip=cleanup/apt/cache,cleanup/apt/lists \
    bookworm "$root" "deb $mirror bookworm main" "deb $mirror bookworm-updates main" \
    "deb $security_mirror bookworm-security main"
  # libopencv-dev alone, through the root's own (verified) package lists.
  mkdir -p "$root/var/cache/rovctl-opencv-dev"
  (cd "$root/var/cache/rovctl-opencv-dev" && apt-get -q -o Dir="$root/" \
    -o Dir::State::status="$root/var/lib/dpkg/status" -o APT::Architecture=arm64 \
    -o APT::Architectures::=arm64 -o Debug::NoLocking=1 download libopencv-dev)
  opencv_cmake_package
  link_alternatives
  echo "${root_packages[*]}" >"$stamp"
}

# Tests that cannot run under user-mode emulation, each as "ctest regex|reason".
emulation_skips=(
  "ThrustersSafe.ExecStopPostDisarmsTheControllerAfterSigkill|rovctl run must arm and thrust within 20 s on a real-time 33 ms tick; emulated, a tick's estimate takes about 0.5 s"
  "ArdusubPeer.RunOverMavlink|its ArduSub peer times rovctl run's neutral command to two 33 ms ticks after a loss; emulated, a tick's estimate takes about 0.5 s"
)
# Not arm64 code, and so not run here (the native build runs them): the include-layering probes
# (compile checks), the lint and docs checks (scripts over the sources), the water-set scripts
# (Python over the committed images), and the slow closed-loop trials and browser test.
native_only_labels='slow|layering|lint|docs|water_set|browser'

# The test units (tests/CMakeLists.txt's rovctl_add_test_unit calls).
units=(hal estimator control drivers runtime tools view cli)

# Why each test named in $2 (one a line) skipped itself: gtest's GTEST_SKIP message (the line
# after "Skipped"), or for a script that exits 77 its last line of output; read from ctest's log
# of the last run ($1).
skip_reasons() {
  awk -v names="$2" '
    BEGIN { n = split(names, list, "\n"); for (i = 1; i <= n; i++) if (list[i] != "") wanted[list[i]] = 1 }
    /^[0-9]+\/[0-9]+ Test: / { name = $0; sub(/^[0-9]+\/[0-9]+ Test: /, "", name); reason = ""; last = ""; next }
    /^Output:/ { out = 1; next }
    /^<end of output>/ {
      out = 0
      if (name in wanted) printf "    skipped by itself: %s: %s\n", name, (reason != "" ? reason : last)
      next
    }
    out && after_skip && NF { reason = $0; after_skip = 0 }
    out && /: Skipped$/ { after_skip = 1 }
    out && NF && !/^\[/ && !/^-+$/ { last = $0 }
  ' "$1"
}

# Which test unit each test belongs to ("name unit" lines): the tests gtest_discover_tests found
# in each unit's binary.
test_units() {
  local unit f
  for unit in "${units[@]}"; do
    for f in "$build_dir/tests/${unit}_tests["*"]_tests.cmake"; do
      [ -f "$f" ] || continue
      sed -n "s/^add_test(\[=\[\([^]]*\)\]=\].*/\1 $unit/p" "$f"
    done
  done
}

# The unit and integration tests under qemu-aarch64-static (the toolchain's
# CMAKE_CROSSCOMPILING_EMULATOR), in one ctest pass, counted per test unit (or only the units
# named; the tests outside the units, the peers' exchanges, as "other"): passed, skipped (each with
# its reason) and failed, with each failure's output.
emulated_tests() {
  local selected=("$@")
  [ ${#selected[@]} -gt 0 ] || selected=("${units[@]}" other)
  local exclude="" entry map=$build_dir/emulated-tests.units log=$build_dir/emulated-tests.log
  for entry in "${emulation_skips[@]}"; do exclude="${exclude:+$exclude|}${entry%%|*}"; done
  test_units >"$map"
  local regex=""
  if [ "${selected[*]}" != "${units[*]} other" ]; then
    # Only the named units' tests: their names, as one anchored regex.
    regex=$(awk -v want=" ${selected[*]} " 'index(want, " " $2 " ") { gsub(/[][.*+?()|^$\\]/, "\\\\&", $1); printf "%s^%s$", (n++ ? "|" : ""), $1 }' "$map")
  fi
  echo "setup arm64: the tests under qemu-aarch64-static (log: $log)"
  local rc=0
  ctest --test-dir "$build_dir" --output-on-failure -j"$jobs" -L 'unit|integration' -LE "$native_only_labels" \
    ${exclude:+-E "$exclude"} ${regex:+-R "$regex"} >"$log" 2>&1 || rc=$?
  # Each test's output, kept before the next ctest call (even -N) writes its log again.
  local outputs=$build_dir/emulated-tests.outputs.log
  cp "$build_dir/Testing/Temporary/LastTest.log" "$outputs"
  # Each test's result line ("1/78 Test #4: Name ....   Passed  0.52 sec") as "name status".
  local results=$build_dir/emulated-tests.results
  sed -n 's/^ *[0-9]*\/[0-9]* Test *#[0-9]*: \([^ ]*\) \.*[ *]*\([A-Za-z]*\).*/\1 \2/p' "$log" >"$results"
  local skipped_names emulation_skipped
  skipped_names=$(awk '$2 == "Skipped" || $2 == "Not" { print $1 }' "$results")
  emulation_skipped=""
  [ -n "$exclude" ] && emulation_skipped=$(ctest --test-dir "$build_dir" -N -R "$exclude" | sed -n 's/^ *Test *#[0-9]*: //p')
  echo "setup arm64: emulated tests per test unit:"
  awk -v sel="${selected[*]}" -v emu="$emulation_skipped" '
    FNR == 1 { file++ }
    file == 1 { unit_of[$1] = $2; next }
    file == 2 {
      u = ($1 in unit_of) ? unit_of[$1] : "other"
      if ($2 == "Passed") pass[u]++; else if ($2 == "Skipped" || $2 == "Not") skip[u]++; else fail[u]++
    }
    END {
      n = split(emu, e, "\n")
      for (i = 1; i <= n; i++) if (e[i] != "") { u = (e[i] in unit_of) ? unit_of[e[i]] : "other"; skip[u]++ }
      m = split(sel, s, " ")
      for (i = 1; i <= m; i++) { u = s[i]; printf "  %-10s %4d passed %3d skipped %3d failed\n", u, pass[u], skip[u], fail[u]; tp += pass[u]; ts += skip[u]; tf += fail[u] }
      printf "setup arm64: emulated tests: %d passed, %d skipped, %d failed\n", tp, ts, tf
    }' "$map" "$results"
  local unit
  for entry in "${emulation_skips[@]}"; do
    while read -r name; do
      unit=$(awk -v n="$name" '$1 == n { print $2 }' "$map")
      [[ " ${selected[*]} " == *" ${unit:-other} "* ]] && echo "    skipped under emulation: $name: ${entry#*|}"
    done < <(ctest --test-dir "$build_dir" -N -R "${entry%%|*}" | sed -n 's/^ *Test *#[0-9]*: //p')
  done
  [ -n "$skipped_names" ] && skip_reasons "$outputs" "$skipped_names"
  [ "$rc" -eq 0 ] || sed -n '/The following tests FAILED/,$p' "$log"
  return "$rc"
}

# The .deb's dependencies, as dpkg-shlibdeps computes them for the amd64 package: it reads each
# library's symbols/shlibs from its unpacked arm64 package (the host's package database knows
# only amd64 libraries).
deb_depends() {
  local work=$PWD/$build_dir/shlibdeps soname deb needed=()
  rm -rf "$work"
  mkdir -p "$work/pkgs" "$work/debian"
  mapfile -t needed < <(aarch64-linux-gnu-objdump -p "$build_dir/rovctl" | awk '/NEEDED/ {print $2}')
  local search_args=()
  local contents
  for deb in "$root"/var/cache/apt/archives/lib*.deb; do
    contents=$(dpkg-deb -c "$deb")
    for soname in "${needed[@]}"; do
      if grep -q "/$soname\$\|/$soname -> " <<<"$contents"; then
        dpkg-deb -R "$deb" "$work/pkgs/$(basename "$deb" .deb)"
        search_args+=(-S"$work/pkgs/$(basename "$deb" .deb)")
        break
      fi
    done
  done
  printf 'Source: rovctl\n\nPackage: rovctl\nArchitecture: arm64\n' >"$work/debian/control"
  (cd "$work" && DEB_HOST_ARCH=arm64 DEB_HOST_MULTIARCH=aarch64-linux-gnu dpkg-shlibdeps -O "${search_args[@]}" "$PWD/../rovctl") |
    sed -n 's/^shlibs:Depends=//p'
}

# The .deb: its control fields and files, unpacked into a scratch arm64 root (the build's root,
# which holds its libraries) where the installed binary runs under qemu; then apt, with that root's
# package lists, an empty package database and arm64 as the only architecture, shows each
# dependency's candidate and plans the install of the .deb and everything it needs.
package() {
  local depends deb scratch
  depends=$(deb_depends)
  echo "setup arm64: Depends: $depends"
  cmake -B "$build_dir" -DROVCTL_DEB_DEPENDS="$depends" >/dev/null
  (cd "$build_dir" && cpack -G DEB >/dev/null)
  deb=$(ls "$build_dir"/rovctl_*_arm64.deb)
  dpkg -I "$deb"
  dpkg -c "$deb"
  scratch=$build_dir/deb-root
  rm -rf "$scratch"
  dpkg-deb -x "$deb" "$scratch"
  echo "setup arm64: the installed $scratch/usr/bin/rovctl under qemu: rovctl params (first lines)"
  "${emulator[@]}" "$scratch/usr/bin/rovctl" params >"$build_dir/params-installed.txt"
  head -3 "$build_dir/params-installed.txt"
  local apt_arm64=(-o Dir="$root/" -o Dir::State::status="$root/var/lib/dpkg/status"
    -o APT::Architecture=arm64 -o APT::Architectures::=arm64 -o Debug::NoLocking=1)
  echo "setup arm64: each dependency on bookworm arm64 (apt-cache policy, candidate):"
  local pkg
  for pkg in $(tr ',' '\n' <<<"$depends" | sed 's/(.*//; s/|.*//; s/ //g'); do
    printf '  %-28s %s\n' "$pkg" "$(apt-cache "${apt_arm64[@]}" policy "$pkg:arm64" | sed -n 's/^ *Candidate: //p')"
  done
  apt-get -q "${apt_arm64[@]}" install -s --no-install-recommends "./$deb" | grep -E '^Inst rovctl|newly installed'
  echo "setup arm64: $deb"
}

install_host_packages
# The JavaScript test peers (node-mavlink), as deploy/setup.sh installs them for the native build.
if [ ! -d tests/node_modules/node-mavlink ]; then
  echo "setup arm64: npm ci in tests/"
  npm ci --prefix tests --no-audit --no-fund --loglevel=error
fi
[ "$stop_after" == host ] && exit 0
make_root
[ "$stop_after" == root ] && exit 0
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_TOOLCHAIN_FILE="$PWD/deploy/toolchain-arm64.cmake" -DROVCTL_ARM64_SYSROOT="$root" \
  "${launcher[@]}" "${cmake_args[@]}" >/dev/null
build() {
  local target_args=() t
  for t in "$@"; do target_args+=(--target "$t"); done
  cmake --build "$build_dir" -j"$jobs" "${target_args[@]}"
  echo "setup arm64: built $build_dir ${*:-(everything)}"
}

emulator=(qemu-aarch64-static -L "$root")
if [ "$ci" -eq 1 ]; then
  build rovctl
  file "$build_dir/rovctl"
  echo "setup arm64: rovctl params under qemu-aarch64-static (first lines)"
  "${emulator[@]}" "$build_dir/rovctl" params >"$build_dir/params.txt"
  head -3 "$build_dir/params.txt"
  exit
fi
if [ "$build_only" -eq 1 ]; then
  build "${targets[@]}"
  exit 0
fi

# The binary and its package first (the tests' binaries take as long again to build), then the
# tests, then the emulated closed loop.
build rovctl
file "$build_dir/rovctl"
echo "setup arm64: rovctl params under qemu-aarch64-static (first lines)"
"${emulator[@]}" "$build_dir/rovctl" params >"$build_dir/params.txt"
head -3 "$build_dir/params.txt"
package
build
tests_rc=0
emulated_tests || tests_rc=$?
echo "setup arm64: rovctl bench under qemu-aarch64-static (emulated: its times are not the board's)"
"${emulator[@]}" "$build_dir/rovctl" bench
echo "setup arm64: rovctl sim --trials 2 under qemu-aarch64-static"
"${emulator[@]}" "$build_dir/rovctl" sim --trials 2
exit "$tests_rc"
