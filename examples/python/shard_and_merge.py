"""Renders a scene in shards (disjoint beam ranges of one seed), saves their
states, loads and merges them, and checks that the merged image equals one
render of all the beams bit for bit.

    PYTHONPATH=build/python python3 examples/python/shard_and_merge.py [SCENE.json] --shards 4

Exits 1 if any array differs.
"""

import argparse
import sys
from pathlib import Path

import numpy as np

import spectrace

REPO = Path(__file__).resolve().parents[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", nargs="?", default=str(REPO / "scenes" / "default.json"), help="scene file")
    parser.add_argument("--shards", type=int, default=4, help="how many beam ranges")
    parser.add_argument("--beams", type=int, default=400_000, help="beams in all")
    parser.add_argument("--seed", type=int, default=1, help="the one seed of every shard")
    parser.add_argument("--dir", default="out/shards", help="folder for the shards' states")
    parser.add_argument("--device", default="auto", help="auto, gpu, cpu or a device name")
    args = parser.parse_args()
    if not 1 <= args.shards <= args.beams:
        parser.error("--shards must be between 1 and --beams")

    folder = Path(args.dir)
    folder.mkdir(parents=True, exist_ok=True)
    # Shard i holds beams [i*N/K, (i+1)*N/K): together exactly [0, N), each
    # beam once, as `spectrace render --shard i/K` splits them.
    bounds = [i * args.beams // args.shards for i in range(args.shards + 1)]

    with spectrace.Session(args.device) as session:
        print(f"device: {session.device}")
        paths = []
        for i, (first, end) in enumerate(zip(bounds, bounds[1:])):
            shard = session.render(args.scene, beams=end - first, first_beam=first, seed=args.seed)
            path = folder / f"shard{i}.state"
            shard.state.save(path)
            paths.append(path)
            print(f"shard {i}: beams [{first}, {end}) in {shard.seconds:.2f} s -> {path}")

        # Only the files go on from here, as if the shards ran elsewhere.
        merged = spectrace.merge([spectrace.load_state(p) for p in paths])
        print(f"merged: {merged.beams} beams, ranges {merged.ranges}")
        developed = session.develop(merged)

        whole = session.render(args.scene, beams=args.beams, seed=args.seed)
        print(f"one render: {whole.beams} beams in {whole.seconds:.2f} s")

    failures = []
    if merged.beams != args.beams:
        failures.append(f"the merged state holds {merged.beams} beams, not {args.beams}")
    for name in ("xyz", "rgb", "irradiance", "error"):
        a, b = getattr(developed, name), getattr(whole, name)
        same = a.shape == b.shape and a.dtype == b.dtype and np.array_equal(a, b)
        detail = "" if same or a.shape != b.shape else f", {int(np.count_nonzero(a != b))} values differ"
        print(f"{name:10s} {'identical' if same else 'DIFFERENT'} {a.shape} {a.dtype}{detail}")
        if not same:
            failures.append(f"{name} of the merged shards differs from the single render")

    for failure in failures:
        print(f"error: {failure}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
