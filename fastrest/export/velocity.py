"""Restitution lookup tables against impact speed for DEM codes: ``fastrest export velocity``.

For one material pair (an :class:`fastrest.Impact`) the rows give, at impact speeds V (m/s) from 0
to ``V_max``, e of every unloading model, 1 - e^2, w_m (m) and w_m* (exact solver,
:mod:`fastrest.direct`). The rows are placed so that linear interpolation in V between two rows
is within ``tol`` of the exact e and 1 - e^2 (absolute) and of w_m* (relative); the placement uses
the fast curves (:mod:`fastrest.curve`) and the result is then measured against the direct solver
at 15 points inside every interval.

Strain hardening: a pair's ``Et`` (and ``flat_Et``; tangent moduli in Pa, default 0) gives the
impact's Et/E (:attr:`fastrest.Impact.et_ratio`, of the body that yields first) and its loading
law (:attr:`fastrest.Impact.loading`), which every row and check then uses; the header records
both. JCG and Etsion unloading were fitted without hardening: their columns are then an
extrapolation (a ValidityWarning once per pair, and a note in the header).
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any
import csv
import io
import json
import math
import os
from collections.abc import Mapping

import numpy as np

from .._validation import ValidityWarning, check_tol, real_scalar, warn
from ..curve_data import build_curve_data, curve_array
from ..direct import impact_array
from ..limits import speed_limit
from ..loading import get as loading_law
from ..impact import Impact
from ..materials import Material
from ..tables.file import check_path, read_bounded
from .. import unloading as _unloading
from ._io import check_target, provenance, write_files
from .._placement import JUMP, interior as _interior, place_rows, scaled_error as _scaled_error

__all__ = ["TOL_MIN", "MAX_ROWS", "MAX_PAIRS", "MAX_PAIRS_BYTES", "Pair", "pair_from_options", "read_pairs",
           "velocity_table", "write_velocity"]

#: Smallest tol: the curves that place the rows are ~1e-13 accurate, the direct solver's
#: Newton step tolerance is 1e-9 in ln w (its e to ~1e-12); 1e-9 keeps the check meaningful.
TOL_MIN = 1e-9
#: Most speed rows of one pair's table (a tol needing more is refused).
MAX_ROWS = 200000
#: Most pairs in one export (a pairs file with more is refused).
MAX_PAIRS = 1000
#: Largest pairs file read (bytes).
MAX_PAIRS_BYTES = 1 << 20
CHECKS_PER_INTERVAL = 15
PAIR_KEYS = ("name", "E", "nu", "Sy", "R", "rho", "mass", "Et", "flat_E", "flat_nu", "flat_Sy", "flat_Et", "V_max")


class Pair(dict[str, Any]):
    """One material pair's inputs (SI units) as given: name, E, nu, Sy, R, rho/mass, Et (tangent
    modulus, Pa; None or 0: no hardening), flat_*, V_max."""


def pair_from_options(**kw: Any) -> Pair:
    return Pair({k: kw.get(k) for k in PAIR_KEYS})


def read_pairs(path: str | os.PathLike[str]) -> list[Pair]:
    """Material pairs from a CSV file with a header row (columns of :data:`PAIR_KEYS`; ``name``,
    ``E``, ``nu``, ``Sy``, ``R`` and ``rho`` or ``mass`` required, empty cells = not given).

    The file is read as table files are (:func:`fastrest.tables.file.read_bounded`): a regular
    file of at most :data:`MAX_PAIRS_BYTES`, never a blocking read of a FIFO or device; at most
    :data:`MAX_PAIRS` pairs. TypeError if ``path`` is not a path; ValueError naming the file
    otherwise.
    """
    data = read_bounded(path, MAX_PAIRS_BYTES, ValueError, "pairs file")
    path = os.fspath(path)
    try:
        text = data.decode("utf-8")
        if "\0" in text:
            raise csv.Error("NUL byte")
        rows = list(csv.DictReader(line for line in text.splitlines() if line.strip()
                                   and not line.lstrip().startswith("#")))
    except (UnicodeDecodeError, csv.Error) as exc:
        raise ValueError(f"{path!r} is not a CSV file ({exc})") from None
    if not rows:
        raise ValueError(f"{path!r} holds no material pairs (a header row and one row per pair)")
    if len(rows) > MAX_PAIRS:
        raise ValueError(f"{path!r} holds {len(rows)} pairs; at most {MAX_PAIRS} in one export")
    unknown = set(rows[0]) - set(PAIR_KEYS)
    if unknown or None in rows[0]:
        raise ValueError(f"unknown column(s) {sorted(map(str, unknown))} in {path!r}; "
                         f"valid: {', '.join(PAIR_KEYS)}")
    pairs: list[Pair] = []
    for i, r in enumerate(rows, start=2):
        p = Pair()
        for k in PAIR_KEYS:
            s = (r.get(k) or "").strip()
            if k == "name":
                p[k] = s or f"pair{len(pairs)}"
                continue
            try:
                p[k] = float(s) if s else None
            except ValueError:
                raise ValueError(f"line {i} of {path!r}: {k} = {s!r} is not a number") from None
        pairs.append(p)
    names = [p["name"] for p in pairs]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise ValueError(f"duplicate pair name(s) {sorted(dup)} in {path!r}")
    for n in names:
        if not _valid_name(n):
            raise ValueError(f"pair name {n!r} in {path!r} must be letters, digits, '-' or '_' (it names files)")
    return pairs


def _valid_name(n):
    return isinstance(n, str) and n.replace("_", "").replace("-", "").isalnum() and n.isascii()


def impact_of(pair, where=""):
    """The :class:`fastrest.Impact` of a pair; ValueError naming the key and the pair."""
    try:
        for k in ("E", "nu", "Sy", "R"):
            if pair.get(k) is None:
                raise ValueError(f"{k} is required")
        if pair.get("rho") is None and pair.get("mass") is None:
            raise ValueError("give rho (sphere density, kg/m^3) or mass (kg)")
        sphere = Material(pair["E"], pair["nu"], pair["Sy"], rho=pair.get("rho"),
                          Et=pair["Et"] if pair.get("Et") is not None else 0.0)
        flat = None
        if pair.get("flat_E") is not None:
            if pair.get("flat_nu") is None:
                raise ValueError("flat_E needs flat_nu")
            flat = Material(pair["flat_E"], pair["flat_nu"],
                            pair["flat_Sy"] if pair.get("flat_Sy") is not None else math.inf,
                            Et=pair["flat_Et"] if pair.get("flat_Et") is not None else 0.0)
        elif any(pair.get(k) is not None for k in ("flat_nu", "flat_Sy", "flat_Et")):
            raise ValueError("flat_nu or flat_Sy or flat_Et needs flat_E (without it the flat is rigid)")
        return Impact(sphere, pair["R"], flat=flat, mass=pair.get("mass"))
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{where}{exc}") from None


def _curves(eps_y, nu, v_max, et_ratio=0.0, loading=None):
    return [build_curve_data(eps_y, nu, name, v_max=v_max, et_ratio=et_ratio, loading=loading)
            for name in _unloading.NAMES]


def _values(curves, v):
    """(quantities, len(v)): w_m*, then e of each model, then 1 - e^2 of each model (curves)."""
    v = np.ascontiguousarray(v, dtype=np.float64)
    out = np.empty((1 + 2 * len(curves), v.size))
    curve_array(curves[0], 0, v, out[0])
    for m, c in enumerate(curves):
        curve_array(c, 1, v, out[1 + m])
        curve_array(c, 2, v, out[1 + len(curves) + m])
    return out


def _direct(v, eps_y, nu, et_ratio=0.0, law=0):
    """Like :func:`_values` from the direct solver; ``law`` is the loading law's code."""
    n = len(_unloading.NAMES)
    out = np.empty((1 + 2 * n, v.size))
    sol = np.empty((5, v.size))
    e, nn, h = np.full(v.size, eps_y), np.full(v.size, nu), np.full(v.size, float(et_ratio))
    for m in range(n):
        impact_array(np.ascontiguousarray(v), e, nn, h, m, False, law, sol)
        out[0], out[1 + m], out[1 + n + m] = sol[0], sol[1], sol[2]
    return out


#: What the tol of a velocity table bounds (error messages of :func:`~fastrest._validation.check_tol`).
_TOL_MEANING = "absolute error of e and 1 - e^2, relative of w_m*"


def velocity_table(impact: Impact, V_max: float | None, tol: float) -> dict[str, Any]:
    """Rows and measured errors for one :class:`fastrest.Impact` up to V_max (m/s).

    Returns a dict: ``columns`` (name -> array), ``critical`` (critical values), ``measured``
    (worst error of linear interpolation against the direct solver per quantity, at
    :data:`CHECKS_PER_INTERVAL` points inside every interval), ``v1_star_max``, ``et_ratio`` and
    ``loading`` (the impact's Et/E and loading law).

    Warns a ValidityWarning once where the impact hardens (``et_ratio > 0``): the JCG and Etsion
    columns are then an extrapolation of models fitted without hardening.
    """
    if not isinstance(impact, Impact):
        raise TypeError(f"impact must be a fastrest.Impact, got {impact!r} ({type(impact).__name__})")
    tol = check_tol(tol, TOL_MIN, _TOL_MEANING)
    V_max = real_scalar(V_max, "V_max")
    Vc = impact.V_c
    h, law = impact.et_ratio, loading_law(impact.loading)
    v_lim = speed_limit(impact.eps_y, impact.nu, et_ratio=h, loading=law)
    lim = v_lim * Vc
    if not (V_max > 0 and V_max <= lim * (1 + 1e-12)):
        raise ValueError(f"V_max = {V_max!r} m/s is outside (0, {lim:.6g}] m/s: the model ends at "
                         f"w_m* = 425 for this pair (V_c = {Vc:.6g} m/s)")
    if h > 0.0:
        unfitted = [m.short for m in _unloading.MODELS.values() if not m.fits_hardening]
        warn(f"the pair hardens (Et/E = {h:.6g}): the {' and '.join(unfitted)} columns unload with models "
             f"fitted to elastic-perfectly plastic finite elements, an extrapolation ("
             f"{', '.join(m.short for m in _unloading.MODELS.values() if m.fits_hardening)} is the pairing "
             "of the hardening law's peers)", ValidityWarning)
    v_top = min(V_max / Vc, v_lim)
    curves = _curves(impact.eps_y, impact.nu, v_top, h, law)
    knots = [0.0, v_top] + [x for x in (1.0,) + JUMP if x < v_top]
    v = place_rows(lambda x: _values(curves, x), knots, tol, MAX_ROWS)
    vals = _direct(v, impact.eps_y, impact.nu, h, law.code)
    # measure: linear interpolation of the exact row values against the exact solver in between
    t = _interior(v[:-1], v[1:], CHECKS_PER_INTERVAL)
    ref = _direct(t.ravel(), impact.eps_y, impact.nu, h, law.code).reshape(-1, *t.shape)
    w = (t - v[:-1, None]) / np.diff(v)[:, None]
    lin = vals[:, :-1, None] * (1 - w) + vals[:, 1:, None] * w
    err = _scaled_error(lin, ref)
    err[:, v[:-1] == JUMP[0]] = 0.0  # the model's own jump
    err = err.reshape(ref.shape[0], -1)
    names = _unloading.NAMES
    qnames = ["omega_m_star"] + [f"e_{n}" for n in names] + [f"loss_{n}" for n in names]
    measured = {q: float(np.max(err[i])) for i, q in enumerate(qnames)}
    cols = {"V_m_s": v * Vc, "V1_star": v}
    for m, n in enumerate(names):
        cols[f"e_{n}"] = vals[1 + m]
    for m, n in enumerate(names):
        cols[f"loss_{n}"] = vals[1 + len(names) + m]
    cols["omega_m_m"] = vals[0] * impact.omega_c
    cols["omega_m_star"] = vals[0]
    return dict(columns=cols, critical=impact.critical_values(), measured=measured, tol=tol,
                V_max=V_max, v1_star_max=v_top, et_ratio=h, loading=law.name)


COLUMN_DOC = {
    "V_m_s": "impact speed V (m/s)", "V1_star": "V/V_c (-)",
    **{f"e_{m.name}": f"coefficient of restitution, {m.label} (-)" for m in _unloading.MODELS.values()},
    **{f"loss_{m.name}": f"1 - e^2, {m.label} (-)" for m in _unloading.MODELS.values()},
    "omega_m_m": "maximum interference w_m (m)", "omega_m_star": "w_m/omega_c (-)",
}


def _header(pair, res):
    prov = provenance()
    law = loading_law(res["loading"])
    loading = {"law": law.name, "et_ratio": res["et_ratio"], "reference": law.reference}
    if res["et_ratio"] > 0.0:
        loading["note"] = ("et_ratio = Et/E of the body that yields first; the law takes E/Sy = (1 - nu^2)/eps_y "
                           "(JGM's equivalent sphere). " + ", ".join(
                               m.short for m in _unloading.MODELS.values() if not m.fits_hardening)
                           + " unloading were fitted without hardening: their columns are an extrapolation")
    return {"fastrest_version": prov["fastrest_version"], "references": prov["references"],
            "source": "fastrest.direct (exact solver); rows placed with fastrest.curve",
            "pair": {k: v for k, v in pair.items() if v is not None}, "critical": res["critical"],
            "loading": loading,
            "V_max_m_s": res["V_max"], "tolerance": res["tol"],
            "tolerance_meaning": "linear interpolation in V between rows: absolute error of e and 1 - e^2, "
                                 "relative error of w_m",
            "measured_max_interpolation_error": res["measured"],
            "below_first_plastic_row": "V <= V_c: elastic, e = 1 exactly",
            "columns": {k: COLUMN_DOC[k] for k in res["columns"]}}


def csv_text(pair, res):
    buf = io.StringIO()
    head = _header(pair, res)
    for k, v in head.items():
        buf.write(f"# {k}: {json.dumps(v)}\n")
    cols = res["columns"]
    buf.write(",".join(cols) + "\n")
    for row in zip(*cols.values()):
        buf.write(",".join(repr(float(x)) for x in row) + "\n")
    return buf.getvalue()


def json_obj(pair, res):
    out = _header(pair, res)
    out["rows"] = {k: [float(x) for x in v] for k, v in res["columns"].items()}
    return out


def _paths(out, pairs):
    """The files ``write_velocity`` writes: out.csv (one pair) or out_<name>.csv, and out.json."""
    base = check_path(out, "out")
    for ext in (".csv", ".json"):
        if base.endswith(ext):
            base = base[: -len(ext)]
    if os.path.basename(base) in ("", ".", ".."):
        raise ValueError(f"out = {out!r} names no file (OUT.csv and OUT.json are written)")
    csvs = [base + ".csv"] if len(pairs) == 1 else [f"{base}_{p['name']}.csv" for p in pairs]
    return csvs, base + ".json"


def write_velocity(out: str | os.PathLike[str], pairs: Sequence[Pair], tol: float,
                   V_max: float | None = None) -> tuple[list[tuple[Any, dict[str, Any]]], list[Any]]:
    """Compute every pair's table, then write ``out``.csv (one pair) or ``out``_<name>.csv (several)
    and ``out``.json (all pairs); nothing is written unless every pair succeeds. Returns
    (list of (pair, result), list of paths).

    Checked before anything is computed: ``out`` (every file it names must be a regular file or a
    new path in a writable directory), ``pairs`` (1 to :data:`MAX_PAIRS` mappings with distinct
    file-safe names), ``tol`` and ``V_max``. A failed write (full disk) raises OSError naming the
    file; no file is left half written.
    """
    if isinstance(pairs, Mapping) or not isinstance(pairs, (list, tuple)):
        raise TypeError(f"pairs must be a list of pair mappings (read_pairs, pair_from_options), got "
                        f"{type(pairs).__name__}")
    if not 1 <= len(pairs) <= MAX_PAIRS:
        raise ValueError(f"pairs must hold 1 to {MAX_PAIRS} pairs; got {len(pairs)}")
    for k, p in enumerate(pairs):
        if not isinstance(p, Mapping):
            raise TypeError(f"pairs[{k}] must be a mapping of {', '.join(PAIR_KEYS)}, got {type(p).__name__}")
        if len(pairs) > 1 and not _valid_name(p.get("name")):
            raise ValueError(f"pairs[{k}]: name {p.get('name')!r} must be letters, digits, '-' or '_' "
                             "(it names a file)")
    names = [p.get("name") for p in pairs]
    if len(pairs) > 1 and len(set(names)) < len(names):
        raise ValueError(f"pairs: duplicate pair names {sorted({n for n in names if names.count(n) > 1})}")
    tol = check_tol(tol, TOL_MIN, _TOL_MEANING)
    if V_max is not None:
        V_max = real_scalar(V_max, "V_max")
    csvs, json_path = _paths(out, pairs)
    for path in csvs + [json_path]:
        check_target(path, "out", "the output file")
    results = []
    for p in pairs:
        where = f"pair {p.get('name')!r}: " if len(pairs) > 1 or p.get("name") else ""
        imp = impact_of(p, where)
        vm = p.get("V_max") if p.get("V_max") is not None else V_max
        if vm is None:
            raise ValueError(f"{where}V_max is required (the largest impact speed, m/s)")
        try:
            results.append((p, velocity_table(imp, vm, tol)))
        except ValueError as exc:
            raise ValueError(f"{where}{exc}") from None
    files = {path: csv_text(p, r) for path, (p, r) in zip(csvs, results)}
    if len(results) == 1:
        doc = json_obj(*results[0])
    else:
        doc = {"pairs": {p["name"]: json_obj(p, r) for p, r in results}}
    files[json_path] = json.dumps(doc, indent=1) + "\n"
    # every temporary file is written before any is renamed into place
    write_files(files, "out", "the output file")
    return results, list(files)
