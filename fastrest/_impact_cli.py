"""``fastrest e``: the model for one impact in SI units, on the command line (:mod:`fastrest.cli`).

A sphere on a rigid flat, on an elastic or elastic-plastic flat (``--flat-*``), or two free spheres
(``--sphere2-*``, :meth:`fastrest.Impact.two_spheres`). Errors of the Python objects name the
command's options (:func:`fastrest.export.cli.cli_names`).
"""
from __future__ import annotations

from typing import Any
import argparse
import json
import math
import sys
import warnings

import numpy as np

__all__ = ["add_parser", "models_text"]

#: Python parameter -> option, per body: the sphere, the flat, the second sphere.
_SPHERE = {"E": "--E", "nu": "--nu", "Sy": "--Sy", "rho": "--rho", "Et": "--Et"}
_FLAT = {"E": "--flat-E", "nu": "--flat-nu", "Sy": "--flat-Sy", "Et": "--flat-Et"}
_SPHERE2 = {"E": "--sphere2-E", "nu": "--sphere2-nu", "Sy": "--sphere2-Sy", "rho": "--sphere2-rho",
            "Et": "--sphere2-Et"}
_SPHERE2_KEYS = ("E", "nu", "Sy", "Et", "R", "rho", "mass")


def _body_options(body: str, options: dict[str, str]) -> dict[str, str]:
    """``body.E`` -> its option, and so on: the names Impact's messages give a body's values."""
    return {f"{body}.{k}": v for k, v in options.items()}


#: What Impact's messages call the bodies' values, as fastrest e's options.
_IMPACT_NAMES = {**_body_options("sphere", _SPHERE), **_body_options("flat", _FLAT),
                 **_body_options("sphere1", _SPHERE), **_body_options("sphere2", _SPHERE2),
                 "R1": "--R", "R2": "--sphere2-R", "mass1": "--mass", "mass2": "--sphere2-mass", "R": "--R",
                 "mass": "--mass"}


def models_text() -> str:
    """'the three unloading models JCG, Etsion and Brake', from the registry (fastrest.unloading):
    the help texts cannot go stale when a model is added."""
    from .unloading import MODELS

    short = [m.short for m in MODELS.values()]
    if len(short) == 1:
        return f"the unloading model {short[0]}"
    words = {2: "both", 3: "the three", 4: "the four"}
    return (f"{words.get(len(short), f'the {len(short)}')} unloading models "
            f"{', '.join(short[:-1])} and {short[-1]}")


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


def _material(names, E, nu, Sy, rho=None, Et=None):
    """A :class:`fastrest.Material` whose errors and warnings name the body's options ``names``."""
    from .export.cli import cli_names, cli_warnings
    from .materials import Material

    with cli_warnings(names), cli_names(names, out=None):
        return Material(E, nu, Sy if Sy is not None else math.inf, rho=rho, Et=Et if Et is not None else 0.0)


def _impact(args):
    """The :class:`fastrest.Impact` of ``fastrest e``'s options."""
    from .export.cli import cli_names, cli_warnings
    from .impact import Impact

    with cli_warnings(_IMPACT_NAMES):
        return _impact_of(args, cli_names, Impact)


def _impact_of(args, cli_names, Impact):
    s2 = {k: getattr(args, "sphere2_" + k) for k in _SPHERE2_KEYS}
    two = any(v is not None for v in s2.values())
    flat_given = [o for k, o in _FLAT.items() if getattr(args, "flat_" + k) is not None]
    if two and flat_given:
        raise ValueError(f"--sphere2-* (a second free sphere) and {', '.join(flat_given)} (a flat) exclude "
                         "each other")
    if args.rho is None and args.mass is None:
        raise ValueError("give --rho (sphere density, kg/m^3) or --mass (kg of the "
                         + ("sphere" if two else "moving body") + ")")
    if args.Sy is None and not two:
        raise ValueError("--Sy is required (the sphere's yield strength, Pa)")
    sphere = _material(_SPHERE, args.E, args.nu, args.Sy if args.Sy is not None else math.inf, args.rho, args.Et)
    if two:
        for k in ("E", "nu", "R"):
            if s2[k] is None:
                raise ValueError(f"a second sphere needs --sphere2-{k} (give --sphere2-E, --sphere2-nu, "
                                 "--sphere2-R and --sphere2-rho or --sphere2-mass)")
        if s2["rho"] is None and s2["mass"] is None:
            raise ValueError("give --sphere2-rho (kg/m^3) or --sphere2-mass (kg) for the second sphere")
        sphere2 = _material(_SPHERE2, s2["E"], s2["nu"], s2["Sy"], s2["rho"], s2["Et"])
        with cli_names({"R1": "--R", "R2": "--sphere2-R", "mass1": "--mass", "mass2": "--sphere2-mass"}, out=None):
            return Impact.two_spheres(sphere, args.R, sphere2, s2["R"], args.mass, s2["mass"])
    if args.flat_E is None and flat_given:
        raise ValueError(f"{', '.join(flat_given)} need(s) --flat-E (without it the flat is rigid)")
    flat = None
    if args.flat_E is not None:
        if args.flat_nu is None:
            raise ValueError("--flat-E needs --flat-nu (the flat's Poisson's ratio)")
        flat = _material(_FLAT, args.flat_E, args.flat_nu, args.flat_Sy, None, args.flat_Et)
    with cli_names({"R": "--R", "mass": "--mass"}, out=None):
        return Impact(sphere, args.R, flat=flat, mass=args.mass)


def _headline(imp, two):
    if two:
        who = "sphere 1 (--E ...)" if imp.yielding is imp.sphere else "sphere 2 (--sphere2-*)"
        return (f"Jackson, Green & Marghitu (2010): two free spheres, V their relative normal speed; "
                f"{who} yields first (smaller C(nu) Sy)")
    if imp.flat is None:
        return "Jackson, Green & Marghitu (2010): sphere on a rigid flat"
    kind = "an elastic flat (never yields)" if math.isinf(imp.flat.Sy) else "an elastic-plastic flat"
    who = "sphere" if imp.yielding is imp.sphere else "flat"
    return f"Jackson, Green & Marghitu (2010): sphere on {kind}; the {who} yields first (smaller C(nu) Sy)"


def _cmd_e(args):
    from . import direct
    from . import models
    from ._validation import ValidityWarning
    from .unloading import MODELS, NAMES

    names = _model_names(args.models)
    imp = _impact(args)
    two = any(getattr(args, "sphere2_" + k) is not None for k in _SPHERE2_KEYS)
    crit = imp.critical_values()
    # every speed the model covers is printed; each one past its end gets its own error line
    # (JCG ends first: every model is printed)
    V, refused = _speeds_covered(imp, np.asarray(args.V, dtype=float), args.extrapolate)
    v1: Any = imp.v1_star(V, "jcg", extrapolate=args.extrapolate)
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
    code = report_refused("e", refused)
    if args.json:
        out = {"critical": crit, "impacts": rows, "warnings": notes}
        if refused:
            out["refused"] = [{"V": v, "error": msg} for v, msg in refused]
        if two:
            out["bodies"] = "two spheres"
        if imp.et_ratio > 0.0:
            out["loading"] = {"law": imp.loading, "et_ratio": imp.et_ratio}
        if names:
            out["models"] = names
        json.dump(out, sys.stdout, indent=2, allow_nan=False)  # strict JSON: no NaN/Infinity
        print()
        return code
    print(_headline(imp, two))
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
    return code


def _speeds_covered(imp, V, extrapolate):
    """(the speeds of V the model covers, [(speed, why) of each it refuses]); a ValueError naming
    the first refused speed when none is covered."""
    try:
        imp.v1_star(V, "jcg", extrapolate=extrapolate)
        return V, []
    except ValueError as exc:
        if not np.all(np.isfinite(V) & (V >= 0.0)):  # bad input, not a speed past the model's end
            raise ValueError("--V: " + _as_option_text(str(exc))) from None
    kept, refused = split_speeds(V, lambda v: imp.v1_star(v, "jcg", extrapolate=extrapolate))
    if not kept.size:
        raise ValueError(f"--V: {refused[0][1]}")
    return kept, refused


def _as_option_text(msg):
    """A model's message as the command line reads it (``extrapolate=True`` is ``--extrapolate``)."""
    return msg.replace("extrapolate=True", "--extrapolate")


def split_speeds(V, attempt):
    """(the speeds of V, m/s, that ``attempt`` takes one by one, [(speed, why)] of each it refuses
    with a ValueError, its message as the command line reads it): what ``fastrest e`` and
    ``fastrest rough`` print of a list of speeds some of which are past the model's end."""
    kept, refused = [], []
    for v in np.ravel(V):
        try:
            attempt(float(v))
            kept.append(float(v))
        except ValueError as exc:
            refused.append((float(v), _as_option_text(str(exc))))
    return np.array(kept), refused


def report_refused(command, refused):
    """One ``fastrest COMMAND: error: --V SPEED: why`` line on stderr per refused speed; the exit
    status (1 if any, else 0)."""
    for v, msg in refused:
        print(f"fastrest {command}: error: --V {v:g}: {msg}", file=sys.stderr)
    return 1 if refused else 0


def add_parser(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> argparse.ArgumentParser:
    """Add ``e`` to the top-level subparsers ``sub``."""
    pe = sub.add_parser("e", help="e and w_m* of one impact at given impact speeds (SI units, exact solver)",
                        description="Critical values (JGM eqs 4-7, 23-28) and, per impact speed, V1* = V/V_c, "
                                    f"w_m* and e for {models_text()} (exact solver); --json adds "
                                    "the rebound speeds V2 = e V (m/s). The bodies: a sphere (--E --nu --Sy --R, "
                                    "--rho or --mass) on a rigid flat; on an elastic or elastic-plastic flat "
                                    "(--flat-E --flat-nu [--flat-Sy]); or two free spheres (--sphere2-E "
                                    "--sphere2-nu --sphere2-R, --sphere2-rho or --sphere2-mass [--sphere2-Sy]), "
                                    "V then being their relative normal speed (fastrest.Impact.two_spheres).")
    pe.add_argument("--E", type=float, required=True, help="sphere Young's modulus (Pa)")
    pe.add_argument("--nu", type=float, required=True, help="sphere Poisson's ratio (-)")
    pe.add_argument("--Sy", type=float, help="sphere yield strength (Pa); required except with --sphere2-* "
                                             "(default then: the sphere never yields)")
    pe.add_argument("--R", type=float, required=True, help="sphere radius (m)")
    pe.add_argument("--rho", type=float, help="sphere density (kg/m^3); gives the mass (or give --mass)")
    pe.add_argument("--mass", type=float, help="mass of the moving body (kg), with --sphere2-* the first "
                                               "sphere's; default: from --rho")
    pe.add_argument("--flat-E", type=float, help="flat's Young's modulus (Pa); without it the flat is rigid")
    pe.add_argument("--flat-nu", type=float, help="flat's Poisson's ratio (-); required with --flat-E")
    pe.add_argument("--flat-Sy", type=float, help="flat's yield strength (Pa); without it the flat never yields")
    pe.add_argument("--Et", type=float, default=0.0,
                    help="sphere tangent modulus (Pa; default 0, elastic-perfectly plastic): strain hardening, "
                         "Ghaednia et al. 2019 (write a negative value as --Et=-1)")
    pe.add_argument("--flat-Et", type=float, help="flat's tangent modulus (Pa; default 0)")
    s2 = {"E": "second sphere's Young's modulus (Pa)", "nu": "second sphere's Poisson's ratio (-)",
          "Sy": "second sphere's yield strength (Pa); without it the second sphere never yields",
          "Et": "second sphere's tangent modulus (Pa; default 0)", "R": "second sphere's radius (m)",
          "rho": "second sphere's density (kg/m^3); gives its mass (or give --sphere2-mass)",
          "mass": "second sphere's mass (kg); default: from --sphere2-rho"}
    for k in _SPHERE2_KEYS:
        pe.add_argument(f"--sphere2-{k}", dest=f"sphere2_{k}", type=float, help=s2[k])
    pe.add_argument("--V", type=float, nargs="+", required=True,
                    help="impact speeds (m/s); of two spheres, their relative normal speed")
    pe.add_argument("--extrapolate", action="store_true", help="allow w_m* > 425 (up to a/R = 1)")
    pe.add_argument("--json", action="store_true", help="machine-readable output")
    pe.add_argument("--model", "--models", dest="models", action="append", metavar="NAME",
                    help="also print a comparison model's e (fastrest.models.evaluate): one of "
                         "thornton, weir_tallon, chang_ling, wu, jgm_fit_jcg, jgm_fit_etsion, or all; "
                         "repeatable or comma-separated")
    pe.set_defaults(func=_cmd_e)
    return pe
