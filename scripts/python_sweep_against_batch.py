#!/usr/bin/env python3
"""Whole-process time of 64 small jobs: one `spectrace batch` run against one
Python process that renders them in one spectrace.Session (Session.sweep).

    PYTHONPATH=build/python build/python-venv/bin/python scripts/python_sweep_against_batch.py

The jobs: scenes/batch/lamp.json swept over 16 blackbody temperatures and 4
powers, 20,000 beams each, on the CPU reference (--device). Three variants,
run in turn --rounds times (default 3), each timed as a whole process
(interpreter start and import included) and the best kept:
  batch         spectrace batch of a 64-job sweep line, EXRs without PNGs;
  sweep         Session.sweep, the images kept as arrays (the Python use);
  sweep + EXR   Session.sweep, each image also written with write_exr.
Prints a Markdown table with each variant's best time and batch : variant,
whole process and, for the Python variants, from opening the Session to
the end (after the interpreter's start and the imports). Every process runs
with OPENBLAS_NUM_THREADS=1: numpy's OpenBLAS otherwise starts a thread per
core at import that spins for a while, taking the cores from the render, a
cost of importing numpy rather than of spectrace (it made the whole-process
sweep about 0.2 s slower here).
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
SCENE = REPO / "scenes" / "batch" / "lamp.json"
TEMPERATURES = [2000 + 500 * i for i in range(16)]
POWERS = [0.5, 1, 2, 4]
SWEEP = {"/lights/0/spd/blackbody_k": TEMPERATURES, "/lights/0/power_w": POWERS}

PYTHON_SWEEP = """
import sys, time
import numpy, spectrace
start = time.perf_counter()
scene, beams, device, out = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
sweep = {sweep!r}
with spectrace.Session(device) as session:
    for index, (overrides, result) in enumerate(session.sweep(scene, sweep, beams=beams, seed=3)):
        result.xyz
        if out:
            result.write_exr(f"{{out}}/lamp_{{index}}.exr", png=False)
print(time.perf_counter() - start)
"""


def timed(command, env=None):
    """(whole-process seconds, the seconds the process printed or None)."""
    start = time.perf_counter()
    done = subprocess.run(command, check=True, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, env=env, text=True)
    seconds = time.perf_counter() - start
    printed = done.stdout.strip().splitlines()
    return seconds, float(printed[-1]) if printed else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--beams", type=int, default=20000)
    parser.add_argument("--device", default="cpu")
    parser.add_argument("--cli", default=str(REPO / "build" / "spectrace"))
    args = parser.parse_args()
    env = dict(os.environ, PYTHONPATH=str(REPO / "build" / "python"), OPENBLAS_NUM_THREADS="1")
    with tempfile.TemporaryDirectory() as work:
        jobs = Path(work) / "jobs.jsonl"
        jobs.write_text(json.dumps({"scene": str(SCENE), "output": "lamp_{index}.exr", "beams": args.beams,
                                    "seed": 3, "sweep": SWEEP}) + "\n")
        script = PYTHON_SWEEP.format(sweep=SWEEP)
        variants = {
            "batch": [args.cli, "batch", str(jobs), "--device", args.device, "--no-png", "--quiet",
                      "--out-dir", str(Path(work) / "batch")],
            "sweep": [sys.executable, "-c", script, str(SCENE), str(args.beams), args.device, ""],
            "sweep + EXR": [sys.executable, "-c", script, str(SCENE), str(args.beams), args.device,
                            str(Path(work))],
        }
        best = {name: float("inf") for name in variants}
        inside = {name: float("inf") for name in variants}
        for _ in range(args.rounds):
            for name, command in variants.items():
                whole, printed = timed(command, env)
                best[name] = min(best[name], whole)
                if printed is not None:
                    inside[name] = min(inside[name], printed)
    jobs_count = len(TEMPERATURES) * len(POWERS)
    print(f"| variant | jobs | beams each | whole process s | batch : variant | from the Session's opening s | "
          "batch : that |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for name, seconds in best.items():
        own = inside[name] if inside[name] != float("inf") else seconds
        print(f"| {name} | {jobs_count} | {args.beams} | {seconds:.3f} | {best['batch'] / seconds:.2f} | {own:.3f} | "
              f"{best['batch'] / own:.2f} |")


if __name__ == "__main__":
    main()
