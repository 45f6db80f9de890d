#!/usr/bin/env bash
# rays_against_base.sh [--rounds N] [--beams-scale X] [BASE_REV]
#
# Whole-process speed of the working tree against BASE_REV (default
# e500837) on scenes with objects, where the time goes into tracing rays
# against triangles:
#   sphere_mesh  the optics bench's mesh scene (opticsMeshScene(1'000'000):
#                998,000 triangles, a spot on a grey sphere, a pinhole),
#                written as JSON + OBJ by scripts/lib/make_mesh_scenes.py;
#   prism        scenes/prism.json (41 lasers through an 8-triangle N-BK7
#                prism);
#   room         a furnished room of over 200,000 triangles (diffuse
#                surfaces, a spot and a disk light), make_mesh_scenes.py.
# For each scene, `spectrace render` on --device cpu and --device gpu, each
# the best of N rounds (default 3) of wall-clock time, base and tree taken in
# turn so that the machine's drift favours neither. Beam counts are fixed per
# scene and device (a tree render of roughly 5-20 s on 2 cores at the
# docs/benchmarks.md Optics speeds), times --beams-scale X (default 1).
# Prints a table: Mbeam/s of each and the ratio tree : base.
#
# Also checks that the physics did not change: the last base and tree
# images of each scene and device must agree in total and in every
# 32x32-pixel block within 5 sigma (tools/exr_blocks_agree), in irradiance
# and in Y. Objects make the beams' weights unequal (connections to the
# pinhole, camera paths, roulette), so the PER_COUNT given to
# exr_blocks_agree is a conservative variance unit: 25 x the mean weight of
# a counted beam (the larger image total over the fewer counted beams, from
# the renders' own summary lines). A 25x unit widens every bound 5x over a
# Poisson count of the mean weight; two tree renders of sphere_mesh at seeds
# 1 and 2 differed by z = 4 in total with that unit at 1x. The Y unit is
# derived from that one, so it does not cover a base whose colour counters
# are noisier than its irradiance counters: e500837 rounded each camera
# connection's colour to whole fixed-point units, and room fails in Y in a
# dim block against it while tree renders at two seeds agree (z < 0.5;
# docs/benchmarks.md, "Rays through objects").
#
# Both binaries read the same scene files and do the same work: light paths
# with one wavelength a beam, the base's only way (it has neither option), and
# the tree's with --estimator light --set /render/wavelengths_per_beam=1
# (its defaults are both estimators and four wavelengths a beam).
#
# Exit status: 0 when every pair agrees, 1 when some pair does not, 2 on a
# usage or build error. Builds as scripts/throughput_against_base.sh does;
# work folder build-base/ (base build, logs, rays/ with scenes and images).
set -euo pipefail
cd "$(dirname "$0")/.."
die() { echo "rays_against_base: $*" >&2; exit 2; }
rounds=3
scale=1
while [[ $# -gt 0 ]]; do
  case $1 in
    --rounds) rounds=${2:?--rounds needs a value}; shift 2 ;;
    --beams-scale) scale=${2:?--beams-scale needs a value}; shift 2 ;;
    -*) die "unknown option $1" ;;
    *) break ;;
  esac
done
[[ $# -le 1 ]] || die "usage: rays_against_base.sh [--rounds N] [--beams-scale X] [BASE_REV]"
[[ $rounds =~ ^[1-9][0-9]*$ ]] || die "--rounds must be a positive integer (got '$rounds')"
python3 -c "import math, sys; x = float(sys.argv[1]); sys.exit(0 if math.isfinite(x) and x > 0 else 1)" "$scale" \
  2>/dev/null || die "--beams-scale must be a positive number (got '$scale')"
base_rev=${1:-e500837}
jobs=$(nproc 2>/dev/null || echo 2)
root=$(pwd -P)
base_sha=$(git rev-parse --verify -q "$base_rev^{commit}") || die "unknown revision '$base_rev'"
# Resolved: a symlinked build-base/ must name the worktree as git knows it.
work=$(realpath -m "$root/build-base")
out=$work/rays
mkdir -p "$work/logs" "$out/scenes" "$out/images" "$out/logs"
# run_logged and build_base_spectrace.
# shellcheck source=lib/base_build.sh
source "$root/scripts/lib/base_build.sh"
use_scratch_env
echo "rays_against_base: building the working tree and $base_rev (${base_sha:0:12})"
[[ -f build/CMakeCache.txt ]] || run_logged "$work/logs/tree-configure.log" cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
run_logged "$work/logs/tree-build.log" cmake --build build -j "$jobs" --target spectrace exr_blocks_agree
build_base_spectrace "$base_sha"
tree_bin=$root/build/spectrace
agree=$root/build/exr_blocks_agree
[[ -x $tree_bin && -x $agree ]] || die "build/spectrace or build/exr_blocks_agree missing after the build"

echo "rays_against_base: writing the mesh scenes into $out/scenes"
python3 "$root/scripts/lib/make_mesh_scenes.py" "$out/scenes" || die "make_mesh_scenes.py failed"

scene_file() {
  case $1 in
    sphere_mesh) echo "$out/scenes/sphere_mesh.json" ;;
    prism) echo "$root/scenes/prism.json" ;;
    room) echo "$out/scenes/room.json" ;;
  esac
}
# Beams per scene and device at scale 1: ~8 s of tracing on 2 cores at
# docs/benchmarks.md's speeds (mesh 1M triangles: 0.94 Mbeam/s CPU, 0.23
# lavapipe; prism: 4.8 and 1.7); the room is taken as costly as the mesh.
base_beams_of() {
  case $1/$2 in
    sphere_mesh/cpu) echo 8000000 ;;
    sphere_mesh/gpu) echo 2000000 ;;
    prism/cpu) echo 40000000 ;;
    prism/gpu) echo 16000000 ;;
    room/cpu) echo 8000000 ;;
    room/gpu) echo 2000000 ;;
  esac
}

# Wall seconds of one whole `spectrace render` process; its messages go to LOG.
seconds_of() {
  local bin=$1 scene=$2 device=$3 beams=$4 exr=$5 log=$6 start end
  local extra=()
  [[ $bin == "$tree_bin" ]] && extra=(--estimator light --set /render/wavelengths_per_beam=1)
  start=$(date +%s.%N)
  if ! "$bin" render "$scene" --device "$device" --beams "$beams" "${extra[@]}" -o "$exr" --no-png > "$log" 2>&1; then
    tail -n 20 "$log" >&2
    die "render failed: $bin render $scene --device $device --beams $beams (log: $log)"
  fi
  end=$(date +%s.%N)
  python3 -c "print($end - $start)"
}

# The beams a render counted, from its summary line "N beams counted (...)".
counted_of() {
  sed -n 's/^spectrace: \([0-9][0-9]*\) beams counted.*/\1/p' "$1" | tail -n 1
}

status=0
table=()
for scene_name in sphere_mesh prism room; do
  scene=$(scene_file "$scene_name")
  [[ -f $scene ]] || die "no scene file $scene"
  for device in cpu gpu; do
    beams=$(python3 -c "print(max(1, round($(base_beams_of "$scene_name" "$device") * $scale)))")
    best_base=inf best_tree=inf
    base_exr=$out/images/base_${scene_name}_$device.exr tree_exr=$out/images/tree_${scene_name}_$device.exr
    base_log=$out/logs/base_${scene_name}_$device.log tree_log=$out/logs/tree_${scene_name}_$device.log
    for ((r = 1; r <= rounds; ++r)); do
      b=$(seconds_of "$base_bin" "$scene" "$device" "$beams" "$base_exr" "$base_log")
      t=$(seconds_of "$tree_bin" "$scene" "$device" "$beams" "$tree_exr" "$tree_log")
      best_base=$(python3 -c "print(min(float('$best_base'), $b))")
      best_tree=$(python3 -c "print(min(float('$best_tree'), $t))")
      echo "  $scene_name $device round $r: base ${b}s, tree ${t}s"
    done
    table+=("$(python3 -c "
b, t, n = $best_base, $best_tree, $beams
print(f'| $scene_name | $device | {n} | {b:.3f} | {t:.3f} | {n / b / 1e6:.3f} | {n / t / 1e6:.3f} | {b / t:.2f} |')")")
    # The physics: the last images of each, with a variance unit from the
    # larger total over the fewer counted beams (see the header).
    counted_base=$(counted_of "$base_log") counted_tree=$(counted_of "$tree_log")
    if [[ -z $counted_base || -z $counted_tree ]]; then
      echo "$scene_name $device: no 'beams counted' line in $base_log or $tree_log" >&2
      status=1
      continue
    fi
    totals=$("$agree" "$base_exr" "$tree_exr" 1 32 | sed -n 's/^irradiance\.E total: \([^ ]*\) vs \([^,]*\),.*/\1 \2/p') || true
    per_count=$(python3 -c "
import sys
a, b = (float(x) for x in sys.argv[1].split())
counted = min(int(sys.argv[2]), int(sys.argv[3]))
print(25.0 * max(a, b) / counted if counted > 0 and max(a, b) > 0 else 0)" "$totals" "$counted_base" "$counted_tree" 2>/dev/null) \
      || per_count=0
    if [[ $per_count == 0 || $per_count == 0.0 ]]; then
      echo "$scene_name $device: no light counted (totals '$totals', counted $counted_base and $counted_tree)" >&2
      status=1
      continue
    fi
    echo "  $scene_name $device: exr_blocks_agree with PER_COUNT $per_count"
    if ! "$agree" "$base_exr" "$tree_exr" "$per_count" 32 | sed 's/^/    /'; then
      echo "$scene_name $device: the images do NOT agree within 5 sigma" >&2
      status=1
    fi
  done
done

echo
echo "| scene | device | beams | $base_rev s | tree s | $base_rev Mbeam/s | tree Mbeam/s | tree : base |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
printf '%s\n' "${table[@]}"
echo "(whole-process wall time, best of $rounds; beams scale $scale)"
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //'), $(nproc) threads; $(date -u '+%Y-%m-%d %H:%M UTC'); load average $(cut -d' ' -f1-3 /proc/loadavg)"
exit $status
