"""A loading / unloading / reloading loop of the time-domain contact law (docs/model.md section 10).

Run from any directory::

    python docs/examples/contact_law_loop.py [--out OUT.png]

One contact (eps_y = 0.005, nu = 0.33) is pushed along the interference path
0 -> 20 -> 8 -> 30 -> 0 (w* = omega/omega_c) for the three unloading models: virgin loading
follows the Jackson-Green law, every return below the largest interference so far follows the
elastic eq-(32) branch of that maximum, reloading retraces it and rejoins the JG law at the old
maximum, and the force is zero below the residual interference w_res*. Writes a PNG (default:
contact_law_loop.png in the current directory; docs/model.md's figure is
``--out docs/figures/contact_law_loop.png``) and prints each model's w_res* after the loop.
"""
import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import fastrest  # noqa: E402

EPS_Y, NU = 0.005, 0.33
LEGS = [(0.0, 20.0), (20.0, 8.0), (8.0, 30.0), (30.0, 0.0)]


def path(n=400):
    return np.concatenate([np.linspace(a, b, n) for a, b in LEGS])


def out_path(argv):
    """The PNG to write: ``--out`` (or a positional path), by default in the current directory."""
    p = argparse.ArgumentParser(prog="contact_law_loop.py", description=__doc__.split("\n")[0])
    p.add_argument("path", nargs="?", help=argparse.SUPPRESS)
    p.add_argument("--out", help="output PNG [default: ./contact_law_loop.png]")
    a = p.parse_args(argv[1:])
    return Path(a.out or a.path or Path.cwd() / "contact_law_loop.png")


def main(argv):
    out = out_path(argv)
    w = path()
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    virgin = np.linspace(0.0, 32.0, 400)
    ax.plot(virgin, fastrest.contact_law(EPS_Y, NU).force(virgin), color="0.75", lw=4,
            label="virgin loading: Jackson-Green law (eqs 9, 14)")
    styles = {"jcg": ("#1f77b4", "-"), "etsion": ("#d62728", "--"), "brake": ("#17becf", ":")}
    for name, (colour, ls) in styles.items():
        law = fastrest.contact_law(EPS_Y, NU, name)
        state = law.new_state()
        p = law.force(w, state)
        ax.plot(w, p, color=colour, ls=ls, lw=1.6, label=f"{name}: unloading / reloading, eq (32)")
        print(f"{name:7s} after the loop: w_max* = {state[0]:.4g}, P*(w_max) = {state[1]:.5g}, "
              f"w_res* = {state[2]:.5g}")
    ax.set_xlabel(r"interference $w^* = \omega/\omega_c$ [-]")
    ax.set_ylabel(r"normal force $P^* = P/P_c$ [-]")
    ax.set_title(rf"Contact law with history: path 0 $\to$ 20 $\to$ 8 $\to$ 30 $\to$ 0 "
                 rf"($\varepsilon_y$ = {EPS_Y:g}, $\nu$ = {NU:g})", fontsize=10)
    ax.set_xlim(0, 32)
    ax.set_ylim(0, None)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=150, metadata={"Software": None})
    print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv)
