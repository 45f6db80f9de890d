#!/usr/bin/env bash
# check_identical_images.sh [options] [BASE_REV]
#
# Checks that the working tree renders every scene exactly as BASE_REV does:
# a refactor must not change any figure in any image.
#
#  1. builds the working tree's spectrace and exr_pixels_equal in build/
#     (as scripts/setup.sh configured it; configured here if it is not), and
#     BASE_REV's spectrace in a git worktree under build-base/ (reused and
#     moved to BASE_REV on later runs);
#  2. renders every scene under scenes/ (every *.json with a "lights" key,
#     scenes/batch/ excepted) with both binaries on every device, at a fixed
#     seed and beam count; both binaries read the working tree's scene files;
#  3. compares each pair of EXRs' channels, data window and raw pixel bits
#     (not their headers, which hold wall time) with tools/exr_pixels_equal.
#
# Prints one line per scene and device and a summary; exits 0 only if every
# pair is bit-identical, 1 if any differs or a render fails, 2 on a usage or
# build error. Renders, logs and Mesa's shader cache stay under build-base/.
#
# Options (each also settable from the environment):
#   --seed N        render seed                        (CHECK_SEED, default 7)
#   --beams N       beams per render                   (CHECK_BEAMS, default 300000)
#   --devices LIST  comma-separated --device values    (CHECK_DEVICES, default gpu,cpu)
#   --jobs N        parallel build jobs                (CHECK_JOBS, default nproc)
#   --base-seed N   seed for BASE_REV's renders only, to see the check fail
#                                                      (CHECK_BASE_SEED, default --seed)
#   --render-args S extra arguments for every render, e.g. "--threads 2"
#                                                      (CHECK_RENDER_ARGS)
#   --shared-channels  compare only the channels both files have, for a
#                   change that adds channels (CHECK_SHARED_CHANNELS=1)
# BASE_REV defaults to origin/main if it exists, else HEAD~1.
set -euo pipefail

usage() { sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "$0"; }
die() { echo "check_identical_images: $*" >&2; exit 2; }

seed=${CHECK_SEED:-7}
beams=${CHECK_BEAMS:-300000}
devices=${CHECK_DEVICES:-gpu,cpu}
jobs=${CHECK_JOBS:-$(nproc 2>/dev/null || echo 2)}
base_seed=${CHECK_BASE_SEED:-}
render_args=${CHECK_RENDER_ARGS:-}
shared_channels=${CHECK_SHARED_CHANNELS:-0}
base_rev=

while (($#)); do
  case $1 in
    -h|--help) usage; exit 0 ;;
    --seed) seed=${2:?--seed needs a value}; shift 2 ;;
    --beams) beams=${2:?--beams needs a value}; shift 2 ;;
    --devices) devices=${2:?--devices needs a value}; shift 2 ;;
    --jobs) jobs=${2:?--jobs needs a value}; shift 2 ;;
    --base-seed) base_seed=${2:?--base-seed needs a value}; shift 2 ;;
    --render-args) render_args=${2?--render-args needs a value}; shift 2 ;;
    --shared-channels) shared_channels=1; shift ;;
    --seed=*|--beams=*|--devices=*|--jobs=*|--base-seed=*|--render-args=*)
      opt=${1%%=*}; set -- "$opt" "${1#*=}" "${@:2}" ;;
    -*) usage >&2; die "unknown option $1" ;;
    *) [[ -z $base_rev ]] || die "only one BASE_REV, got '$base_rev' and '$1'"; base_rev=$1; shift ;;
  esac
done
base_seed=${base_seed:-$seed}
for n in "$seed" "$beams" "$base_seed" "$jobs"; do
  [[ $n =~ ^[0-9]+$ ]] || die "not a non-negative integer: '$n'"
done
IFS=', ' read -r -a device_list <<< "$devices"
((${#device_list[@]})) || die "no devices given"
read -r -a extra_args <<< "$render_args"

cd "$(dirname "$0")/.."
root=$(pwd -P)
git rev-parse --is-inside-work-tree > /dev/null 2>&1 || die "$root is not a git work tree"

if [[ -z $base_rev ]]; then
  if git rev-parse --verify -q 'origin/main^{commit}' > /dev/null; then base_rev=origin/main; else base_rev=HEAD~1; fi
fi
base_sha=$(git rev-parse --verify -q "$base_rev^{commit}") || die "unknown revision '$base_rev'"
head_sha=$(git rev-parse HEAD)
if [[ -z $(git status --porcelain) ]]; then
  tree_desc=${head_sha:0:12}
else
  tree_desc="working tree (HEAD ${head_sha:0:12} + changes)"
fi

# Resolved: a symlinked build-base/ must name the worktree as git knows it.
work=$(realpath -m "$root/build-base")
src=$work/src
mkdir -p "$work/logs"
if command -v flock > /dev/null; then
  exec 9> "$work/.lock"
  flock -n 9 || die "another check_identical_images run is using $work"
fi
start=$SECONDS

# run_logged and build_base_spectrace.
# shellcheck source=lib/base_build.sh
source "$root/scripts/lib/base_build.sh"
use_scratch_env

# 1. The working tree's binaries, in build/.
echo "check_identical_images: building the working tree's spectrace and exr_pixels_equal in build/"
# Configured afresh (keeping build/'s cache) so that a build/ from before
# tools/ existed learns the exr_pixels_equal target.
tree_cmake_args=()
[[ -f build/CMakeCache.txt ]] || tree_cmake_args=(-DCMAKE_BUILD_TYPE=Release)
run_logged "$work/logs/tree-configure.log" cmake -S . -B build "${tree_cmake_args[@]}"
run_logged "$work/logs/tree-build.log" cmake --build build -j "$jobs" --target spectrace exr_pixels_equal
tree_bin=$root/build/spectrace
compare=$root/build/exr_pixels_equal
[[ -x $tree_bin && -x $compare ]] || die "build/spectrace or build/exr_pixels_equal missing after the build"

# BASE_REV's spectrace, in a detached worktree at build-base/src (reused).
echo "check_identical_images: building spectrace at $base_rev (${base_sha:0:12}) in build-base/"
build_base_spectrace "$base_sha"
build_seconds=$((SECONDS - start))

# 2. The scenes: every JSON under scenes/ with a "lights" key, not scenes/batch/.
scenes=()
skipped=0
while IFS= read -r -d '' f; do
  if grep -q '"lights"[[:space:]]*:' "$f"; then scenes+=("$f"); else skipped=$((skipped + 1)); fi
done < <(find scenes -name '*.json' -not -path 'scenes/batch/*' -type f -print0 | LC_ALL=C sort -z)
((${#scenes[@]})) || die "no scene files under scenes/"

images=$work/images
rm -rf "$images"
echo "check_identical_images: ${#scenes[@]} scenes x ${#device_list[@]} devices (${device_list[*]}), --seed $seed$([[ $base_seed != "$seed" ]] && echo " (base --seed $base_seed)") --beams $beams${render_args:+ $render_args}$( ((skipped)) && echo ", $skipped JSON files without \"lights\" skipped")"

# Renders scene $1 on device $2 with binary $3 and seed $4 into $5; on
# failure prints why and returns non-zero.
render() {
  local scene=$1 device=$2 bin=$3 rseed=$4 out=$5
  mkdir -p "$(dirname "$out")"
  local rc=0
  "$bin" render "$root/$scene" --device "$device" --seed "$rseed" --beams "$beams" --no-png -q -o "$out" \
    "${extra_args[@]}" > "$out.log" 2>&1 || rc=$?
  if ((rc)); then
    echo "render failed (exit $rc): $(grep -v '^[[:space:]]*$' "$out.log" | tail -n 1)"
    return 1
  fi
  [[ -f $out ]] || { echo "render wrote no $out"; return 1; }
}

same=0
different=0
failed=0
width=0
for scene in "${scenes[@]}"; do ((${#scene} > width)) && width=${#scene}; done
for scene in "${scenes[@]}"; do
  name=${scene#scenes/}
  name=${name%.json}
  name=${name//\//__}
  for device in "${device_list[@]}"; do
    base_exr=$images/base/$device/$name.exr
    tree_exr=$images/tree/$device/$name.exr
    if ! why=$(render "$scene" "$device" "$base_bin" "$base_seed" "$base_exr"); then
      result="FAILED: base $why"; failed=$((failed + 1))
    elif ! why=$(render "$scene" "$device" "$tree_bin" "$seed" "$tree_exr"); then
      result="FAILED: tree $why"; failed=$((failed + 1))
    else
      rc=0
      compare_args=()
      [[ $shared_channels == 1 ]] && compare_args=(--shared-channels)
      why=$("$compare" "${compare_args[@]}" "$base_exr" "$tree_exr" 2>&1) || rc=$?
      case $rc in
        0) result=same; same=$((same + 1)) ;;
        1) result="DIFFERENT: $why"; different=$((different + 1)) ;;
        *) result="FAILED: exr_pixels_equal: $why"; failed=$((failed + 1)) ;;
      esac
    fi
    printf '%-*s  %-4s %s\n' "$width" "$scene" "$device" "$result"
  done
done

total=$((${#scenes[@]} * ${#device_list[@]}))
summary="check_identical_images: ${#scenes[@]} scenes x ${#device_list[@]} devices: $same identical, $different different"
((failed)) && summary+=", $failed failed"
summary+=" (base ${base_sha:0:12}, tree $tree_desc)"
echo "$summary; builds ${build_seconds} s, renders $((SECONDS - start - build_seconds)) s"
((same == total))
