"""Accuracy of rough-surface 1 - e_s^2 near the onset of yield.

    python -m bench.rough_onset          # from the repository root; prints a markdown table

Public API only (``RoughSurface.impact``, ``direct.loss_exact``) and the 40-digit reference of
``tests/rough_reference.py``, so the script runs against any version of ``fastrest.rough``. For
each case it reports the largest relative error of 1 - e_s^2 over a few speeds an ulp apart:

* one summit at V1* = 1 + x, with M = U_c/2 so that V_c = 2 m/s exactly and V1 = 2 V1* carries
  V1* exactly (reference: ``direct.loss_exact``, exact there), and with M = 1e-6 kg (reference:
  the 40-digit solution for the exact energy M V1^2 / (2 U_c) of the given doubles);
* clusters of summits around the onset (the tallest at w* = 1 + x, others within a few x of it,
  the rest out of contact), a tallest summit well into yield (w* = 1.5) beside summits just past
  the onset and in elastic contact, and a tallest summit at the onset beside summits in elastic
  contact below w* = 1/2 (this one is limited by the rounding of those summits' heights).
"""
import math
import sys
from pathlib import Path

import numpy as np

import fastrest
from fastrest import direct, rough

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
from rough_reference import onset_reference  # noqa: E402

STEEL = fastrest.Material(E=200e9, nu=0.3, Sy=1e9)
R_A = 1e-4
ONSET = (1e-12, 1e-9, 1e-6)


def single_exact(x):
    s = rough.RoughSurface(STEEL, R_A, heights=[3e-7])
    M = s.U_c / 2
    v = 1.0 + x + np.arange(-15, 16) * 2.0**-52
    r = s.impact(2.0 * v, M)
    return float(np.max(np.abs(r.loss / direct.loss_exact(v, s.eps_y, s.nu) - 1)))


def single_any_mass(x, M=1e-6):
    s = rough.RoughSurface(STEEL, R_A, heights=[3e-7])
    Vc = math.sqrt(2 * s.U_c / M)
    err = 0.0
    for V1 in (1.0 + x) * Vc * (1 + np.arange(-3, 4) * 2.0**-52):
        loss, _ = onset_reference([0.0], V1, M, s.U_c)
        err = max(err, abs(s.impact(V1, M).loss / loss - 1))
    return err


def cases(x):
    far = [-1.5, -2.0, -3.7]
    return {"cluster of 5 around the onset": ([0.0, -0.3 * x, -0.7 * x, -1.6 * x, -2.5 * x] + far, 1.0 + x),
            "cluster of 3 past the onset": ([0.0, -0.3 * x, -0.9 * x] + far, 1.0 + x),
            "tallest at w* = 1.5, 3 near the onset, 2 elastic": (
                [0.0, -0.5 + 0.1 * x, -0.5 + 0.5 * x, -0.5 - 0.2 * x, -0.9, -1.2], 1.5),
            "tallest at the onset, 2 elastic below w* = 1/2 (conditioning)": ([0.0, -0.5, -0.9], 1.0 + x)}


def several(h_units, w_top, M=1e-6):
    wc = rough.RoughSurface(STEEL, R_A, heights=[0.0]).omega_c
    z = 3e-7 + np.array(h_units) * wc
    s = rough.RoughSurface(STEEL, R_A, heights=z)
    h = (z - z.max()) / s.omega_c
    E = sum((w_top + hi) ** 2.5 for hi in h if w_top + hi > 0)
    err = 0.0
    for k in range(-3, 4):
        V1 = math.sqrt(2 * s.U_c * E / M) * (1 + k * 2.0**-52)
        loss, _ = onset_reference(h, V1, M, s.U_c)
        err = max(err, abs(s.impact(V1, M).loss / loss - 1))
    return err


def sensitivity(x, M=1e-6):
    """Relative change of the exact 1 - e_s^2 for one ulp of V1 (the last case's conditioning)."""
    h_units, w_top = cases(x)["tallest at the onset, 2 elastic below w* = 1/2 (conditioning)"]
    wc = rough.RoughSurface(STEEL, R_A, heights=[0.0]).omega_c
    z = 3e-7 + np.array(h_units) * wc
    s = rough.RoughSurface(STEEL, R_A, heights=z)
    h = (z - z.max()) / s.omega_c
    V1 = math.sqrt(2 * s.U_c * sum((w_top + hi) ** 2.5 for hi in h) / M)
    a, _ = onset_reference(h, V1, M, s.U_c)
    b, _ = onset_reference(h, np.nextafter(V1, 2 * V1), M, s.U_c)
    return abs(b / a - 1)


def main():
    print("| case | " + " | ".join(f"x = {x:g}" for x in ONSET) + " |")
    print("|---|" + "---|" * len(ONSET))
    print("| one summit, V1* = 1 + x, V_c = 2 m/s (vs direct.loss_exact) | "
          + " | ".join(f"{single_exact(x):.1e}" for x in ONSET) + " |")
    print("| one summit, V1* = 1 + x, M = 1e-6 kg (vs 40 digits) | "
          + " | ".join(f"{single_any_mass(x):.1e}" for x in ONSET) + " |")
    for name in cases(1e-9):
        print(f"| {name} | " + " | ".join(f"{several(*cases(x)[name]):.1e}" for x in ONSET) + " |")
    print("| (that case: change of the exact 1 - e_s^2 for 1 ulp of V1) | "
          + " | ".join(f"{sensitivity(x):.1e}" for x in ONSET) + " |")


if __name__ == "__main__":
    main()
