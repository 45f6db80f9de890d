#!/usr/bin/env bash
# Measured MPI scaling (docs/scaling.md): one fixed scene on the CPU
# reference (or lavapipe) with one thread per rank, rendered by 1 and by 2 ranks,
# interleaved (1, 2, 1, 2, ...) so that a change in the machine's load hits
# both, best of 3 each. Prints each run's wall time (mpirun start to end)
# and the speedup of 2 ranks over 1, and checks the two images are
# bit-identical. Needs build/spectrace built with MPI (scripts/setup.sh).
# Usage: bash scripts/mpi_scaling.sh [BEAMS [DEVICE]]   (default 40000000 cpu)
# DEVICE gpu: lavapipe, one llvmpipe thread per rank (LP_NUM_THREADS=1), so
# that 2 ranks use the 2 cores as 2 CPU-reference ranks do.
set -euo pipefail
cd "$(dirname "$0")/.."
beams=${1:-40000000}
device=${2:-cpu}
case $device in
  cpu) device_args=(--device cpu --threads 1) ;;
  gpu) device_args=(--device gpu); export LP_NUM_THREADS=1 ;;
  *) echo "mpi_scaling: DEVICE must be cpu or gpu" >&2; exit 2 ;;
esac
scene=scenes/reference/pinhole_rect.json
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# --oversubscribe: 2 ranks may exceed the cores MPI counts; as root (CI,
# containers) OpenMPI needs --allow-run-as-root; one node needs no ssh;
# containers without ptrace rights refuse cross-process memory copies.
mpirun=(mpirun --oversubscribe --allow-run-as-root --mca plm_rsh_agent false
        --mca btl_vader_single_copy_mechanism none)
[[ $device == gpu ]] && mpirun+=(-x LP_NUM_THREADS)
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
declare -A best
for round in 1 2 3; do
  for ranks in 1 2; do
    start=$(date +%s.%N)
    "${mpirun[@]}" -np "$ranks" build/spectrace render "$scene" --mpi --beams "$beams" "${device_args[@]}" \
      -q --no-png -o "$out/ranks$ranks.exr"
    end=$(date +%s.%N)
    seconds=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }')
    echo "round $round, $ranks rank(s): $seconds s"
    if [[ -z "${best[$ranks]:-}" ]] || awk -v s="$seconds" -v b="${best[$ranks]}" 'BEGIN { exit !(s < b) }'; then
      best[$ranks]=$seconds
    fi
  done
done
build/exr_pixels_equal "$out/ranks1.exr" "$out/ranks2.exr" >/dev/null
echo "scene $scene, $beams beams, --device $device, 1 thread per rank, $(nproc) cores, $(date -u +%Y-%m-%d)"
echo "load average (1, 5, 15 min) before: $load_before, after: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "best of 3: 1 rank ${best[1]} s, 2 ranks ${best[2]} s; speedup $(awk -v a="${best[1]}" -v b="${best[2]}" 'BEGIN { printf "%.2f", a / b }')"
