"""Command line: ``fastrest e`` (the model for one impact), ``build``, ``info``, ``warmup``, ``figures``,
``export`` (:mod:`fastrest.export.cli`)."""
from __future__ import annotations

from typing import Any
import argparse
import json
import math
import os
import re
import sys
import time
import warnings

import numpy as np

__all__ = ["main"]


def _model_names(values):
    """Names given to ``e --model``/``--models``: repeatable, comma-separated, or ``all``."""
    from .models import MODELS

    names: list[str] = []
    for value in values or []:
        for name in value.split(","):
            name = name.strip()
            if name == "all":
                names.extend(MODELS)
            elif name in MODELS:
                names.append(name)
            else:
                raise ValueError(f"unknown comparison model {name!r}; choose from "
                                 f"{', '.join(MODELS)} or 'all'")
    return list(dict.fromkeys(names))


def _cmd_e(args):
    from . import direct
    from . import models
    from ._validation import ValidityWarning
    from .impact import Impact
    from .materials import Material
    from .unloading import MODELS, NAMES

    names = _model_names(args.models)
    if args.rho is None and args.mass is None:
        raise ValueError("give --rho (sphere density, kg/m^3) or --mass (kg of the moving body)")
    if args.flat_E is None and (args.flat_nu is not None or args.flat_Sy is not None):
        raise ValueError("--flat-nu and --flat-Sy need --flat-E (without it the flat is rigid)")
    if args.flat_E is None and args.flat_Et is not None:
        raise ValueError("--flat-Et needs --flat-E (without it the flat is rigid)")
    sphere = Material(args.E, args.nu, args.Sy, rho=args.rho, Et=args.Et)
    flat = None
    if args.flat_E is not None:
        if args.flat_nu is None:
            raise ValueError("--flat-E needs --flat-nu (the flat's Poisson's ratio)")
        flat = Material(args.flat_E, args.flat_nu, args.flat_Sy if args.flat_Sy is not None else math.inf,
                        Et=args.flat_Et if args.flat_Et is not None else 0.0)
    imp = Impact(sphere, args.R, flat=flat, mass=args.mass)
    crit = imp.critical_values()
    V = np.asarray(args.V, dtype=float)
    try:
        v1: Any = imp.v1_star(V, "jcg", extrapolate=args.extrapolate)  # every model is printed; JCG ends first
    except ValueError as exc:
        msg = str(exc).replace("Pass extrapolate=True", "Pass --extrapolate")
        raise ValueError(f"--V: {msg}") from None
    with warnings.catch_warnings(record=True) as caught:
        # record the model's own warnings (validity, extrapolation) for the output; others pass through
        warnings.simplefilter("always", ValidityWarning)
        sols = {m: direct.solve(v1, imp.eps_y, imp.nu, m, extrapolate=args.extrapolate, et_ratio=imp.et_ratio,
                                loading=imp.loading) for m in NAMES}
        others, model_notes = {}, []
        for n in names:
            # one value per speed: a comparison model undefined at a speed (Weir-Tallon at V = 0)
            # gives null there, with the reason, instead of Infinity or losing the other rows
            vals: list[float | None] = []
            for v in V:
                try:
                    vals.append(float(models.evaluate(n, imp, float(v))))
                except ValueError as exc:
                    vals.append(None)
                    model_notes.append(f"{n} at V = {float(v):g} m/s: {exc}")
            others[n] = vals
    rows: list[dict[str, Any]] = [{"V": float(a), "V1_star": float(b),
             "omega_m_star": float(np.atleast_1d(sols[NAMES[0]]["omega_m_star"])[i])} for i, (a, b) in enumerate(zip(V, v1))]
    for m in NAMES:
        for r, e in zip(rows, np.atleast_1d(sols[m]["e"])):
            r["e_" + m] = float(e)
    for m in NAMES:
        for r in rows:
            r["V2_" + m] = r["V"] * r["e_" + m]
    for n, vals in others.items():
        for r, x in zip(rows, vals):
            r["e_" + n] = x
    notes = sorted({str(w.message) for w in caught if issubclass(w.category, ValidityWarning)}) + model_notes
    for w in caught:
        if not issubclass(w.category, ValidityWarning):
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    if args.json:
        out = {"critical": crit, "impacts": rows, "warnings": notes}
        if imp.et_ratio > 0.0:
            out["loading"] = {"law": imp.loading, "et_ratio": imp.et_ratio}
        if names:
            out["models"] = names
        json.dump(out, sys.stdout, indent=2, allow_nan=False)  # strict JSON: no NaN/Infinity
        print()
        return 0
    if flat is None:
        print("Jackson, Green & Marghitu (2010): sphere on a rigid flat")
    else:
        kind = "an elastic flat (never yields)" if math.isinf(flat.Sy) else "an elastic-plastic flat"
        who = "sphere" if imp.yielding is sphere else "flat"
        print(f"Jackson, Green & Marghitu (2010): sphere on {kind}; the {who} yields first (smaller C(nu) Sy)")
    if imp.et_ratio > 0.0:
        print(f"  strain hardening: Ghaednia et al. (2019) loading, Et/E = {imp.et_ratio:.6g} (docs/model.md section 12)")
    units = {"E_eff": "Pa", "R_eff": "m", "mass": "kg", "nu": "-", "Sy": "Pa", "C": "-", "eps_y": "-",
             "omega_c": "m", "P_c": "N", "A_c": "m^2", "U_c": "J", "V_c": "m/s"}
    for k, val in crit.items():
        print(f"  {k:<8s} = {val:.6g} {units[k]}")
    print()
    widths = {n: max(10, len(n) + 4) for n in names}
    extra_head = "".join(f" {'e (' + n + ')':>{widths[n]}s}" for n in names)
    heads = "".join(f" {'e (' + MODELS[m].short + ')':>11s}" for m in NAMES)
    print(f"  {'V (m/s)':>10s} {'V1*':>10s} {'w_m*':>10s}{heads}{extra_head}")
    for r in rows:
        extra = "".join(f" {r['e_' + n]:{widths[n]}.6f}" if r["e_" + n] is not None
                        else f" {'n/a':>{widths[n]}s}" for n in names)
        cols = "".join(f" {r['e_' + m]:11.6f}" for m in NAMES)
        print(f"  {r['V']:10.4g} {r['V1_star']:10.4g} {r['omega_m_star']:10.5g}{cols}{extra}")
    if names:
        print("  comparison models: fastrest.models.evaluate (see docs/model.md); values are the "
              "published formulas, not clipped to e <= 1")
    for n in notes:
        print(f"  warning: {n}")
    return 0


def _parse_blocks(text):
    if text.strip().lower() in ("none", ""):
        return []
    try:
        return [[float(v), int(n)] for v, n in (item.split(":") for item in text.split(","))]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected V:N[,V:N...] (e.g. 128:24,512:40) or none; got {text!r}") from None


def _cmd_build(args):
    from . import tables

    grid = {k: getattr(args, k) for k in tables.DEFAULT_GRID if getattr(args, k, None) is not None}
    if args.default:
        if grid:
            print("fastrest build: --default takes no grid options", file=sys.stderr)
            return 2
        out = args.out or tables.source_tree_table_path()
        if out is None:
            print("fastrest build: --default writes fastrest/tables/default.h5 of a source checkout; this "
                  "fastrest is installed without one, so give --out FILE", file=sys.stderr)
            return 2
    else:
        out = args.out
    from .tables.error import DEFAULT_TOL

    tol = args.tol if args.tol is not None else (DEFAULT_TOL if args.default else None)
    from .export.cli import cli_names
    from .tables.error import AccuracyWarning

    t0 = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", AccuracyWarning)
        with cli_names({"path": "--out", "tol": "--tol"}, out=None):
            table = tables.build(out, grid, progress=None if args.progress else False, tol=tol)
    dt = time.perf_counter() - t0
    print(f"wrote {table.path} in {dt:.1f} s" + (f" (tol {tol:g})" if tol is not None else ""))
    _print_errors(table.attrs.get("measured_error", {}))
    for w in caught:  # one line each, after the table was written
        if issubclass(w.category, AccuracyWarning):
            print(f"fastrest build: warning: {str(w.message).removeprefix('fastrest.tables.build: ')}",
                  file=sys.stderr)
        else:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    return 0


def _print_errors(errors):
    for name, err in errors.items():
        metric = err.get("metric", "relative")
        note = "" if metric == "relative" else f" ({metric})"
        print(f"  max relative error {name:<13s} {err['max_rel_error']:.2e}{note} at V1*={err['at_v1_star']:.6g} "
              f"eps_y={err['at_eps_y']:.4g} nu={err['at_nu']:.4g}")


def _cmd_info(args):
    from . import tables

    if args.file is None:
        try:
            args.file = str(tables.default_table_path())
        except FileNotFoundError as exc:
            print(f"fastrest info: {exc}", file=sys.stderr)
            return 1
    try:
        t = tables.read(args.file)
    except (tables.TableFileError, OSError) as exc:
        print(f"fastrest info: invalid table: {exc}", file=sys.stderr)
        return 1
    a = t.attrs
    if args.json:
        json.dump({k: v for k, v in a.items()}, sys.stdout, indent=2, default=str)
        print()
        return 0
    print(f"{args.file}: {a['format']} version {a['format_version']}, written by fastrest {a['fastrest_version']}")
    print(f"  model: {a['references']}")
    g = a["grid"]
    blocks = ", ".join(f"{n} up to V1* = {v:g}" for v, n in g["eps_y_blocks"])
    print(f"  grid: eps_y [{g['eps_y_min']}, {g['eps_y_max']}], nodes in C(nu) eps_y: "
          + (f"{blocks}, then {g['n_eps_y']}" if blocks else f"{g['n_eps_y']}")
          + f"; nu [{g['nu_min']}, {g['nu_max']}] ({g['n_nu']} nodes); W*(w*) on {g['n_eps_y_energy']} eps_y nodes")
    print(f"  V1* cells: {a['cells']['count']} (2^{g['fine_bits_per_octave']} per octave up to "
          f"V1* = {g['fine_v1_star_max']:g}, 2^{g['bits_per_octave']} above; degree {a['cells']['degree']}) "
          f"up to V1* = {a['cells']['v1_star_top']:.6g}; closed form below 1.9^1.25")
    q = a["quadrature"]
    print(f"  quadrature: {q['rule']}, {q['order']} points per panel <= {q['panel_width_ln_w']} in ln w")
    _print_errors(a.get("measured_error", {}))
    print(f"  checksum ({a['checksum_algorithm']}): {a['checksum']}")
    return 0


def _cmd_warmup(args):
    """Compile (or load from Numba's cache) every entry point once, timing each."""
    import fastrest
    from . import _threads, rough, tables
    from .jit import e_curve, e_material, e_table
    from .tables.kernel import table_array_parallel

    def step(name, fn):
        t = time.perf_counter()
        fn()
        print(f"  {name:<40s} {time.perf_counter() - t:7.2f} s")

    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        big = np.full(tables.PARALLEL_MIN_POINTS, 5.0)
        steel = fastrest.Material(2e11, 0.3, 1e9)
        ip = fastrest.Impact(steel, 1e-4, mass=1.0)
        c = fastrest.curve(0.005, 0.33, v_max=10.0)
        s = fastrest.scene([(0.005, 0.33), (0.003, 0.3)], v_max=10.0)
        t = fastrest.load_table()
        step("direct solver (scalar, array)", lambda: (fastrest.direct.e_exact(5.0, 0.005, 0.33),
                                                       fastrest.direct.e_exact([2.0, 5.0], 0.005, 0.33)))
        step("curve (scalar, arrays)", lambda: (c.e(5.0), c.e(np.array([5.0])), c.loss(np.array([5.0])),
                                                c.omega_m(np.array([5.0]))))
        step("scene", lambda: (s.e(np.array([5.0]), np.array([1])), s.e(5.0, 1)))
        step("table: scalar e_star", lambda: (fastrest.e_star(5.0, 0.005, 0.33), t.loss_star(5.0, 0.005, 0.33)))
        step("table: batch kernels (serial, parallel)",
             lambda: (fastrest.e_star([5.0], 0.005, 0.33),
                      _threads.run_parallel(table_array_parallel, None, t.data, 1, big, big * 0.001,
                                            big * 0.066, np.empty(big.size))))
        step("jit functions (curve, scene, table)", lambda: _warm_jit(c, s, t, e_curve, e_material, e_table))
        step("rough surfaces (explicit, statistical)",
             lambda: (rough.RoughSurface(steel, 1e-4, heights=[0.0, 1e-7]).impact(1e-3, 1e-3),
                      rough.RoughSurface(steel, 1e-4, gw=dict(eta=1e10, sigma=0.5 * ip.omega_c, A_n=1e-6))
                      .impact([1e-4, 2e-4, 5e-4, 1e-3], 1e-3),
                      rough.RoughSurface(steel, 1e-4, gw=dict(eta=1e10, sigma=0.5 * ip.omega_c, A_n=1e-6))
                      .impact(1e-3, 1e-3)))
        law = fastrest.contact_law(0.005, 0.33)
        step("contact law (force, impact, energy)", lambda: (law.force([0.5, 2.0, 1.0]),
                                                             law.impact(5.0, steps_per_contact=200),
                                                             law.dissipated_energy(law.new_state())))
        step("comparison models", lambda: [fastrest.models.MODELS[m](5.0, 0.005, 0.33) for m in fastrest.models.MODELS])
    print(f"fastrest kernels ready in {time.perf_counter() - t0:.2f} s")
    return 0


def _warm_jit(c, s, t, e_curve, e_material, e_table):
    """The fastrest.jit functions compile inside the caller's function; warm their callees."""
    import numba as nb

    @nb.njit  # not fastrest._jit.jit: a throwaway closure, nothing to cache
    def run(cd, sd, td):
        return e_curve(cd, 5.0) + e_material(sd, 5.0, 1) + e_table(td, 5.0, 0.005, 0.33, 0)

    return run(c.data, s.data, t.data)


def _cmd_figures(args):
    """Draw the paper's Figs 2-8 as PNG files."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("fastrest figures: matplotlib is required; install it with: pip install fastrest[plot]",
              file=sys.stderr)
        return 1
    from .export.cli import cli_names
    from .figures import write_all

    t0 = time.perf_counter()
    with cli_names({"dpi": "--dpi", "out_dir": "--out"}):
        paths = write_all(args.out, dpi=args.dpi)
    for p in paths:
        print(f"wrote {p}")
    print(f"{len(paths)} figures in {time.perf_counter() - t0:.1f} s")
    return 0


_DESCRIPTION = """\
The coefficient of restitution of an elastic-perfectly plastic sphere striking a flat
(Jackson, Green & Marghitu 2010, doi:10.1007/s11071-009-9591-z). Run `fastrest COMMAND -h`
for a command's options.
"""

_GRID_HELP = {
    "eps_y_min": "smallest eps_y = Sy/E' (-)",
    "eps_y_max": "largest eps_y (-); past 0.01 add nodes (--n-eps-y, --eps-y-blocks) and check "
                 "the measured error that build prints",
    "n_eps_y": "nodes in C(nu) eps_y for V1* cells above the last --eps-y-blocks entry",
    "nu_min": "smallest Poisson's ratio (-)",
    "nu_max": "largest Poisson's ratio (-), < 0.5",
    "n_nu": "nodes in nu (uniform)",
    "bits_per_octave": "V1* cells per octave = 2^BITS above --fine-v1-star-max",
    "c_eps_y_map_rate": "clustering of the eps_y nodes towards large C(nu) eps_y (0 = uniform)",
    "fine_bits_per_octave": "V1* cells per octave = 2^BITS up to --fine-v1-star-max",
    "fine_v1_star_max": "V1* (a power of two) where the finer cells end",
    "n_eps_y_energy": "nodes in eps_y of the stored W*(w*) grid",
}


def _models_text():
    """'the three unloading models JCG, Etsion and Brake', from the registry (fastrest.unloading):
    the help texts cannot go stale when a model is added."""
    from .unloading import MODELS

    short = [m.short for m in MODELS.values()]
    if len(short) == 1:
        return f"the unloading model {short[0]}"
    words = {2: "both", 3: "the three", 4: "the four"}
    return (f"{words.get(len(short), f'the {len(short)}')} unloading models "
            f"{', '.join(short[:-1])} and {short[-1]}")


_NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE)


def main(argv: list[str] | None = None) -> int:
    from ._version import __version__
    from .tables import DEFAULT_GRID

    p = argparse.ArgumentParser(prog="fastrest", description=_DESCRIPTION,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True, metavar="COMMAND", title="commands")

    pe = sub.add_parser("e", help="e and w_m* of one sphere at given impact speeds (SI units, exact solver)",
                        description="Critical values (JGM eqs 4-7, 23-28) and, per impact speed, V1* = V/V_c, "
                                    f"w_m* and e for {_models_text()} (exact solver); --json adds "
                                    "the rebound speeds V2 = e V (m/s).")
    pe.add_argument("--E", type=float, required=True, help="sphere Young's modulus (Pa)")
    pe.add_argument("--nu", type=float, required=True, help="sphere Poisson's ratio (-)")
    pe.add_argument("--Sy", type=float, required=True, help="sphere yield strength (Pa)")
    pe.add_argument("--R", type=float, required=True, help="sphere radius (m)")
    pe.add_argument("--rho", type=float, help="sphere density (kg/m^3); gives the mass (or give --mass)")
    pe.add_argument("--mass", type=float, help="mass of the moving body (kg); default: from --rho")
    pe.add_argument("--flat-E", type=float, help="flat's Young's modulus (Pa); without it the flat is rigid")
    pe.add_argument("--flat-nu", type=float, help="flat's Poisson's ratio (-); required with --flat-E")
    pe.add_argument("--flat-Sy", type=float, help="flat's yield strength (Pa); without it the flat never yields")
    pe.add_argument("--Et", type=float, default=0.0,
                    help="sphere tangent modulus (Pa; default 0, elastic-perfectly plastic): strain hardening, "
                         "Ghaednia et al. 2019 (write a negative value as --Et=-1)")
    pe.add_argument("--flat-Et", type=float, help="flat's tangent modulus (Pa; default 0)")
    pe.add_argument("--V", type=float, nargs="+", required=True, help="impact speeds (m/s)")
    pe.add_argument("--extrapolate", action="store_true", help="allow w_m* > 425 (up to a/R = 1)")
    pe.add_argument("--json", action="store_true", help="machine-readable output")
    pe.add_argument("--model", "--models", dest="models", action="append", metavar="NAME",
                    help="also print a comparison model's e (fastrest.models.evaluate): one of "
                         "thornton, weir_tallon, chang_ling, wu, jgm_fit_jcg, jgm_fit_etsion, or all; "
                         "repeatable or comma-separated")
    pe.set_defaults(func=_cmd_e)

    pb = sub.add_parser("build", help="build a multi-material table (HDF5)",
                        description=f"Tabulate w_m*, e and 1 - e^2 over eps_y, nu and V1* for {_models_text()}. "
                                    "Defaults are the shipped table's grid.")
    pb.add_argument("--out", help="output file (default: the user cache, $FASTREST_CACHE_DIR)")
    pb.add_argument("--default", action="store_true",
                    help="rebuild the shipped fastrest/tables/default.h5 of this source checkout")
    for k, typ in (("eps_y_min", float), ("eps_y_max", float), ("n_eps_y", int), ("nu_min", float),
                   ("nu_max", float), ("n_nu", int), ("bits_per_octave", int), ("c_eps_y_map_rate", float),
                   ("fine_bits_per_octave", int), ("fine_v1_star_max", float), ("n_eps_y_energy", int)):
        pb.add_argument("--" + k.replace("_", "-"), dest=k, type=typ, metavar="N" if k.startswith("n_") else
                        "BITS" if "bits" in k else "X", help=f"{_GRID_HELP[k]} [default: {DEFAULT_GRID[k]:g}]")
    blocks = ",".join(f"{v:g}:{n}" for v, n in DEFAULT_GRID["eps_y_blocks"])
    pb.add_argument("--eps-y-blocks", dest="eps_y_blocks", type=_parse_blocks, metavar="V:N,V:N",
                    help="cells ending at or below V1* = V (a power of two) use N nodes in C(nu) eps_y; "
                         f"'none' for --n-eps-y everywhere [default: {blocks}]")
    pb.add_argument("--tol", type=float, metavar="TOL",
                    help="refine node counts until the measured error meets TOL (relative; a 1 - e^2 that "
                         "changes sign: relative to max(|1 - e^2|, 0.1)); --default uses 1e-9")
    pb.add_argument("--no-progress", dest="progress", action="store_false", help="no progress bar")
    pb.set_defaults(func=_cmd_build)

    pi = sub.add_parser("info", help="describe a table file; exit 1 if it is invalid",
                        description="Format, provenance, grid and measured error of a table file.")
    pi.add_argument("file", nargs="?", help="table file (HDF5); default: the shipped default table")
    pi.add_argument("--json", action="store_true", help="all root attributes as JSON")
    pi.set_defaults(func=_cmd_info)

    pw = sub.add_parser("warmup", help="compile every Numba kernel into the cache (run once after install)")
    pw.set_defaults(func=_cmd_warmup)

    pf = sub.add_parser("figures", help="draw the paper's Figs 2-8 as PNG files (needs matplotlib)")
    pf.add_argument("--out", required=True, help="output directory (created if needed)")
    pf.add_argument("--dpi", type=int, default=150, help="resolution, 1 to 1200 (default: 150)")
    pf.set_defaults(func=_cmd_figures)

    from .export.cli import add_parser as add_export_parser

    add_export_parser(sub)

    p.add_argument("--version", action="version", version=f"fastrest {__version__}")
    for parser in (p, pe, pb, pi, pw, pf):
        # argparse takes "-2e11" (exponent) or "-inf" for an option: read them as numbers, so a
        # negative value gets the model's own message ("E must be finite and > 0")
        parser._negative_number_matcher = _NEGATIVE_NUMBER
    args = p.parse_args(argv)
    try:
        code = args.func(args)
        sys.stdout.flush()  # a closed pipe shows here, not at interpreter exit
        return code
    except BrokenPipeError:
        # the reader went away (`fastrest info --json FILE | head`): stop quietly, as cat does;
        # stdout goes to /dev/null so that the interpreter's final flush does not complain
        try:
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        except (OSError, ValueError):
            pass
        return 141  # 128 + SIGPIPE, what a shell reports for a command killed by SIGPIPE
    except (ValueError, TypeError) as exc:
        cmd = args.cmd + (f" {args.what}" if getattr(args, "what", None) else "")
        print(f"fastrest {cmd}: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:  # unwritable --out, full disk: the message names the file
        print(f"fastrest {args.cmd}: error: {exc}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
