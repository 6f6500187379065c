"""The direct solver near the end of JCG's eq (35): ``python -m bench.jcg_end``.

Extrapolating far past w_m* = 425 (small eps_y), eq (35)'s w_res/w_m reaches 1 at w_m* = 10017.5
and e ~ sqrt(distance to the end). For speeds V1* = (1 - d) x the end speed
(``fastrest.limit(..., "jcg", extrapolate=True).v1_star``), prints the relative error of
``direct.e_exact`` and of R_res/R (``direct.solve``) against the 40-digit reference of
``tests/reference.py`` (the model with the paper's decimal constants), and the change of the exact e
for one ulp of V1* (the problem's own conditioning). Quoted in README ("What is not done yet") and
docs/model.md section 7.
"""
import sys
import warnings
from pathlib import Path

import numpy as np

import fastrest
from fastrest import direct

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
from reference import ref_e_star, ref_residual_star  # noqa: E402

MATERIALS = ((0.0005, 0.2), (0.0005, 0.45), (0.0008, 0.3))
DISTANCES = (1e-3, 1e-6, 1e-9, 1e-12)


def rel(a, b):
    return abs(a - b) / abs(b)


def main():
    print("| eps_y | nu | d | e | rel. error of e | (x d) | R_res/R rel. error | e change for 1 ulp of V1* |")
    print("|---|---|---|---|---|---|---|---|")
    worst = 0.0
    for eps, nu in MATERIALS:
        end = fastrest.limit(eps, nu, "jcg", extrapolate=True).v1_star
        for d in DISTANCES:
            v = float(end * (1 - d))
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", fastrest.ExtrapolationWarning)
                s = direct.solve(v, eps, nu, "jcg", extrapolate=True)
            ref = ref_e_star(v, eps, nu)
            err = rel(s["e"], ref)
            worst = max(worst, err * d)
            one_ulp = rel(ref_e_star(float(np.nextafter(v, 0)), eps, nu), ref)
            rr = rel(s["R_res_ratio"], ref_residual_star(v, eps, nu)[1])
            print(f"| {eps:g} | {nu:g} | {d:g} | {s['e']:.6e} | {err:.2e} | {err * d:.1e} | {rr:.1e} | {one_ulp:.1e} |")
    print(f"\nworst relative error of e x d: {worst:.2e}")


if __name__ == "__main__":
    main()
