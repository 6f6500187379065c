"""``fastrest export {grid,velocity,c}``: the command-line side of :mod:`fastrest.export`.

The Python functions name their own parameters in errors (``V_max``, ``tol``, ``path``); the
commands translate those names into their options (:func:`cli_names`).
"""
import contextlib
import re
import shlex
import time

__all__ = ["add_parser", "cli_names"]

_PAIR_OPTIONS = {k: "--" + k.replace("_", "-") for k in
                 ("E", "nu", "Sy", "R", "rho", "mass", "flat_E", "flat_nu", "flat_Sy")}


@contextlib.contextmanager
def cli_names(names, out="--out"):
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
        msg = str(exc)
        for name, option in names.items():
            after = r"\s+(?:=|must\b)" if name in ("path", "out") else \
                r"(?:\s+(?:=|must\b|is\b|needs?\b|and\b|or\b|\()|\s*$|:)"
            msg = re.sub(rf"(?<![\w\-'.\[]){re.escape(name)}(?={after})", option, msg)
        if msg == str(exc):
            raise
        raise type(exc)(msg) from None


def _cmd_c(args):
    from . import c_header

    names = {"v_max": "--v-max", "materials": "--materials", "path": "--out"}
    with cli_names(names):
        materials = c_header.parse_materials(args.materials)
        command = ("fastrest export c --materials " + " ".join(shlex.quote(m) for m in args.materials)
                   + (f" --v-max {args.v_max!r}" if args.v_max is not None else ""))
        t0 = time.perf_counter()
        path, curves = c_header.write_header(args.out, materials, args.v_max, command)
    print(f"wrote {path} ({len(materials)} materials, {len(curves[0])} unloading models) "
          f"in {time.perf_counter() - t0:.1f} s")
    for k, c in enumerate(curves):
        print(f"  material {k}: eps_y = {materials[k][0]:g}, nu = {materials[k][1]:g}, V1* up to {c[0].v_max:.6g}")
    return 0


def _cmd_velocity(args):
    from . import velocity

    names = {"V_max": "--V-max", "tol": "--tol", "out": "--out"}
    if args.pairs is None:
        names.update(_PAIR_OPTIONS)
    with cli_names(names):
        pairs = _velocity_pairs(args, velocity)
        t0 = time.perf_counter()
        results, paths = velocity.write_velocity(args.out, pairs, args.tol, args.V_max)
    return _print_velocity(results, paths, t0)


def _velocity_pairs(args, velocity):
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


def add_parser(sub):
    """Add ``export`` and its subcommands to the top-level subparsers ``sub``."""
    px = sub.add_parser("export", help="files for other tools: gridded NetCDF, velocity tables, C header",
                        description="Export the model for tools outside Python (README: 'Using fastrest "
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
    pv.add_argument("--E", type=float, help="sphere Young's modulus (Pa)")
    pv.add_argument("--nu", type=float, help="sphere Poisson's ratio (-)")
    pv.add_argument("--Sy", type=float, help="sphere yield strength (Pa)")
    pv.add_argument("--R", type=float, help="sphere radius (m)")
    pv.add_argument("--rho", type=float, help="sphere density (kg/m^3)")
    pv.add_argument("--mass", type=float, help="mass of the moving body (kg); default: from --rho")
    pv.add_argument("--flat-E", dest="flat_E", type=float, help="flat's Young's modulus (Pa); default rigid")
    pv.add_argument("--flat-nu", dest="flat_nu", type=float, help="flat's Poisson's ratio (-)")
    pv.add_argument("--flat-Sy", dest="flat_Sy", type=float, help="flat's yield strength (Pa); default never yields")
    pv.add_argument("--pairs", help="CSV file of pairs: header name,E,nu,Sy,R,rho[,mass,flat_E,flat_nu,flat_Sy,V_max]")
    pv.add_argument("--pair", action="append", metavar="NAME", help="only this pair of --pairs (repeatable)")
    pv.add_argument("--V-max", dest="V_max", type=float, help="largest impact speed (m/s)")
    pv.add_argument("--tol", type=float, default=1e-4,
                    help="error of linear interpolation between rows (absolute in e and 1 - e^2, "
                         "relative in w_m) [default: 1e-4]")
    pv.add_argument("--out", required=True, help="output name: OUT.csv and OUT.json")
    pv.set_defaults(func=_cmd_velocity)

    pc = xs.add_parser("c", help="self-contained C99 header evaluating e, w_m*, 1 - e^2 per material",
                       description="Static arrays of each material's cells and inline evaluators "
                                   "fastrest_e(k, v1_star, unloading), fastrest_omega_m(k, v1_star), "
                                   "fastrest_loss(k, v1_star, unloading) (JCG = 0, ETSION = 1, BRAKE = 2); "
                                   "NaN outside the domain. Link with -lm.")
    pc.add_argument("--materials", nargs="+", required=True, metavar="EPS_Y:NU",
                    help="materials k = 0, 1, ...: eps_y = Sy/E' and nu")
    pc.add_argument("--v-max", dest="v_max", type=float,
                    help="largest V1* of every material [default: each material's w_m* = 425 speed]")
    pc.add_argument("--out", default="fastrest_scene.h", help="output header [default: fastrest_scene.h]")
    pc.set_defaults(func=_cmd_c)
    return px
