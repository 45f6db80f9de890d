#!/usr/bin/env bash
# throughput_against_base.sh [--rounds N] [BASE_REV]
#
# Whole-process throughput of the working tree against BASE_REV (default
# 2cc8a60, before the throughput work), on the throughput scene
# (scenes/bench/throughput.json: D65 disk light, bare 512x512 sensor, 64
# bins, exact colour on, 2^25 beams), for `spectrace render` on
# --device gpu and --device cpu: each the best of N rounds (default 3) of
# wall-clock time, base and tree taken in turn so that the machine's drift
# favours neither. Prints beams/s and the ratio after : before per device.
#
# Also checks that the physics did not change: one render of each binary
# must agree in total and in every 32x32-pixel block within 5 sigma
# (tools/exr_blocks_agree), in irradiance and in Y. (Against 2cc8a60 both
# are independent estimates: the emission now takes its four words from
# the geometry block alone, and the wavelengths come from another table.)
# Exit status: 0 when they agree, 1 when not, 2 on
# a usage or build error. Builds as scripts/check_identical_images.sh does.
set -euo pipefail
cd "$(dirname "$0")/.."
die() { echo "throughput_against_base: $*" >&2; exit 2; }
rounds=3
while [[ $# -gt 0 ]]; do
  case $1 in
    --rounds) rounds=${2:?--rounds needs a value}; shift 2 ;;
    -*) die "unknown option $1" ;;
    *) break ;;
  esac
done
base_rev=${1:-2cc8a60}
jobs=$(nproc 2>/dev/null || echo 2)
root=$(pwd -P)
base_sha=$(git rev-parse --verify -q "$base_rev^{commit}") || die "unknown revision '$base_rev'"
# Resolved: a symlinked build-base/ must name the worktree as git knows it.
work=$(realpath -m "$root/build-base")
mkdir -p "$work/logs" "$work/throughput"
# run_logged and build_base_spectrace.
# shellcheck source=lib/base_build.sh
source "$root/scripts/lib/base_build.sh"
use_scratch_env
echo "throughput_against_base: building the working tree and $base_rev (${base_sha:0:12})"
[[ -f build/CMakeCache.txt ]] || run_logged "$work/logs/tree-configure.log" cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
run_logged "$work/logs/tree-build.log" cmake --build build -j "$jobs" --target spectrace exr_blocks_agree
build_base_spectrace "$base_sha"
tree_bin=$root/build/spectrace

scene=$root/scenes/bench/throughput.json
beams=33554432
# W/m^2 of one counted beam: 1 W over the beams and one pixel of (0.1 m / 512)^2.
per_count=$(python3 -c "print(1.0 / ($beams * (0.1 / 512) ** 2))")
out=$work/throughput

# Wall seconds of one whole `spectrace render` process.
seconds_of() {
  local bin=$1 device=$2 exr=$3 start end
  start=$(date +%s.%N)
  "$bin" render "$scene" --device "$device" --beams "$beams" -o "$exr" --no-png -q
  end=$(date +%s.%N)
  python3 -c "print($end - $start)"
}

status=0
for device in gpu cpu; do
  best_base=inf best_tree=inf
  for ((r = 1; r <= rounds; ++r)); do
    b=$(seconds_of "$work/build/spectrace" "$device" "$out/base_$device.exr")
    t=$(seconds_of "$tree_bin" "$device" "$out/tree_$device.exr")
    best_base=$(python3 -c "print(min(float('$best_base'), $b))")
    best_tree=$(python3 -c "print(min(float('$best_tree'), $t))")
    echo "  $device round $r: base ${b}s, tree ${t}s"
  done
  python3 -c "
b, t = $best_base, $best_tree
print(f'$device: $base_rev {$beams / b / 1e6:.2f} Mbeam/s ({b:.3f} s), tree {$beams / t / 1e6:.2f} Mbeam/s ({t:.3f} s): after : before = {b / t:.2f}')"
  if ! "$root/build/exr_blocks_agree" "$out/base_$device.exr" "$out/tree_$device.exr" "$per_count" 32; then
    echo "$device: the images do NOT agree within 5 sigma" >&2
    status=1
  fi
done
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //'), $(nproc) threads; $(date -u '+%Y-%m-%d %H:%M UTC'); load average $(cut -d' ' -f1-3 /proc/loadavg)"
exit $status
