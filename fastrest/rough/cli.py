"""``fastrest rough FILE``: a measured topography's summits struck by a rigid flat, e(V) on the
command line (:func:`fastrest.rough.from_topography`, :meth:`fastrest.rough.RoughSurface.impact`)."""
from __future__ import annotations

import argparse
import json
from typing import Any

import numpy as np

from ..unloading import NAMES

__all__ = ["add_parser"]

_MATERIAL = {"E": "--E", "nu": "--nu", "Sy": "--Sy", "Et": "--Et"}
_READING = {"cutoff": "--cutoff", "detrend": "--detrend", "unit": "--unit", "physical_size": "--physical-size",
            "periodic": "--periodic", "M": "--M", "V1": "--V"}


def _cmd_rough(args: argparse.Namespace) -> int:
    from .._impact_cli import _material, report_refused
    from ..export.cli import cli_names, cli_warnings
    from .summits import from_topography

    material = _material(_MATERIAL, args.E, args.nu, args.Sy, None, args.Et)
    try:
        # the summits are spheres of the surface's material: Impact's "sphere.E" is --E
        with cli_names(_READING, out=None), cli_warnings({f"sphere.{k}": v for k, v in _MATERIAL.items()}):
            surface = from_topography(args.file, material, detrend=args.detrend, cutoff=args.cutoff,
                                      unit=args.unit, physical_size=args.physical_size,
                                      periodic=True if args.periodic else None)
            r, refused = _impacts_covered(surface, np.asarray(args.V, dtype=float), args)
    except ImportError as exc:  # SurfaceTopography missing: say how to install it
        raise ValueError(str(exc)) from None
    except ValueError as exc:
        raise ValueError(str(exc).replace("extrapolate=True", "--extrapolate")) from None
    found = surface.topography_summits
    rows: list[dict[str, Any]] = []
    for k, v in enumerate(np.atleast_1d(r.V1)):
        rows.append({key: float(np.atleast_1d(getattr(r, key))[k]) for key in
                     ("e", "loss", "d_min", "force_max", "dissipated")}
                    | {"V": float(v), "n_contact": int(np.atleast_1d(r.n_contact)[k]),
                       "n_yielded": int(np.atleast_1d(r.n_yielded)[k])})
    radii = surface.radii
    summary = {"file": found.source, "dx": found.dx, "dy": found.dy, "periodic": found.periodic,
               "area": found.area, **found.counts(), "summit_density": found.density,
               "radius_min": float(radii.min()), "radius_median": float(np.median(radii)),
               "radius_max": float(radii.max()), "height_sigma": float(surface.sigma),
               "plasticity_index": float(surface.plasticity_index)}
    code = report_refused("rough", refused)  # each speed past the model's end: its own line
    if args.json:
        doc = {"topography": summary, "M": args.M, "unloading": args.unloading,
               "detrend": args.detrend or ("mean" if found.periodic else "height"), "cutoff": args.cutoff,
               "impacts": rows}
        if refused:
            doc["refused"] = [{"V": v, "error": msg} for v, msg in refused]
        print(json.dumps(doc, indent=2))
        return code
    print(f"rough surface from {found.source}: {found.n_pixels} pixels, dx = {found.dx:.6g} m, "
          f"dy = {found.dy:.6g} m, {'periodic' if found.periodic else 'non-periodic'}")
    print(f"  summits: {found.n_summits} ({found.n_found} strict 8-neighbour maxima, "
          f"{found.n_curvature_left_out} left out for curvature <= 0, {found.n_border} border pixels excluded)")
    print(f"  summit radius (m): min {summary['radius_min']:.6g}, median {summary['radius_median']:.6g}, "
          f"max {summary['radius_max']:.6g}; summit height sigma = {surface.sigma:.6g} m")
    print(f"  rigid flat of M = {args.M:.6g} kg, {args.unloading} unloading")
    print()
    print(f"  {'V (m/s)':>10s} {'e':>10s} {'loss':>11s} {'n_contact':>10s} {'n_yielded':>10s} {'force_max (N)':>14s}")
    for row in rows:
        print(f"  {row['V']:10.4g} {row['e']:10.6f} {row['loss']:11.4e} {row['n_contact']:10d} "
              f"{row['n_yielded']:10d} {row['force_max']:14.6g}")
    return code


def _impacts_covered(surface, V, args):
    """(the impacts at the speeds of V the model covers, [(speed, why) of each refused]); the first
    refusal raised when no speed is covered."""
    from .._impact_cli import split_speeds

    try:
        return surface.impact(V, args.M, args.unloading, extrapolate=args.extrapolate), []
    except ValueError as whole:
        if not np.all(np.isfinite(V) & (V > 0.0)):  # bad input: as it is
            raise
        kept, refused = split_speeds(V, lambda v: surface.impact(v, args.M, args.unloading,
                                                                 extrapolate=args.extrapolate))
        if not kept.size:  # no speed covered: the whole call's refusal
            raise whole
    return surface.impact(kept, args.M, args.unloading, extrapolate=args.extrapolate), refused


def add_parser(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> argparse.ArgumentParser:
    """Add ``fastrest rough`` to the CLI's subparsers.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The top-level subparsers (:func:`fastrest.cli.main`).

    Returns
    -------
    argparse.ArgumentParser
        The ``rough`` parser.

    Examples
    --------
    >>> import argparse
    >>> sub = argparse.ArgumentParser(prog="fastrest").add_subparsers(dest="cmd")
    >>> add_parser(sub).prog
    'fastrest rough'
    """
    p = sub.add_parser("rough", help="e(V) of a rigid flat striking a measured topography's summits "
                                     "(docs/topography.md)",
                       description="Read a height map (any format SurfaceTopography reads; pip install "
                                   "\"fastrest[topography]\"), find its summits (pixels strictly higher than "
                                   "their 8 neighbours) with their radii of curvature, and print e, the loss "
                                   "1 - e^2, the summits in contact and yielded, and the peak force of a rigid "
                                   "flat of mass --M striking them at each --V (Jackson-Green summits, "
                                   "fastrest.rough.from_topography).")
    p.add_argument("file", help="topography file (units and physical size from the file, or --unit and "
                                "--physical-size)")
    p.add_argument("--E", type=float, required=True, help="surface Young's modulus (Pa)")
    p.add_argument("--nu", type=float, required=True, help="surface Poisson's ratio (-)")
    p.add_argument("--Sy", type=float, required=True, help="surface yield strength (Pa)")
    p.add_argument("--Et", type=float, default=0.0, help="surface tangent modulus (Pa; default 0): strain "
                                                         "hardening, Ghaednia et al. 2019")
    p.add_argument("--M", type=float, required=True, help="mass of the rigid flat (kg)")
    p.add_argument("--V", type=float, nargs="+", required=True, help="impact speeds (m/s)")
    p.add_argument("--unloading", choices=NAMES, default="jcg",
                   help="unloading model of every summit (fastrest.unloading; default jcg)")
    p.add_argument("--cutoff", type=float, help="remove wavelengths shorter than this (m) (default: no filter)")
    p.add_argument("--detrend", choices=("height", "mean", "slope", "curvature", "none"),
                   help="trend removed (SurfaceTopography's detrend; default: mean for a periodic map, height "
                        "(the best plane) otherwise)")
    p.add_argument("--periodic", action="store_true",
                   help="the map is one period of a periodic surface (edges are neighbours; .x3p and many "
                        "formats do not say)")
    p.add_argument("--unit", help="length unit of a file that states none (m, um, nm, ...)")
    p.add_argument("--physical-size", dest="physical_size", type=float, nargs=2, metavar=("SX", "SY"),
                   help="physical size (m) of a file that states none")
    p.add_argument("--extrapolate", action="store_true", help="allow summits past w* = 425 (up to a/R = 1)")
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.set_defaults(func=_cmd_rough)
    return p
