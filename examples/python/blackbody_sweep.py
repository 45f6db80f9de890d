"""Sweeps a light's blackbody temperature and plots each render's chromaticity
on the CIE 1931 xy diagram, beside the spectral and Planckian loci.

    PYTHONPATH=build/python python3 examples/python/blackbody_sweep.py --out out/blackbody_sweep.png

Exits 1 if the rendered points do not follow the Planckian locus.
"""

import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt
import numpy as np

import spectrace

REPO = Path(__file__).resolve().parents[2]
CMF_CSV = REPO / "data" / "cie" / "cie1931_2deg_xyz.csv"

TEMPERATURES_K = [2000, 2500, 3000, 3500, 4000, 5000, 6000, 7000, 8500, 10000]

# A spot light shining straight onto a bare 1 cm sensor: the 0.5° cone is
# 8.7 mm across there, so every beam lands on the sensor and none is wasted.
SCENE = {
    "camera": {
        "position": [0, 0, 0],
        "look_at": [0, 0, 1],
        "up": [0, 1, 0],
        "sensor": {"width_m": 0.01, "height_m": 0.01, "pixels": [32, 32]},
    },
    "lights": [
        {
            "name": "blackbody",
            "type": "spot",
            "position": [0, 0, 0.5],
            "direction": [0, 0, -1],
            "cone_deg": 0.5,
            "power_w": 1,
            "spd": {"blackbody_k": 3000},
        }
    ],
    "render": {"seed": 1},
}


def tolerance_xy(beams):
    """How far (in xy) a render may be from the locus computed here: the
    renderer integrates the CMFs over 5 nm bins where this file sums them at
    1 nm (well under 0.002), and its beams' Monte Carlo noise falls as
    1/sqrt(beams) (about 0.3/sqrt(beams) on this scene; five times that)."""
    return 0.002 + 1.5 / np.sqrt(beams)


def load_cmf(path):
    table = np.loadtxt(path, delimiter=",", skiprows=1)
    return table[:, 0], table[:, 1:4]


def chromaticity(xyz):
    xyz = np.asarray(xyz, dtype=np.float64)
    total = xyz.sum(axis=-1, keepdims=True)
    return xyz[..., :2] / total


def planck(nm, kelvin):
    """Spectral radiance by Planck's law (any constant factor drops out of xy)."""
    h, c, k = 6.62607015e-34, 2.99792458e8, 1.380649e-23
    m = nm * 1e-9
    return 2 * h * c**2 / m**5 / np.expm1(h * c / (m * k * kelvin))


def planckian_xy(nm, cmf, kelvins):
    # The CMF table has a constant 1 nm step, so a plain sum is the integral
    # up to a factor that chromaticity divides out.
    return np.array([chromaticity(planck(nm, t) @ cmf) for t in kelvins])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default="out/blackbody_sweep.png", help="PNG to write")
    parser.add_argument("--beams", type=int, default=200_000, help="beams per temperature")
    parser.add_argument("--device", default="auto", help="auto, gpu, cpu or a device name")
    args = parser.parse_args()

    nm, cmf = load_cmf(CMF_CSV)
    expected = planckian_xy(nm, cmf, TEMPERATURES_K)

    rendered = []
    with spectrace.Session(args.device) as session:
        print(f"device: {session.device}")
        axes = {"/lights/0/spd/blackbody_k": TEMPERATURES_K}
        for overrides, result in session.sweep(SCENE, axes, beams=args.beams):
            kelvin = overrides["/lights/0/spd/blackbody_k"]
            x, y = chromaticity(result.xyz.reshape(-1, 3).astype(np.float64).mean(axis=0))
            rendered.append((x, y))
            print(f"{kelvin:6d} K  x={x:.4f}  y={y:.4f}  ({result.seconds:.2f} s)")
    rendered = np.array(rendered)

    failures = []
    # Along the Planckian locus x falls as T rises (checked on the computed
    # locus first, so that the rendered points are held to the physics).
    if not np.all(np.diff(expected[:, 0]) < 0):
        failures.append("the computed Planckian locus's x does not fall as T rises")
    if not np.all(np.diff(rendered[:, 0]) < 0):
        failures.append("the rendered x does not fall as T rises")
    distance = np.hypot(*(rendered - expected).T)
    tolerance = tolerance_xy(args.beams)
    for t, d in zip(TEMPERATURES_K, distance):
        if not d < tolerance:
            failures.append(f"{t} K is {d:.4f} from the Planckian locus in xy (tolerance {tolerance:.4f})")
    print(f"largest distance from the Planckian locus: {distance.max():.5f} (tolerance {tolerance:.4f})")

    # The diagram: the spectral locus closed by the line of purples, the
    # Planckian locus from 1000 K to 25000 K, and the rendered points.
    spectral_xy = chromaticity(cmf)
    locus_t = np.geomspace(1000, 25000, 200)
    locus_xy = planckian_xy(nm, cmf, locus_t)
    fig, ax = plt.subplots(figsize=(6.5, 7))
    ax.plot(*np.vstack([spectral_xy, spectral_xy[:1]]).T, color="black", lw=1, label="spectral locus")
    for mark in (460, 480, 500, 520, 540, 560, 580, 600, 620):
        i = int(np.argmin(np.abs(nm - mark)))
        ax.annotate(f"{mark}", spectral_xy[i], fontsize=7, xytext=(4, 2), textcoords="offset points")
    ax.plot(*locus_xy.T, color="tab:gray", lw=1, ls="--", label="Planckian locus")
    ax.scatter(*rendered.T, c=TEMPERATURES_K, cmap="coolwarm_r", s=30, zorder=3, edgecolors="black",
               linewidths=0.5, label="rendered")
    for t, (x, y) in zip(TEMPERATURES_K, rendered):
        # Slanted across the locus, so that close points' labels do not overlap.
        ax.annotate(f"{t} K", (x, y), fontsize=7, xytext=(4, -4), textcoords="offset points", rotation=-45,
                    rotation_mode="anchor", ha="left", va="top")
    ax.set(xlim=(0, 0.8), ylim=(0, 0.9), xlabel="x", ylabel="y", aspect="equal",
           title=f"Blackbody sweep, {args.beams} beams each (CIE 1931 2°)")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right")
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=120, bbox_inches="tight")
    print(f"wrote {out}")

    for failure in failures:
        print(f"error: {failure}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
