"""Adversarial accuracy sweep of every fast path against the direct solver (issue 12).

``python -m bench.adversarial [--quick]`` writes bench/ADVERSARIAL.md: the worst error of the
default table (``fastrest.e_star`` & co.), curves, scenes and the jit functions, on points chosen
to find it rather than at random: every V1* cell boundary and +/- 1 ulp around it, every cell
midpoint, both sides of the switch at 1.9^1.25, V1* -> 1, the last cell before each material's
w_m* = 425 speed down to the limit itself; materials on the corners and densely along the edges of
the table's (eps_y, nu) rectangle (including its last ulp), and random ones inside. The sample is
denser than, and independent of, the one the table is built against (fastrest.tables.error).

Metrics: relative, except for a 1 - e^2 that changes sign (Etsion, Brake: e > 1 just above the
switch), given both absolute and relative to max(|1 - e^2|, 0.1). Also: the largest jump at a cell
boundary (value at the edge + 1 ulp minus at the edge - 1 ulp, in units of the value's ulp) and
the largest step against the model's direction (w_m* decreasing or e increasing), in ulp.
"""
import argparse
import datetime
import math
import sys
import warnings
from pathlib import Path

import numpy as np

import fastrest
from fastrest import direct
from fastrest.energy import V_SWITCH
from fastrest.interpolation import cell_edges

HERE = Path(__file__).resolve().parent
NAMES = ("jcg", "etsion", "brake")


def table_materials(n_edge, n_random, seed):
    rng = np.random.default_rng(seed)
    e0, e1, n0, n1 = 0.0005, 0.01, 0.2, 0.45
    ends_e = (e0, e1, np.nextafter(e1, 0), np.nextafter(e0, 1))
    ends_n = (n0, n1, np.nextafter(n1, 0), np.nextafter(n0, 1))
    pts = [(e, n) for e in ends_e for n in ends_n]
    t = rng.uniform(0.0, 1.0, (4, n_edge))
    pts += [(e1, n0 + x * (n1 - n0)) for x in t[0]] + [(e0, n0 + x * (n1 - n0)) for x in t[1]]
    pts += [(e0 * (e1 / e0) ** x, n0) for x in t[2]] + [(e0 * (e1 / e0) ** x, n1) for x in t[3]]
    pts += list(zip(rng.uniform(e0, e1, n_random), rng.uniform(n0, n1, n_random)))
    return pts


def speeds(edges_lo, lim, rng):
    inner = edges_lo[edges_lo <= lim]
    mids = 0.5 * (inner[:-1] + inner[1:])
    s = np.concatenate([np.nextafter(inner, 0), inner, np.nextafter(inner, np.inf), mids,
                        [1.0 + 1e-12, 1.0 + 1e-9, V_SWITCH, np.nextafter(V_SWITCH, 0), np.nextafter(V_SWITCH, 4),
                         V_SWITCH * (1 + 1e-12), lim, lim * (1 - 1e-12), lim * (1 - 1e-6), lim * (1 - 1e-3)],
                        np.exp(rng.uniform(0, math.log(lim), 24))])
    return s[(s > 0) & (s <= lim)]


def errors(got, ref, sign_changing):
    d = np.abs(got - ref)
    rel = d / np.abs(ref)
    rel = np.where(np.isfinite(rel), rel, np.where(d == 0, 0.0, np.inf))
    out = {"relative": float(np.max(rel))}
    if sign_changing:
        out["absolute"] = float(np.max(d))
        near = np.abs(ref) < 0.1
        out["absolute where |x| < 0.1"] = float(np.max(d[near])) if np.any(near) else 0.0
        out["relative to max(|x|, 0.1)"] = float(np.max(d / np.maximum(np.abs(ref), 0.1)))
    return out


def sweep_table(cfg, log):
    t = fastrest.load_table()
    edges = t.cell_edges[:, 0]
    rng = np.random.default_rng(7)
    v, e, n = [], [], []
    for eps, nu in table_materials(cfg["n_edge"], cfg["n_random"], 11):
        s = speeds(np.concatenate([edges, [t.cell_edges[-1, 1]]]), direct.v1_star_limit(eps, nu) * (1 - 2e-9), rng)
        v.append(s), e.append(np.full(s.size, eps)), n.append(np.full(s.size, nu))
    v, e, n = np.concatenate(v), np.concatenate(e), np.concatenate(n)
    out = {"points": int(v.size)}
    ref_w = direct.omega_m_star(v, e, n)
    out["omega_m_star"] = errors(fastrest.omega_m_star(v, e, n), ref_w, False)
    for m in NAMES:
        s = direct.solve(v, e, n, m)
        out[f"e_{m}"] = errors(fastrest.e_star(v, e, n, m), s["e"], False)
        out[f"loss_{m}"] = errors(fastrest.loss_star(v, e, n, m), s["loss"], bool(np.any(s["loss"] < 0)))
    log(f"  table: {v.size} points")
    return out


def boundary_jumps(f, edges, direction):
    lo, hi = f(np.nextafter(edges, 0)), f(np.nextafter(edges, np.inf))
    ulp = np.spacing(np.abs(0.5 * (lo + hi)))
    jump = (hi - lo) / ulp
    return float(np.max(np.abs(jump))), float(max(0.0, np.max(-direction * jump)))


def sweep_curves(cfg, log):
    rng = np.random.default_rng(5)
    mats = [(0.0005, 0.2), (0.0005, 0.45), (0.01, 0.2), (0.01, 0.45), (0.005, 0.33)]
    mats += list(zip(rng.uniform(0.0005, 0.01, cfg["n_curves"]), rng.uniform(0.2, 0.45, cfg["n_curves"])))
    res = {m: {"e": 0.0, "omega_m": 0.0, "loss": {}} for m in NAMES}
    jumps = {"curve": [0.0, 0], "table": [0.0, 0]}
    for eps, nu in mats:
        for m in NAMES:
            c = fastrest.curve(eps, nu, m)
            _, ed = cell_edges(V_SWITCH, c.v_max, 5)
            v = speeds(np.concatenate([ed[:, 0], [c.v_max]]), c.v_max, rng)
            s = direct.solve(v, eps, nu, m)
            r = res[m]
            r["e"] = max(r["e"], errors(c.e(v), s["e"], False)["relative"])
            r["omega_m"] = max(r["omega_m"], errors(c.omega_m(v), s["omega_m_star"], False)["relative"])
            le = errors(c.loss(v), s["loss"], bool(np.any(s["loss"] < 0)) or m != "jcg")
            for k, x in le.items():
                r["loss"][k] = max(r["loss"].get(k, 0.0), x)
            inner = ed[1:, 0]
            for f, d in ((c.omega_m, 1), (c.e, -1)):
                j, a = boundary_jumps(f, inner, d)
                jumps["curve"][0] = max(jumps["curve"][0], j)
                jumps["curve"][1] = max(jumps["curve"][1], a)
        # the table's cell boundaries for this material (inside its range)
        t = fastrest.load_table()
        lim = direct.v1_star_limit(eps, nu)
        inner = t.cell_edges[1:, 0]
        inner = inner[inner < lim * 0.999]
        for f, d in ((lambda x: fastrest.omega_m_star(x, eps, nu), 1), (lambda x: fastrest.e_star(x, eps, nu), -1)):
            j, a = boundary_jumps(f, inner, d)
            jumps["table"][0] = max(jumps["table"][0], j)
            jumps["table"][1] = max(jumps["table"][1], a)
    log(f"  curves: {len(mats)} materials x {len(NAMES)} models")
    return res, jumps, len(mats)


def write(tab, cur, jumps, n_curves, cfg, path):
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    L = ["# Adversarial accuracy sweep", "",
         f"Generated by `python -m bench.adversarial{' --quick' if cfg['quick'] else ''}` on {date}: worst error "
         "against `fastrest.direct` (itself within ~1e-15 of a 40-digit reference, tests/test_direct.py). "
         "Points: every V1* cell boundary and +/- 1 ulp, cell midpoints, both sides of the switch at 1.9^1.25, "
         "V1* -> 1, the last cell before each material's w_m* = 425 speed down to the limit; see the script's doc.", "",
         f"## Default table ({tab['points']} points; materials on the corners, "
         f"{cfg['n_edge']} random points along each edge of the (eps_y, nu) rectangle, {cfg['n_random']} inside)", "",
         "| quantity | relative | absolute | absolute where abs < 0.1 | relative to max(abs, 0.1) |",
         "|---|---|---|---|---|"]
    nan = float("nan")
    for k, d in tab.items():
        if k == "points":
            continue
        L.append(f"| {k} | {d['relative']:.2e} | {d.get('absolute', nan):.2e} | "
                 f"{d.get('absolute where |x| < 0.1', nan):.2e} | {d.get('relative to max(|x|, 0.1)', nan):.2e} |")
    L += ["", "The relative error of a sign-changing 1 - e^2 (Etsion, Brake) is unbounded at its zero "
          "(just above the switch, nu below ~0.32); its bound is stated absolutely there: 1e-10 where "
          "|1 - e^2| < 0.1, 1e-9 relative above (the metric relative to max(|1 - e^2|, 0.1)).", "",
          f"## Curves ({n_curves} materials, corners included, every model)", "",
          "| model | e | w_m* | 1 - e^2 |", "|---|---|---|---|"]
    for m, r in cur.items():
        loss = ", ".join(f"{k} {x:.1e}" for k, x in r["loss"].items())
        L.append(f"| {m} | {r['e']:.2e} | {r['omega_m']:.2e} | {loss} |")
    L += ["", "## Continuity at cell boundaries", "",
          "| path | largest jump across a boundary (ulp of the value) | largest step against the model's direction "
          "(w_m* falling or e rising; ulp) |",
          "|---|---|---|"]
    for k, (j, a) in jumps.items():
        L.append(f"| {k} | {j:.1f} | {a:.1f} |")
    L += ["", "Before this release (first-kind Chebyshev nodes, no blend) the audit measured jumps of up to "
          "5.3e-14 (curves, ~240 ulp) and 2.2e-10 (tables, ~1e6 ulp) relative."]
    L.append("")
    path.write_text("\n".join(L) + "\n")


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m bench.adversarial", description=__doc__)
    p.add_argument("--quick", action="store_true")
    p.add_argument("--out", default=str(HERE / "ADVERSARIAL.md"))
    a = p.parse_args(argv)
    warnings.simplefilter("ignore", fastrest.ValidityWarning)
    cfg = dict(quick=a.quick, n_edge=12 if a.quick else 64, n_random=8 if a.quick else 64, n_curves=2 if a.quick else 12)
    tab = sweep_table(cfg, print)
    cur, jumps, n = sweep_curves(cfg, print)
    write(tab, cur, jumps, n, cfg, Path(a.out))
    print(Path(a.out).read_text())
    return 0


if __name__ == "__main__":
    sys.exit(main())
