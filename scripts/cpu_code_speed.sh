#!/usr/bin/env bash
# cpu_code_speed.sh [--rounds N] [SCENE]
#
# The CPU reference's two machine codes (--cpu-code baseline and
# x86-64-v3, host/backend/cpu_code.h) against each other: whole-process
# `spectrace render --device cpu` of SCENE (default the throughput scene,
# scenes/bench/throughput.json), each the best of N rounds (default 5) of
# wall-clock time, taken in turn so that the machine's drift favours
# neither. Prints both times, the ratio baseline : x86-64-v3, and whether
# the two images are bit for bit the same (tools/exr_pixels_equal), which
# they must be. Exit status: 0 when the images are equal, 1 when not, 2 on a
# usage or build error, or on a processor without x86-64-v3.
set -euo pipefail
cd "$(dirname "$0")/.."
die() { echo "cpu_code_speed: $*" >&2; exit 2; }
rounds=5
while [[ $# -gt 0 ]]; do
  case $1 in
    --rounds) rounds=${2:?--rounds needs a value}; shift 2 ;;
    -*) die "unknown option $1" ;;
    *) break ;;
  esac
done
scene=${1:-scenes/bench/throughput.json}
[[ -f $scene ]] || die "no scene file $scene"
[[ -f build/CMakeCache.txt ]] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null || die "configure failed"
cmake --build build -j "$(nproc 2>/dev/null || echo 2)" --target spectrace exr_pixels_equal >/dev/null || die "build failed"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

seconds_of() {  # seconds_of CODE: wall seconds of one render with --cpu-code CODE
  local start end
  start=$(date +%s.%N)
  build/spectrace render "$scene" --device cpu --cpu-code "$1" -o "$out/$1.exr" --no-png -q || die "render with --cpu-code $1 failed"
  end=$(date +%s.%N)
  python3 -c "print($end - $start)"
}

best_baseline=inf best_v3=inf
for ((r = 1; r <= rounds; ++r)); do
  b=$(seconds_of baseline)
  v=$(seconds_of x86-64-v3)
  best_baseline=$(python3 -c "print(min(float('$best_baseline'), $b))")
  best_v3=$(python3 -c "print(min(float('$best_v3'), $v))")
  echo "  round $r: baseline ${b}s, x86-64-v3 ${v}s"
done
python3 -c "print(f'best of $rounds: baseline {$best_baseline:.3f} s, x86-64-v3 {$best_v3:.3f} s: baseline : x86-64-v3 = {$best_baseline / $best_v3:.2f}')"
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //'), $(nproc) threads; $(date -u '+%Y-%m-%d %H:%M UTC')"
if build/exr_pixels_equal "$out/baseline.exr" "$out/x86-64-v3.exr"; then
  echo "images: bit for bit the same"
else
  echo "images: DIFFERENT" >&2
  exit 1
fi
