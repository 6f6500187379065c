"""Coefficient of restitution of a rough surface struck by a rigid flat, for several plasticity indices.

Run from any directory::

    python docs/examples/rough_surface.py [--out OUT.png]

A 10 g rigid flat hits 1 cm^2 of a steel surface (E = 200 GPa, nu = 0.3, Sy = 1 GPa) carrying
1e10 summits/m^2 of radius 100 um with Gaussian heights (Greenwood-Williamson model). The summit
height standard deviation sigma is set from the plasticity index psi = sqrt(sigma/omega_c)
(docs/rough.md, section 5). For psi = 2 an explicit surface of 1e6 sampled summits is shown too
(markers): it follows the statistical model within its sampling error.

Writes a PNG (default: rough_surface.png in the current directory) and prints a table.
"""
import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import fastrest  # noqa: E402
from fastrest import rough  # noqa: E402

STEEL = fastrest.Material(E=200e9, nu=0.3, Sy=1e9)
R_A = 100e-6      # summit radius (m)
ETA = 1e10        # summits per m^2
A_N = 1e-4        # nominal area (m^2): 1e6 summits
M = 0.01          # mass of the flat (kg)
PSI = (0.5, 1.0, 2.0, 4.0)
V1 = np.geomspace(1e-3, 10.0, 60)  # impact speeds (m/s)


def out_path(out=None):
    """The PNG to write: ``out``, by default rough_surface.png in the current directory."""
    return Path(out) if out else Path.cwd() / "rough_surface.png"


def main(out=None):
    out = out_path(out)
    omega_c = fastrest.Impact(STEEL, R_A, mass=M).omega_c
    fig, (ax_e, ax_n) = plt.subplots(1, 2, figsize=(10, 4.2), constrained_layout=True)
    print(f"omega_c = {omega_c:.4g} m;  e_s at V1 = {V1[0]:g} ... {V1[-1]:g} m/s")
    for psi in PSI:
        sigma = psi**2 * omega_c
        surface = rough.RoughSurface(STEEL, R_A, gw=dict(eta=ETA, sigma=sigma, A_n=A_N))
        r = surface.impact(V1, M)
        line, = ax_e.semilogx(V1, r.e, label=f"psi = {psi:g} (sigma = {sigma * 1e9:.3g} nm)")
        ax_n.loglog(V1, r.n_contact, color=line.get_color())
        ax_n.loglog(V1, np.maximum(r.n_yielded, 1e-3), color=line.get_color(), ls="--")
        print(f"psi = {psi:4g}: e_s = {r.e[0]:.4f} ... {r.e[-1]:.4f}; contacts "
              f"{r.n_contact[0]:.3g} ... {r.n_contact[-1]:.3g}")
        if psi == 2.0:
            explicit = rough.RoughSurface(STEEL, R_A, heights=rough.gaussian_summits(
                int(ETA * A_N), sigma, seed=1))
            v = V1[::6]
            rx = explicit.impact(v, M)
            ax_e.semilogx(v, rx.e, "o", color=line.get_color(), mfc="none",
                          label="psi = 2, 1e6 sampled summits")
    ax_e.set_xlabel("impact speed V1 (m/s)")
    ax_e.set_ylabel("coefficient of restitution e_s")
    ax_e.set_title("Rigid flat (10 g) on a rough steel surface")
    ax_e.legend(fontsize=8)
    ax_e.grid(True, which="both", alpha=0.3)
    ax_n.set_xlabel("impact speed V1 (m/s)")
    ax_n.set_ylabel("summits in contact (solid), yielded (dashed)")
    ax_n.set_ylim(1e-2, 2e6)
    ax_n.grid(True, which="both", alpha=0.3)
    fig.savefig(out, dpi=120, metadata={"Software": None})
    print(f"wrote {out}")
    return out


if __name__ == "__main__":
    parser = argparse.ArgumentParser(prog="rough_surface.py", description=__doc__.split("\n")[0])
    parser.add_argument("path", nargs="?", help=argparse.SUPPRESS)
    parser.add_argument("--out", help="output PNG [default: ./rough_surface.png]")
    args = parser.parse_args()
    main(args.out or args.path)
