"""``fastrest export {grid,velocity,c}``: the command-line side of :mod:`fastrest.export`.

The Python functions name their own parameters in errors (``V_max``, ``tol``, ``path``); the
commands translate those names into their options (:func:`cli_names`).
"""
from __future__ import annotations

import argparse
from collections.abc import Iterator
from typing import Any
import contextlib
import re
import shlex
import time
import warnings

from ..unloading import MODELS

__all__ = ["add_parser", "cli_names", "cli_warnings"]

_PAIR_OPTIONS = {k: "--" + k.replace("_", "-") for k in
                 ("E", "nu", "Sy", "R", "rho", "mass", "Et", "flat_E", "flat_nu", "flat_Sy", "flat_Et")}
#: The columns a --pairs file needs (rho or mass), before the optional ones.
_PAIR_COLUMNS_REQUIRED = ("name", "E", "nu", "Sy", "R", "rho")


def _pairs_header() -> str:
    """The header row of a --pairs file as the help and docs/export.md write it:
    ``name,E,nu,Sy,R,rho[,mass,...]``, every column of :data:`fastrest.export.velocity.PAIR_KEYS`
    in that order (the file may order its columns as it likes: they are read by name)."""
    from .velocity import PAIR_KEYS

    optional = [k for k in PAIR_KEYS if k not in _PAIR_COLUMNS_REQUIRED]
    return ",".join(k for k in PAIR_KEYS if k in _PAIR_COLUMNS_REQUIRED) + "[," + ",".join(optional) + "]"


@contextlib.contextmanager
def cli_names(names: dict[str, str], out: str | None = "--out") -> Iterator[None]:
    """Re-raise a TypeError or ValueError with the Python parameters of ``names`` (parameter ->
    option) written as the command's options, and an OSError (it names the file) prefixed with
    the option ``out`` that gave the file (None: unchanged).

    A parameter is translated where a message names it as one: followed by ``=``, ``must``,
    ``is``, ``need(s)``, ``and``, ``or``, ``(`` or the end; ``path`` and ``out`` (also English
    words) only before ``=`` or ``must``.
    """
    try:
        yield
    except OSError as exc:
        if out is None or exc.errno is None or exc.strerror is None:
            raise
        raise OSError(exc.errno, f"{out}: {exc.strerror}") from None
    except (TypeError, ValueError) as exc:
        msg = _as_options(str(exc), names)
        if msg == str(exc):
            raise
        raise type(exc)(msg) from None


def _as_options(msg: str, names: dict[str, str]) -> str:
    """``msg`` with the parameters of ``names`` written as options (the rule of :func:`cli_names`)."""
    for name, option in names.items():
        after = r"\s+(?:=|must\b)" if name in ("path", "out") else \
            r"(?:\s+(?:=|must\b|is\b|needs?\b|and\b|or\b|\()|\s*$|:)"
        msg = re.sub(rf"(?<![\w\-'.\[]){re.escape(name)}(?={after})", option, msg)
    return msg


@contextlib.contextmanager
def cli_warnings(names: dict[str, str], objects: tuple[str, ...] = ("Material: ", "Impact: ")) -> Iterator[None]:
    """Warnings raised inside, issued again (same category) with the Python parameters of ``names``
    written as the command's options (as :func:`cli_names`) and without a leading ``objects``
    prefix: a command-line user never made the Material or Impact the message would name."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield
    for w in caught:
        # the units hint ("check the units: E and Sy in Pa ...") speaks of quantities, not options
        head, hint, tail = str(w.message).partition("; check the units")
        msg = _as_options(head, names) + hint + tail
        for prefix in objects:
            msg = msg.removeprefix(prefix)
        warnings.warn_explicit(msg, w.category, w.filename, w.lineno)


def _cmd_law(args):
    from ..force_law import contact_law
    from . import c_header, law_c

    path = args.out or "fastrest_law.h"
    with cli_names({"materials": "--materials", "path": "--out", "w_max": "--w-max", "unloading": "--unloading"}):
        if args.materials is None:
            raise ValueError("--law needs --materials EPS_Y:NU[:ET_RATIO] ... (normalised materials)")
        given = [k for k in ("V_max", "v_max", "pairs", *_PAIR_OPTIONS) if getattr(args, k, None) is not None]
        if given:
            raise ValueError("--law takes --materials, --unloading and --w-max only")
        materials = c_header.parse_materials(args.materials)
        _check_materials(args.materials, materials)
        laws = [contact_law(m[0], m[1], args.unloading or "jcg", w_max=args.w_max,
                            et_ratio=m[2] if len(m) == 3 else 0.0) for m in materials]
        out = law_c.write_law_header(path, laws, command=_command(args))
    print(f"wrote {out} ({len(laws)} contact laws, {args.unloading or 'jcg'} unloading)")
    return 0


def _cmd_c(args):
    from . import c_header, velocity

    if args.law:
        return _cmd_law(args)
    if args.unloading is not None or args.w_max is not None:
        raise ValueError("--unloading and --w-max go with --law")
    if args.out is None:
        args.out = "fastrest_scene.h"

    names = {"v_max": "--v-max", "V_max": "--V-max", "materials": "--materials", "path": "--out"}
    physical = args.pairs is not None or any(getattr(args, k) is not None for k in _PAIR_OPTIONS)
    if physical and args.pairs is None and args.materials is None:
        names.update(_PAIR_OPTIONS)  # a pair's errors name its options (--E, --nu, ...)
    with cli_names(names):
        if args.materials is not None and (physical or args.V_max is not None):
            raise ValueError("give --materials (normalised EPS_Y:NU[:ET_RATIO]) or the pairs' physical properties "
                             "(--E --nu --Sy --R --rho, or --pairs), not both")
        critical = pair_names = None
        if args.materials is not None:
            materials, v_max = c_header.parse_materials(args.materials), args.v_max
            _check_materials(args.materials, materials)
        elif physical:
            if args.v_max is not None:
                raise ValueError("--v-max (a V1*) is for --materials; give --V-max (m/s) with physical properties")
            pairs = _pairs_from_args(args, velocity)
            if len(pairs) > c_header.MAX_MATERIALS:
                raise ValueError(f"--pairs: at most {c_header.MAX_MATERIALS} pairs in one header; got {len(pairs)}")
            impacts, tops = [], []
            for p in pairs:
                where = f"pair {p.get('name')!r}: " if p.get("name") else ""
                impacts.append(velocity.impact_of(p, where))
                tops.append(p.get("V_max") if p.get("V_max") is not None else args.V_max)
            pair_names = [p.get("name") for p in pairs]
            materials, v_max, critical = c_header.impact_materials(impacts, tops, pair_names)
        else:
            raise ValueError("give --materials EPS_Y:NU ..., or a pair's --E --nu --Sy --R and --rho or --mass, "
                             "or --pairs FILE")
        t0 = time.perf_counter()
        path, curves = c_header.write_header(args.out, materials, v_max, _command(args), critical=critical,
                                             names=pair_names)
    print(f"wrote {path} ({len(materials)} materials, {len(curves[0])} unloading models) "
          f"in {time.perf_counter() - t0:.1f} s")
    for k, c in enumerate(curves):
        hard = f", et_ratio = {materials[k][2]:g}" if len(materials[k]) == 3 and materials[k][2] > 0 else ""
        line = (f"  material {k}: eps_y = {materials[k][0]:g}, nu = {materials[k][1]:g}{hard}, "
                f"V1* up to {c[0].v_max:.6g}")
        if critical:
            line += f" (V up to {c[0].v_max * critical[k]['V_c']:.6g} m/s, V_c = {critical[k]['V_c']:.6g} m/s)"
        print(line)
    return 0


def _check_materials(given, materials):
    """Each --materials entry's eps_y, nu and Et/E in range; ValueError naming the entry."""
    from .._validation import check_eps_y, check_nu
    from ..loading import resolve

    for k, (text, m) in enumerate(zip(given, materials)):
        try:
            check_eps_y(m[0])
            check_nu(m[1])
            resolve(None, m[2] if len(m) == 3 else 0.0)
        except ValueError as exc:
            raise ValueError(f"--materials entry {text!r} (material {k}): {exc}") from None


def _command(args):
    """The command line that reproduces ``args`` of ``export c`` (recorded in the header)."""
    parts = ["fastrest export c"]
    if args.materials is not None:
        parts.append("--materials " + " ".join(shlex.quote(m) for m in args.materials))
    for key, option in list(_PAIR_OPTIONS.items()) + [("pairs", "--pairs"), ("V_max", "--V-max"), ("v_max", "--v-max")]:
        val = getattr(args, key)
        if val is not None:
            parts.append(f"{option} {shlex.quote(val) if isinstance(val, str) else repr(val)}")
    for name in args.pair or ():
        parts.append(f"--pair {shlex.quote(name)}")
    return " ".join(parts)


def _cmd_velocity(args):
    from . import velocity

    names = {"V_max": "--V-max", "tol": "--tol", "out": "--out"}
    if args.pairs is None:
        names.update(_PAIR_OPTIONS)
    with cli_names(names):
        pairs = _pairs_from_args(args, velocity)
        t0 = time.perf_counter()
        results, paths = velocity.write_velocity(args.out, pairs, args.tol, args.V_max)
    return _print_velocity(results, paths, t0)


def _pairs_from_args(args, velocity):
    """The material pairs of a command's :func:`_add_pair_options` (``export velocity``, ``export c``):
    one from --E --nu --Sy --R --rho/--mass (and --flat-*), or those of a --pairs file (--pair picks)."""
    if args.pairs is not None:
        given = [k for k in _PAIR_OPTIONS if getattr(args, k) is not None]
        if given:
            raise ValueError(f"--pairs takes the materials from the file; do not also give "
                             f"{', '.join(_PAIR_OPTIONS[g] for g in given)}")
        try:
            pairs = velocity.read_pairs(args.pairs)
        except ValueError as exc:
            raise ValueError(f"--pairs: {exc}") from None
        if args.pair:
            by = {p["name"]: p for p in pairs}
            unknown = [n for n in args.pair if n not in by]
            if unknown:
                raise ValueError(f"--pair: unknown pair(s) {unknown}; {args.pairs} holds {sorted(by)}")
            pairs = [by[n] for n in args.pair]
        return pairs
    if args.pair:
        raise ValueError("--pair selects pairs of a --pairs file")
    return [velocity.pair_from_options(**{k: getattr(args, k) for k in velocity.PAIR_KEYS if k != "name"})]


def _print_velocity(results, paths, t0):
    for p, r in results:
        name = f"{p['name']}: " if p.get("name") else ""
        print(f"{name}{r['columns']['V_m_s'].size} rows, V up to {r['V_max']:.6g} m/s "
              f"(V_c = {r['critical']['V_c']:.6g} m/s); worst error of linear interpolation against "
              f"the direct solver (tol {r['tol']:g}):")
        print("  " + ", ".join(f"{q} {e:.2e}" for q, e in r["measured"].items()))
    for path in paths:
        print(f"wrote {path}")
    print(f"in {time.perf_counter() - t0:.1f} s")
    return 0


def _cmd_grid(args):
    from . import grid

    t0 = time.perf_counter()
    with cli_names({"tol": "--tol", "n_check": "--check-points", "path": "--out"}):
        ds, report = grid.write_grid(args.out, tol=args.tol, table_path=args.table, n_check=args.check_points)
    shape = " x ".join(f"{k} {v}" for k, v in report["shape"].items())
    print(f"wrote {args.out}: {shape} nodes, {', '.join(report['variables'])} "
          f"in {time.perf_counter() - t0:.1f} s")
    print(f"worst error against the direct solver at {report['n_check']} random points "
          f"(|error| / max(|value|, 1); tol {report['tol']:g}):")
    for method in ("linear", "cubic"):
        print(f"  {method:<6s}: " + ", ".join(f"{q} {e:.2e}" for q, e in report[method].items()))
    print(f"  points within the domain left NaN by the grid's edge: {report['nan_fraction']:.2%}")
    return 0


def _add_pair_options(parser):
    """The options of one material pair in SI units, or a --pairs file: ``export velocity`` and
    ``export c`` share them (read by :func:`_pairs_from_args`)."""
    parser.add_argument("--E", type=float, help="sphere Young's modulus (Pa)")
    parser.add_argument("--nu", type=float, help="sphere Poisson's ratio (-)")
    parser.add_argument("--Sy", type=float, help="sphere yield strength (Pa)")
    parser.add_argument("--R", type=float, help="sphere radius (m)")
    parser.add_argument("--rho", type=float, help="sphere density (kg/m^3)")
    parser.add_argument("--mass", type=float, help="mass of the moving body (kg); default: from --rho")
    parser.add_argument("--flat-E", dest="flat_E", type=float, help="flat's Young's modulus (Pa); default rigid")
    parser.add_argument("--flat-nu", dest="flat_nu", type=float, help="flat's Poisson's ratio (-)")
    parser.add_argument("--flat-Sy", dest="flat_Sy", type=float, help="flat's yield strength (Pa); default never yields")
    parser.add_argument("--Et", type=float, help="sphere's tangent modulus of strain hardening (Pa); default 0: "
                                                 "elastic-perfectly plastic")
    parser.add_argument("--flat-Et", dest="flat_Et", type=float, help="flat's tangent modulus (Pa); default 0")
    parser.add_argument("--pairs", help=f"CSV file of pairs, one per row, under a header row naming the columns "
                                        f"(in any order): {_pairs_header()}; rho or mass; empty cells "
                                        "are not given")
    parser.add_argument("--pair", action="append", metavar="NAME", help="only this pair of --pairs (repeatable)")


def add_parser(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> argparse.ArgumentParser:
    """Add ``export`` and its subcommands to the top-level subparsers ``sub``."""
    px = sub.add_parser("export", help="files for other tools: gridded NetCDF, velocity tables, C header",
                        description="Export the model for tools outside Python (docs/export.md: 'Using fastrest "
                                    "from other tools'). Every file is written atomically.")
    xs = px.add_subparsers(dest="what", required=True, metavar="WHAT")

    pg = xs.add_parser("grid", help="CF-style NetCDF4/HDF5 grid of w_m*, e, 1 - e^2 on (v1_star, eps_y, nu)",
                       description="Rectilinear grid over the table's materials for xarray "
                                   "(engine='h5netcdf') and any NetCDF reader; NaN past w_m* = 425.")
    pg.add_argument("--out", required=True, help="output file (.nc or .h5)")
    pg.add_argument("--tol", type=float, default=None,
                    help="target error of linear interpolation in (ln V1*, eps_y, nu) [default: 1e-3]")
    pg.add_argument("--table", help="source table (default: the shipped one)")
    pg.add_argument("--check-points", type=int, default=20000,
                    help="random points at which the error is measured [default: 20000]")
    pg.set_defaults(func=_cmd_grid)

    pv = xs.add_parser("velocity", help="per material pair: e, 1 - e^2, w_m against impact speed V (CSV, JSON)",
                       description="Rows of V (m/s) against e (every unloading model), 1 - e^2 and w_m, "
                                   "placed so that linear interpolation in V stays within --tol; critical "
                                   "values and provenance in the header. Writes OUT.csv and OUT.json "
                                   "(with --pairs: OUT_<name>.csv per pair and OUT.json).")
    _add_pair_options(pv)
    pv.add_argument("--V-max", dest="V_max", type=float, help="largest impact speed (m/s)")
    pv.add_argument("--tol", type=float, default=1e-4,
                    help="error of linear interpolation between rows (absolute in e and 1 - e^2, "
                         "relative in w_m) [default: 1e-4]")
    pv.add_argument("--out", required=True, help="output name: OUT.csv and OUT.json")
    pv.set_defaults(func=_cmd_velocity)

    pc = xs.add_parser("c", help="self-contained C99 header evaluating e, w_m*, 1 - e^2 per material",
                       description="Static arrays of each material's cells and inline evaluators "
                                   "fastrest_e(k, v1_star, unloading), fastrest_omega_m(k, v1_star), "
                                   "fastrest_loss(k, v1_star, unloading) ("
                                   + ", ".join(f"{m.short.upper()} = {m.code}" for m in MODELS.values())
                                   + "); NaN outside the domain. Link with -lm. Materials: normalised "
                                   "(--materials EPS_Y:NU ...), or material pairs in SI units as for "
                                   "'export velocity' (--E --nu --Sy --R --rho, or --pairs FILE): the header "
                                   "then also holds each pair's critical values (fastrest_V_c[k], "
                                   "fastrest_omega_c[k], fastrest_P_c[k], ...) and fastrest_v1_star(k, V), "
                                   "V (m/s) -> V1*.")
    pc.add_argument("--materials", nargs="+", metavar="EPS_Y:NU[:ET_RATIO]",
                    help="normalised materials k = 0, 1, ...: eps_y = Sy/E', nu and optionally Et/E "
                         "(strain hardening) [default Et/E: 0]")
    _add_pair_options(pc)
    pc.add_argument("--V-max", dest="V_max", type=float,
                    help="largest impact speed (m/s) of a pair given by its properties (a --pairs file's "
                         "V_max column overrides it) [default: each pair's w_m* = 425 speed]")
    pc.add_argument("--v-max", dest="v_max", type=float, metavar="V1_STAR",
                    help="largest V1* of every --materials material [default: each material's w_m* = 425 speed]")
    pc.add_argument("--law", action="store_true",
                    help="write the contact law with its history instead (fastrest_law_step(rows, first, last, "
                         "w_end, state, w), translated from fastrest.jit.contact_force, and each --materials "
                         "material's rows); takes --materials, --unloading, --w-max")
    pc.add_argument("--unloading", choices=list(MODELS), help="with --law: the unloading model [default: jcg]")
    pc.add_argument("--w-max", dest="w_max", type=float, metavar="W_STAR",
                    help="with --law: largest interference w* served [default: the model's end, 425]")
    pc.add_argument("--out", default=None, help="output header [default: fastrest_scene.h; with --law: fastrest_law.h]")
    pc.set_defaults(func=_cmd_c)
    return px
