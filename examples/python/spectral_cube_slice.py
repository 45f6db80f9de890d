"""Renders a scene's spectral cube and plots one wavelength slice of it beside
the spectrum of one pixel.

    PYTHONPATH=build/python python3 examples/python/spectral_cube_slice.py [SCENE.json] --nm 550

Exits 1 if the cube does not add up to the irradiance image.
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


def pixel_arg(text):
    x, _, y = text.partition(",")
    return int(x), int(y)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", nargs="?", default=str(REPO / "scenes" / "prism.json"), help="scene file")
    parser.add_argument("--out", default="out/spectral_slice.png", help="PNG to write")
    parser.add_argument("--beams", type=int, default=1_000_000, help="beams to trace")
    parser.add_argument("--nm", type=float, default=550.0, help="wavelength of the slice (nearest bin)")
    parser.add_argument("--pixel", type=pixel_arg, help="X,Y (column, row) of the spectrum; default the brightest")
    parser.add_argument("--device", default="auto", help="auto, gpu, cpu or a device name")
    args = parser.parse_args()

    result = spectrace.render(args.scene, beams=args.beams, device=args.device, spectral=True)
    cube, nm = result.spectral, result.wavelengths_nm  # (H, W, bins) W m^-2 nm^-1; bin centres
    height, width, bins = cube.shape
    print(f"{result!r}: {bins} bins, {nm[0]:g}..{nm[-1]:g} nm, {result.seconds:.2f} s")

    failures = []
    # Each bin holds spectral irradiance, so the cube summed over wavelength
    # (times the bin width) is the irradiance image, up to float32 rounding.
    width_nm = np.diff(nm).mean() if bins > 1 else 1.0
    integrated = cube.astype(np.float64).sum(axis=2) * width_nm
    irradiance = result.irradiance.astype(np.float64)
    scale = max(float(irradiance.max()), 1e-300)
    worst = float(np.abs(integrated - irradiance).max()) / scale
    print(f"cube integrated over wavelength vs irradiance: largest difference {worst:.2e} of the peak")
    if not worst < 1e-4:
        failures.append(f"the cube does not add up to the irradiance ({worst:.2e} of the peak)")

    k = int(np.argmin(np.abs(nm - args.nm)))
    if args.pixel is None:
        row, col = np.unravel_index(int(np.argmax(result.irradiance)), (height, width))
    else:
        col, row = args.pixel
        if not (0 <= col < width and 0 <= row < height):
            parser.error(f"--pixel {col},{row} is outside the {width}x{height} image")
    spectrum = cube[row, col, :]
    print(f"slice at {nm[k]:g} nm (nearest bin to {args.nm:g}); pixel x={col} y={row}: "
          f"irradiance {result.irradiance[row, col]:.4g} W/m^2, peak at {nm[int(np.argmax(spectrum))]:g} nm")

    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4), gridspec_kw={"width_ratios": [1.6, 1]})
    image = left.imshow(cube[:, :, k], cmap="inferno", interpolation="nearest")
    left.plot(col, row, marker="+", color="cyan", markersize=12)
    left.set(title=f"{Path(args.scene).name} at {nm[k]:g} nm", xlabel="x (pixel)", ylabel="y (pixel)")
    fig.colorbar(image, ax=left, label="W m$^{-2}$ nm$^{-1}$", shrink=0.8)
    right.step(nm, spectrum, where="mid", color="black")
    right.axvline(nm[k], color="tab:orange", lw=1, ls="--", label=f"slice {nm[k]:g} nm")
    right.set(title=f"pixel ({col}, {row})", xlabel="wavelength (nm)", ylabel="W m$^{-2}$ nm$^{-1}$")
    right.legend()
    right.grid(alpha=0.3)
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110, bbox_inches="tight")
    print(f"wrote {out}")

    for failure in failures:
        print(f"error: {failure}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
