"""Numbers from every public path on a fixed sample, to show a refactor changed none of them.

    python -m bench.fingerprint dump before.npz      # on the old commit
    python -m bench.fingerprint dump after.npz       # on the new one
    python -m bench.fingerprint compare before.npz after.npz

``compare`` prints, per array, whether it is bit-identical and otherwise the largest relative
difference; it exits 1 if any array differs by more than ``--rtol`` (default 0: bit for bit).
Only public names are used, so the script runs unchanged on both sides of a layout change.

``dump`` compiles every kernel into a fresh Numba cache directory (a minute or two): Numba's
on-disk cache checks only the source file of the function it compiled, so after an edit to a
callee in another module a cached caller can still run the old code.
"""
import argparse
import os
import sys
import tempfile
import warnings

import numpy as np


def dump(path):
    warnings.simplefilter("ignore")
    import fastrest
    from fastrest import direct, forward, models, rough
    import fastrest.jit as fj

    rng = np.random.default_rng(7)
    n = 400
    eps = rng.uniform(0.0005, 0.01, n)
    nu = rng.uniform(0.2, 0.45, n)
    lim = np.array([direct.v1_star_limit(a, b) for a, b in zip(eps, nu)])
    v = np.exp(rng.uniform(0, 1, n) * np.log(lim))
    v[:20] = np.linspace(0.5, 2.5, 20)
    out = {}
    steel = fastrest.Material(200e9, 0.33, 1.12e9, 7800)
    alu = fastrest.Material(70e9, 0.3, 2.8e8, 2700)
    scene = fastrest.scene([(0.005, 0.33), (0.002, 0.3)], v_max=[300.0, 200.0])
    for m in ("jcg", "etsion", "brake"):
        for k, x in direct.solve(v, eps, nu, m).items():
            out[f"direct_{m}_{k}"] = np.asarray(x, float)
        c = fastrest.curve(0.005, 0.33, m)
        vv = np.geomspace(0.5, c.v_max, 3000)
        out[f"curve_{m}"] = np.stack([c.e(vv), c.loss(vv), c.omega_m(vv)])
        out[f"curve_jit_{m}"] = np.array([fj.e_curve(c.data, x) for x in vv[::10]])
        out[f"table_{m}"] = np.stack([fastrest.e_star(v, eps, nu, m), fastrest.loss_star(v, eps, nu, m)])
        code = getattr(fj, m.upper())
        tab = fastrest.load_table().data
        out[f"table_jit_{m}"] = np.array([fj.e_table(tab, a, b, c_, code)
                                          for a, b, c_ in zip(v, eps, nu)])
        sv = np.geomspace(0.5, 150.0, 500)
        out[f"scene_{m}"] = fastrest.scene([(0.005, 0.33), (0.002, 0.3)], m, v_max=[300.0, 200.0]).e(
            sv, np.arange(500) % 2)
        fd = forward.forward_data(0.005, 0.33, 400.0, m)
        ww = np.geomspace(0.1, 400, 2000)
        out[f"forward_{m}"] = np.array([forward.forward_values(fd, x) for x in ww])
        rs = rough.RoughSurface(steel, 1e-4, heights=rough.gaussian_summits(2000, 1e-6, seed=1))
        r = rs.impact(np.array([0.01, 0.1, 1.0]), 1e-3, unloading=m)
        out[f"rough_{m}"] = np.asarray(r.e, float)
        law = fastrest.contact_law(0.005, 0.33, m, w_max=400.0)
        w = np.concatenate([np.linspace(0, 300, 700), np.linspace(300, 0, 700)])
        out[f"force_{m}"] = law.force(w)
        out[f"force_impact_{m}"] = np.array([law.impact(x, steps_per_contact=400)["e"] for x in (1.5, 10.0, 100.0)])
        imp = fastrest.Impact(steel, 0.01, alu)
        out[f"impact_{m}"] = np.array([imp.e(x, unloading=m) for x in (0.05, 0.5, 5.0)])
    out["table_w"] = fastrest.omega_m_star(v, eps, nu)
    out["scene_w"] = scene.omega_m(np.geomspace(0.5, 150.0, 500), np.arange(500) % 2)
    out["crit"] = np.array(list(fastrest.Impact(steel, 0.01).critical_values().values()))
    out["P_A"] = np.stack([fastrest.P_star(np.geomspace(0.1, 500, 200), 0.005, 0.33),
                           fastrest.A_star(np.geomspace(0.1, 500, 200), 0.005, 0.33)])
    out["W"] = fastrest.W_star(np.geomspace(0.1, 500, 200), 0.005, 0.33)
    imp = fastrest.Impact(steel, 0.01)
    for name in sorted(models.MODELS):
        with np.errstate(all="ignore"):
            try:
                out[f"model_{name}"] = np.asarray(models.evaluate(name, imp, np.array([0.01, 0.1, 1.0])), float)
            except Exception as exc:  # the same refusal on both sides is what matters
                out[f"model_{name}"] = np.array([hash(type(exc).__name__) % 1000], float)
    np.savez(path, **out)
    print(f"{path}: {len(out)} arrays")


def compare(a_path, b_path, rtol):
    a, b = np.load(a_path), np.load(b_path)
    bad = 0
    for k in sorted(set(a.files) | set(b.files)):
        if k not in a.files or k not in b.files:
            print(f"{k:28s} only in {'after' if k in b.files else 'before'}")
            bad += 1
            continue
        x, y = a[k], b[k]
        if x.shape != y.shape:
            print(f"{k:28s} shape {x.shape} -> {y.shape}")
            bad += 1
        elif np.array_equal(x, y, equal_nan=True):
            print(f"{k:28s} identical")
        else:
            scale = np.maximum(np.abs(x), np.finfo(float).tiny)
            d = np.nanmax(np.abs(x - y) / scale)
            nan_moved = not np.array_equal(np.isnan(x), np.isnan(y))
            print(f"{k:28s} max rel diff {d:.3g}{'  NaN pattern differs' if nan_moved else ''}")
            bad += d > rtol or nan_moved
    print(f"{bad} arrays differ beyond rtol={rtol:g}")
    return 1 if bad else 0


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = p.add_subparsers(dest="cmd", required=True)
    d = sub.add_parser("dump")
    d.add_argument("path")
    c = sub.add_parser("compare")
    c.add_argument("before")
    c.add_argument("after")
    c.add_argument("--rtol", type=float, default=0.0)
    args = p.parse_args(argv)
    if args.cmd == "dump":
        if "numba" in sys.modules:
            raise RuntimeError("run bench.fingerprint in a fresh process: Numba is already imported")
        with tempfile.TemporaryDirectory(prefix="fastrest-fp-") as cache:
            os.environ["NUMBA_CACHE_DIR"] = cache
            dump(args.path)
        return 0
    return compare(args.before, args.after, args.rtol)


if __name__ == "__main__":
    sys.exit(main())
