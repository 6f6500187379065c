"""Command line: ``fastrest e`` (the model for one impact, in ``fastrest/_impact_cli.py``), ``build``,
``info``, ``warmup``, ``figures``, ``export`` (:mod:`fastrest.export.cli`).

What a user sees: errors as ``fastrest COMMAND: error: ...`` (exit status 2 for bad input, 1 for a
file that cannot be read or written), warnings as ``fastrest COMMAND: warning: ...`` on stderr.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import re
import sys
import time
import warnings

import numpy as np

from ._impact_cli import add_parser as add_e_parser, models_text

__all__ = ["main"]


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
            raise ValueError("--default takes no grid options")
        out = args.out or tables.source_tree_table_path()
        if out is None:
            raise ValueError("--default writes fastrest/tables/default.h5 of a source checkout; this "
                             "fastrest is installed without one, so give --out FILE")
    else:
        out = args.out
    from .tables.error import DEFAULT_TOL

    tol = args.tol if args.tol is not None else (DEFAULT_TOL if args.default else None)
    from .export.cli import cli_names
    from .tables.error import AccuracyWarning
    from .tables.file import check_target

    with cli_names({"path": "--out"}):
        tables.normalise_grid(grid)  # the grid options first, then --out
        if args.out is not None:  # one rule with the exports: --out's directory must exist
            check_target(args.out, "path", "the table file")
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


def _round_up(x, digits=3):
    """`x` to `digits` significant digits, rounded up: a printed bound never sits below the value."""
    if not (math.isfinite(x) and x > 0):
        return f"{x:.{digits - 1}e}"
    text = f"{x:.{digits - 1}e}"
    if float(text) < x:
        mantissa, exponent = text.split("e")
        text = f"{float(mantissa) + 10.0 ** (1 - digits):.{digits - 1}f}e{exponent}"
        text = f"{float(text):.{digits - 1}e}"   # 9.99e-10 + 0.01 -> 1.00e-09
    return text


def _print_errors(errors):
    for name, err in errors.items():
        metric = err.get("metric", "relative")
        note = "" if metric == "relative" else f" ({metric})"
        print(f"  max relative error {name:<13s} {_round_up(err['max_rel_error'])}{note} at V1*={err['at_v1_star']:.6g} "
              f"eps_y={err['at_eps_y']:.4g} nu={err['at_nu']:.4g}")


def _cmd_info(args):
    from . import tables

    if args.file is None:
        try:
            args.file = str(tables.default_table_path())
        except FileNotFoundError as exc:
            print(f"fastrest info: error: {exc}", file=sys.stderr)
            return 1
    try:
        t = tables.read(args.file)
    except (tables.TableFileError, OSError) as exc:
        print(f"fastrest info: error: invalid table: {exc}", file=sys.stderr)
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
        step("rough surfaces (explicit with one radius and with radii, statistical)",
             lambda: (rough.RoughSurface(steel, 1e-4, heights=[0.0, 1e-7]).impact(1e-3, 1e-3),
                      rough.RoughSurface(steel, heights=[0.0, 1e-7], radii=[1e-4, 2e-4]).impact(1e-3, 1e-3),
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
        print("fastrest figures: error: matplotlib is required; install it with: pip install fastrest[plot]",
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


_NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE)


def main(argv: list[str] | None = None) -> int:
    from ._version import __version__
    from .tables import DEFAULT_GRID

    p = argparse.ArgumentParser(prog="fastrest", description=_DESCRIPTION,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True, metavar="COMMAND", title="commands")

    pe = add_e_parser(sub)

    pb = sub.add_parser("build", help="build a multi-material table (HDF5)",
                        description=f"Tabulate w_m*, e and 1 - e^2 over eps_y, nu and V1* for {models_text()}. "
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

    pw = sub.add_parser("warmup", help="compile every Numba kernel into the cache (run once after install)",
                        description="Compile (or load from Numba's cache) every entry point once and print the "
                                    "time each took: the direct solver, curves, scenes, the table's scalar and "
                                    "parallel kernels, the fastrest.jit functions, rough surfaces, the contact "
                                    "law and the comparison models. Run it once after installing: later "
                                    "processes then load the kernels instead of compiling them (seconds each). "
                                    "It writes nothing but Numba's cache.")
    pw.set_defaults(func=_cmd_warmup)

    pf = sub.add_parser("figures", help="draw the paper's Figs 2-8 as PNG files (needs matplotlib)",
                        description="Redraw Figs 2-8 of Jackson, Green & Marghitu (2010) from the model (the "
                                    "loading energy, the maximum and residual interference, e against Chang & "
                                    f"Ling, e for {models_text()}, alumina spheres on aluminium and on steel) and "
                                    "e against V1* with strain hardening (Ghaednia et al. 2019): one PNG file "
                                    "each (fig2_energy.png ... hardening_e.png) in --out, replaced atomically. "
                                    "Needs matplotlib (pip install \"fastrest[plot]\").")
    pf.add_argument("--out", required=True, help="output directory (created, with its parents, if needed)")
    pf.add_argument("--dpi", type=int, default=150, help="resolution, 1 to 1200 (default: 150)")
    pf.set_defaults(func=_cmd_figures)

    from .export.cli import add_parser as add_export_parser

    add_export_parser(sub)
    from .lammps.cli import add_parser as add_lammps_parser

    add_lammps_parser(sub)
    from .rough.cli import add_parser as add_rough_parser

    pr = add_rough_parser(sub)

    p.add_argument("--version", action="version", version=f"fastrest {__version__}")
    for parser in (p, pe, pb, pi, pw, pf, pr):
        # argparse takes "-2e11" (exponent) or "-inf" for an option: read them as numbers, so a
        # negative value gets the model's own message ("E must be finite and > 0")
        parser._negative_number_matcher = _NEGATIVE_NUMBER
    args = p.parse_args(argv)
    prefix = "fastrest " + args.cmd + (f" {args.what}" if getattr(args, "what", None) else "")
    with warnings.catch_warnings():  # restores warnings.showwarning on the way out
        warnings.showwarning = _warning_printer(prefix)
        return _run(args, prefix)


def _warning_printer(prefix):
    """``warnings.showwarning`` for the command line: ``fastrest COMMAND: warning: message`` on
    stderr, instead of Python's file, line number and source line."""
    def show(message, category, filename, lineno, file=None, line=None):
        try:
            print(f"{prefix}: warning: {message}", file=sys.stderr if file is None else file)
        except OSError:  # stderr closed: a warning is not worth a failure
            pass
    return show


def _os_error_text(exc):
    """An OSError as a reader wants it: the message (naming the file), without ``[Errno N]``."""
    if exc.strerror is None:
        return str(exc)
    text = exc.strerror
    if exc.filename is not None:
        text += f": {os.fsdecode(exc.filename)!r}"
    return text


def _run(args, prefix):
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
        print(f"{prefix}: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:  # unwritable --out, full disk: the message names the file
        print(f"{prefix}: error: {_os_error_text(exc)}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
