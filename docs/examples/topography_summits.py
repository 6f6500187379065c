"""A synthetic topography, its summits, and e(V) of the flat striking it (docs/topography.md).

Run from any directory (needs the ``topography`` and ``plot`` extras)::

    python docs/examples/topography_summits.py [--out OUT.png]

A periodic self-affine surface (SurfaceTopography's ``fourier_synthesis``: 256 x 256 pixels over
0.2 mm, Hurst exponent 0.8, rms height 0.2 um, seeded) is read with
:func:`fastrest.rough.load_topography`; its summits (strict 8-neighbour maxima, radius from the
mean principal curvature) are marked on the height map, coloured by radius; beside it, e(V) of a
steel flat of 1 mg striking the explicit summits (:func:`fastrest.rough.from_topography`) and the
spectral Greenwood-Williamson surface of the same map (:func:`fastrest.rough.spectral_surface`).
Writes a PNG (default: topography_summits.png in the current directory; the docs' figure is
``--out docs/figures/topography_summits.png``) and prints the summit counts and e at three speeds.
"""
import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from SurfaceTopography.Generation import fourier_synthesis  # noqa: E402

import fastrest  # noqa: E402
from fastrest import rough  # noqa: E402

N, SIZE, HURST, RMS, SEED = 256, 0.2e-3, 0.8, 0.2e-6, 2026
STEEL = fastrest.Material(E=200e9, nu=0.3, Sy=1e9)
M = 1e-6  # kg
SPEEDS = np.geomspace(1e-3, 1.0, 40)  # m/s


def out_path(argv):
    """The PNG to write: ``--out``, by default in the current directory."""
    p = argparse.ArgumentParser(prog="topography_summits.py", description=__doc__.split("\n")[0])
    p.add_argument("--out", help="output PNG [default: ./topography_summits.png]")
    a = p.parse_args(argv[1:])
    return Path(a.out or Path.cwd() / "topography_summits.png")


def main(argv):
    out = out_path(argv)
    np.random.seed(SEED)  # fourier_synthesis draws from NumPy's global generator
    t = fourier_synthesis((N, N), (SIZE, SIZE), HURST, rms_height=RMS, unit="m", periodic=True)
    topo = rough.load_topography(t, detrend="mean")
    found = rough.topography_summits(topo)
    explicit = rough.from_topography(topo, STEEL)
    spectral = rough.spectral_surface(topo, STEEL)
    e_x, e_s = explicit.impact(SPEEDS, M).e, spectral.impact(SPEEDS, M).e
    print(found.counts(), f"plasticity index of the spectral GW surface: {spectral.plasticity_index:.3g}")
    for k in (0, len(SPEEDS) // 2, len(SPEEDS) - 1):
        print(f"V = {SPEEDS[k]:.3g} m/s: e explicit {e_x[k]:.4f}, spectral GW {e_s[k]:.4f}")

    fig, (a0, a1) = plt.subplots(1, 2, figsize=(11.0, 4.6))
    ext = [0.0, N * topo.dy * 1e6, N * topo.dx * 1e6, 0.0]
    lo, hi = np.percentile(topo.heights, [1, 99]) * 1e6
    a0.imshow(topo.heights * 1e6, cmap="gray", extent=ext, vmin=lo, vmax=hi)
    sc = a0.scatter((found.j + 0.5) * topo.dy * 1e6, (found.i + 0.5) * topo.dx * 1e6, c=found.radii * 1e6,
                    s=5, cmap="plasma", norm=matplotlib.colors.LogNorm())
    fig.colorbar(sc, ax=a0, label="summit radius [um]")
    a0.set_title(f"heights (grey, {lo:.2f} to {hi:.2f} um), {found.n_summits} summits", fontsize=10)
    a0.set_xlabel("y [um]")
    a0.set_ylabel("x [um]")
    a1.semilogx(SPEEDS, e_x, "-", label=f"explicit summits ({found.n_summits}, own radii)")
    a1.semilogx(SPEEDS, e_s, "--", label="spectral Greenwood-Williamson (one mean radius)")
    a1.set_xlabel("impact speed V [m/s]")
    a1.set_ylabel("coefficient of restitution e [-]")
    a1.set_title(f"steel flat, M = {M * 1e6:g} mg; spectral GW: psi = {spectral.plasticity_index:.2f}", fontsize=10)
    a1.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
