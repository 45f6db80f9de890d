#!/usr/bin/env bash
# Fuzzes spectrace's parsers of outside input with libFuzzer under ASan +
# UBSan (docs/reliability.md, "Fuzzing"): scene JSON, SPD CSV, batch job
# lines and their sweeps, render-state files, OBJ meshes and luminaire
# files (IES, EULUMDAT).
#
#   bash scripts/fuzz.sh [SECONDS]      # SECONDS per target, default 600
#   bash scripts/fuzz.sh --build-only   # install clang and build the targets only
#   bash scripts/fuzz.sh --install-only # install clang only
#
# Environment: SPECTRACE_FUZZ_PARALLEL (targets run at once, default 1),
# SPECTRACE_FUZZ_TARGETS (space-separated subset), SPECTRACE_FUZZ_BUILD (a
# build folder configured elsewhere with clang and -DSPECTRACE_FUZZ=ON, as
# .ci/run's sanitizer build is: the targets are built there, not
# configured again; default build-fuzz, configured here). Installs clang and its
# runtime (libFuzzer, sanitizers) if missing (needs root), builds the
# targets into build-fuzz/ with clang, seeds each corpus from scenes/,
# data/cie/, tests/data/ and tests/fuzz/seeds/, and runs each target. The corpora grow in
# build-fuzz/fuzz/corpus/<target>/ (kept between runs); a finding (crash,
# sanitizer report, uncaught exception, leak, timeout, out-of-memory) is
# saved under build-fuzz/fuzz/findings/<target>/ and fails the script.
set -euo pipefail
cd "$(dirname "$0")/.."
build_only=false
install_only=false
if [[ ${1:-} == --build-only ]]; then build_only=true; shift; fi
if [[ ${1:-} == --install-only ]]; then install_only=true; shift; fi
build=${SPECTRACE_FUZZ_BUILD:-build-fuzz}
seconds=${1:-600}
parallel=${SPECTRACE_FUZZ_PARALLEL:-1}
targets=(${SPECTRACE_FUZZ_TARGETS:-scene_json csv_spd job_lines job_sweep film_state obj_mesh photometric_file})

missing=()
for p in clang libclang-rt-14-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

$install_only && exit 0

if [[ -z ${SPECTRACE_FUZZ_BUILD:-} ]]; then
  cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSPECTRACE_FUZZ=ON -DBUILD_TESTING=OFF >/dev/null
fi
cmake --build "$build" --target fuzz_targets -j "$(nproc)"
$build_only && exit 0

build=$(realpath "$build")
work=$build/fuzz
seed_files() {  # the seed inputs of target $1, one path a line
  case $1 in
    scene_json) find scenes tests/data -name '*.json' -not -path '*/layering_back_arrow/*' ;;
    csv_spd) find scenes data/cie -name '*.csv' ;;
    job_lines) find scenes tests/data -name '*.jsonl' ;;
    job_sweep) find tests/fuzz/seeds/job_sweep -type f ;;
    film_state) echo "$work/generated/valid.state" ;;
    obj_mesh) find scenes tests/data -name '*.obj' ;;
    photometric_file) find scenes tests/fuzz/seeds/photometric -name '*.ies' -o -name '*.ldt' ;;
  esac
}
mkdir -p "$work/generated"
"$build/tests/fuzz/make_state_seed" "$work/generated/valid.state"

run_target() {  # runs target $1; its log is $work/$1.log, its exit status $work/$1.status
  local t=$1 rc=0
  local seeds=$work/seeds/$t corpus=$work/corpus/$t findings=$work/findings/$t/
  mkdir -p "$seeds" "$corpus" "$findings"
  seed_files "$t" | while read -r f; do cp "$f" "$seeds/"; done
  # -rss_limit_mb also bounds one allocation: an input that makes a parser
  # ask for gigabytes is a finding. -timeout: one input may take 30 s.
  "$build/tests/fuzz/${t}_fuzz" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$findings" "$corpus" "$seeds" >"$work/$t.log" 2>&1 || rc=$?
  echo "$rc" >"$work/$t.status"
}

started=$(date -u +%Y-%m-%dT%H:%MZ)
for t in "${targets[@]}"; do
  rm -f "$work/$t.status"
  run_target "$t" &
  while (($(jobs -rp | wc -l) >= parallel)); do wait -n || true; done
done
wait
echo "== fuzzing: $seconds s per target, started $started =="
status=0
for t in "${targets[@]}"; do
  if [[ $(cat "$work/$t.status" 2>/dev/null) == 0 ]]; then result=ok; else result=FINDING; status=1; fi
  runs=$(sed -n "s/^stat::number_of_executed_units: *//p" "$work/$t.log" 2>/dev/null | tail -1 || true)
  echo "$t: $result, ${runs:-?} executions, corpus $(ls "$work/corpus/$t" | wc -l) inputs"
  if [[ $result != ok ]]; then
    grep -E 'ERROR|runtime error|finding|terminate|SUMMARY|Test unit written' "$work/$t.log" | head -20 || true
    echo "   full log: $work/$t.log; inputs: $work/findings/$t/"
  fi
done
exit "$status"
