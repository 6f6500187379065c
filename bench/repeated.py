"""Repeated impacts on one spot: e of the n-th impact, with shakedown marked (docs figure).

``python -m bench.repeated`` writes docs/figures/repeated_impacts.png: a steel sphere (E = 200 GPa,
nu = 0.3, Sy = 1 GPa, rho = 7850 kg/m^3, R = 10 mm) striking a steel flat of the same steel again
and again on the same spot at 0.5, 2 and 8 m/s (JCG unloading), ``Impact.repeated_impacts``;
the first impact with e >= 0.99 is marked on each curve. Needs matplotlib.
"""
import argparse
from pathlib import Path

import numpy as np

import fastrest

HERE = Path(__file__).resolve().parent
STEEL = fastrest.Material(200e9, 0.3, 1e9, rho=7850.0)
SPEEDS = (0.5, 2.0, 8.0)
E_SHAKEDOWN = 0.99


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=60, help="impacts per speed (default 60)")
    ap.add_argument("--out", default=str(HERE.parent / "docs" / "figures" / "repeated_impacts.png"))
    args = ap.parse_args(argv)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    imp = fastrest.Impact(STEEL, 0.01, flat=STEEL)
    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=150)
    n = np.arange(1, args.n + 1)
    for v in SPEEDS:
        r = imp.repeated_impacts(v, args.n)
        k = r.shakedown(E_SHAKEDOWN)
        note = f"; e >= {E_SHAKEDOWN:g} from impact {k} (circled)" if k is not None else ""
        line, = ax.plot(n, r.e, marker=".", ms=3, lw=1, label=f"V = {v:g} m/s (V/V_c = {v / imp.V_c:.0f}){note}")
        if k is not None:
            ax.plot([k], [r.e[k - 1]], "o", mfc="none", ms=8, color=line.get_color())
        print(f"V = {v:g} m/s: e_1 = {r.e[0]:.4f}, e_{args.n} = {r.e[-1]:.4f}, shakedown (e >= {E_SHAKEDOWN:g}) at {k}")
    ax.set_xscale("log")
    ax.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    ax.set_xlabel("impact number n on the same spot")
    ax.set_ylabel("coefficient of restitution e_n")
    ax.set_title("Steel sphere (R = 10 mm) on a steel flat, JCG unloading", fontsize=9)
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(args.out)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
