#!/usr/bin/env bash
# profile_against_base.sh [--rounds N] [--beams B] [BASE_REV]
#
# The bench's stage profile and ceiling (`spectrace bench --only
# profile,ceiling`) of the working tree against BASE_REV, in one run: the
# two binaries' benches are taken in turn, N rounds (default 3), and each
# stage keeps its least ns/beam per binary and device, so that the
# machine's drift favours neither. BASE_REV defaults to 474d8c5, the first
# revision whose bench has the profile (the throughput work's alias tables
# and chunk specialisation were already in; what came after was measured
# against it). Prints one Markdown table per device: each stage's ns/beam
# before and after and the ratio, then spectrace : ceiling before and
# after. Exit status: 0, or 2 on a usage or build error.
set -euo pipefail
cd "$(dirname "$0")/.."
die() { echo "profile_against_base: $*" >&2; exit 2; }
rounds=3
beams=8388608
while [[ $# -gt 0 ]]; do
  case $1 in
    --rounds) rounds=${2:?--rounds needs a value}; shift 2 ;;
    --beams) beams=${2:?--beams needs a value}; shift 2 ;;
    -*) die "unknown option $1" ;;
    *) break ;;
  esac
done
base_rev=${1:-474d8c5}
jobs=$(nproc 2>/dev/null || echo 2)
root=$(pwd -P)
base_sha=$(git rev-parse --verify -q "$base_rev^{commit}") || die "unknown revision '$base_rev'"
# Resolved: a symlinked build-base-profile/ must name the worktree as git knows it.
work=$(realpath -m "$root/build-base-profile")
mkdir -p "$work/logs" "$work/runs"
# run_logged and build_base_spectrace.
# shellcheck source=lib/base_build.sh
source "$root/scripts/lib/base_build.sh"
use_scratch_env
echo "profile_against_base: building the working tree and $base_rev (${base_sha:0:12})" >&2
[[ -f build/CMakeCache.txt ]] || run_logged "$work/logs/tree-configure.log" cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
run_logged "$work/logs/tree-build.log" cmake --build build -j "$jobs" --target spectrace
build_base_spectrace "$base_sha"

# bench_into BIN DIR: the profile and ceiling sections' CSV files in DIR/bench/.
bench_into() {
  rm -rf "$2"
  run_logged "$2.log" "$1" bench --only profile,ceiling --profile-beams "$beams" --out "$2"
}
for ((r = 1; r <= rounds; ++r)); do
  echo "  round $r of $rounds" >&2
  bench_into "$base_bin" "$work/runs/base_$r"
  bench_into "$root/build/spectrace" "$work/runs/tree_$r"
done

python3 - "$work/runs" "$rounds" "$base_rev" <<'EOF'
import csv, sys, pathlib
runs, rounds, base_rev = pathlib.Path(sys.argv[1]), int(sys.argv[2]), sys.argv[3]

def least(side, name, key, value):
    """{key(row): least value(row)} over the rounds of one side."""
    best = {}
    for r in range(1, rounds + 1):
        with open(runs / f"{side}_{r}" / "bench" / name, newline="") as f:
            for row in csv.DictReader(f):
                k, v = key(row), value(row)
                best[k] = min(best.get(k, v), v)
    return best

stage_key = lambda row: (row["device"], int(row["stage"]))
ns = lambda row: float(row["ns_per_beam"])
before, after = least("base", "profile.csv", stage_key, ns), least("tree", "profile.csv", stage_key, ns)
names = least("tree", "profile.csv", stage_key, lambda row: (row["device_name"], row["stage_name"]))
print(f"Stage profile, ns/beam (least of {rounds} interleaved rounds), {base_rev} against the working tree:\n")
for device in sorted({k[0] for k in after}):
    stages = sorted(k for k in after if k[0] == device)
    print(f"{names[stages[0]][0]} ({device}):\n")
    print(f"| stage | {base_rev} | tree | {base_rev} : tree |")
    print("| --- | ---: | ---: | ---: |")
    for k in stages:
        b = before.get(k)
        cells = (f"{b:.2f}", f"{b / after[k]:.2f}") if b else ("-", "-")
        print(f"| {names[k][1]} | {cells[0]} | {after[k]:.2f} | {cells[1]} |")
    print()

ceiling_key = lambda row: row["device"]
def ratio(row):  # spectrace : ceiling, the larger the better: keep the best as the least of its inverse
    return -float(row["spectrace_to_ceiling"])
cb, ca = least("base", "ceiling.csv", ceiling_key, ratio), least("tree", "ceiling.csv", ceiling_key, ratio)
print("| device | spectrace : ceiling, " + base_rev + " | tree |")
print("| --- | ---: | ---: |")
for d in sorted(ca):
    print(f"| {d} | {-cb[d]:.3f} | {-ca[d]:.3f} |" if d in cb else f"| {d} | - | {-ca[d]:.3f} |")
EOF
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //'), $(nproc) threads; $(date -u '+%Y-%m-%d %H:%M UTC')"
