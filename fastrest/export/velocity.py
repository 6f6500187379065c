"""Restitution lookup tables against impact speed for DEM codes: ``fastrest export velocity``.

For one material pair (an :class:`fastrest.Impact`) the rows give, at impact speeds V (m/s) from 0
to ``V_max``, e of every unloading model, 1 - e^2, w_m (m) and w_m* (exact solver,
:mod:`fastrest.direct`). The rows are placed so that linear interpolation in V between two rows
is within ``tol`` of the exact e and 1 - e^2 (absolute) and of w_m* (relative); the placement uses
the fast curves (:mod:`fastrest.curve`) and the result is then measured against the direct solver
at 15 points inside every interval.
"""
import csv
import io
import json
import math

import numpy as np

from .._validation import real_scalar
from ..curve_data import build_curve_data, curve_array
from ..direct import impact_array
from ..limits import v1_star_limit
from ..materials import Impact, Material
from .. import unloading as _unloading
from ._io import atomic_path, provenance
from ._placement import JUMP, interior as _interior, place_rows, scaled_error as _scaled_error

__all__ = ["TOL_MIN", "MAX_ROWS", "Pair", "pair_from_options", "read_pairs", "velocity_table",
           "write_velocity"]

#: Smallest --tol: the curves that place the rows are ~1e-13 accurate, the direct solver's
#: Newton step tolerance is 1e-9 in ln w (its e to ~1e-12); 1e-9 keeps the check meaningful.
TOL_MIN = 1e-9
MAX_ROWS = 200000
CHECKS_PER_INTERVAL = 15
PAIR_KEYS = ("name", "E", "nu", "Sy", "R", "rho", "mass", "flat_E", "flat_nu", "flat_Sy", "V_max")


class Pair(dict):
    """One material pair's inputs (SI units) as given: name, E, nu, Sy, R, rho/mass, flat_*, V_max."""


def pair_from_options(**kw):
    return Pair({k: kw.get(k) for k in PAIR_KEYS})


def read_pairs(path, option="--pairs"):
    """Material pairs from a CSV file with a header row (columns of :data:`PAIR_KEYS`; ``name``,
    ``E``, ``nu``, ``Sy``, ``R`` and ``rho`` or ``mass`` required, empty cells = not given)."""
    try:
        with open(path, newline="", encoding="utf-8") as fh:
            rows = list(csv.DictReader(line for line in fh if line.strip() and not line.lstrip().startswith("#")))
    except OSError as exc:
        raise ValueError(f"{option}: cannot read {path!r}: {exc.strerror or exc}") from None
    except (UnicodeDecodeError, csv.Error) as exc:
        raise ValueError(f"{option}: {path!r} is not a CSV file ({exc})") from None
    if not rows:
        raise ValueError(f"{option}: {path!r} holds no material pairs (a header row and one row per pair)")
    unknown = set(rows[0]) - set(PAIR_KEYS)
    if unknown or None in rows[0]:
        raise ValueError(f"{option}: unknown column(s) {sorted(map(str, unknown))} in {path!r}; "
                         f"valid: {', '.join(PAIR_KEYS)}")
    pairs = []
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
                raise ValueError(f"{option}: line {i} of {path!r}: {k} = {s!r} is not a number") from None
        pairs.append(p)
    names = [p["name"] for p in pairs]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise ValueError(f"{option}: duplicate pair name(s) {sorted(dup)} in {path!r}")
    for n in names:
        if not n.replace("_", "").replace("-", "").isalnum():
            raise ValueError(f"{option}: pair name {n!r} must be letters, digits, '-' or '_' (it names files)")
    return pairs


def impact_of(pair, where=""):
    """The :class:`fastrest.Impact` of a pair; ValueError naming the option and the pair."""
    try:
        for k in ("E", "nu", "Sy", "R"):
            if pair.get(k) is None:
                raise ValueError(f"--{k} is required")
        if pair.get("rho") is None and pair.get("mass") is None:
            raise ValueError("give --rho (sphere density, kg/m^3) or --mass (kg)")
        sphere = Material(pair["E"], pair["nu"], pair["Sy"], rho=pair.get("rho"))
        flat = None
        if pair.get("flat_E") is not None:
            if pair.get("flat_nu") is None:
                raise ValueError("--flat-E needs --flat-nu")
            flat = Material(pair["flat_E"], pair["flat_nu"],
                            pair["flat_Sy"] if pair.get("flat_Sy") is not None else math.inf)
        elif pair.get("flat_nu") is not None or pair.get("flat_Sy") is not None:
            raise ValueError("--flat-nu and --flat-Sy need --flat-E (without it the flat is rigid)")
        return Impact(sphere, pair["R"], flat=flat, mass=pair.get("mass"))
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{where}{exc}") from None


def _curves(eps_y, nu, v_max):
    return [build_curve_data(eps_y, nu, name, v_max=v_max) for name in _unloading.NAMES]


def _values(curves, v):
    """(quantities, len(v)): w_m*, then e of each model, then 1 - e^2 of each model (curves)."""
    v = np.ascontiguousarray(v, dtype=np.float64)
    out = np.empty((1 + 2 * len(curves), v.size))
    curve_array(curves[0], 0, v, out[0])
    for m, c in enumerate(curves):
        curve_array(c, 1, v, out[1 + m])
        curve_array(c, 2, v, out[1 + len(curves) + m])
    return out


def _direct(v, eps_y, nu):
    n = len(_unloading.NAMES)
    out = np.empty((1 + 2 * n, v.size))
    sol = np.empty((5, v.size))
    e, nn = np.full(v.size, eps_y), np.full(v.size, nu)
    for m in range(n):
        impact_array(np.ascontiguousarray(v), e, nn, m, False, sol)
        out[0], out[1 + m], out[1 + n + m] = sol[0], sol[1], sol[2]
    return out


def velocity_table(impact, V_max, tol):
    """Rows and measured errors for one :class:`fastrest.Impact` up to V_max (m/s).

    Returns a dict: ``columns`` (name -> array), ``critical`` (critical values), ``measured``
    (worst error of linear interpolation against the direct solver per quantity, at
    :data:`CHECKS_PER_INTERVAL` points inside every interval), ``v1_star_max``.
    """
    tol = real_scalar(tol, "--tol")
    if not (TOL_MIN <= tol < 1.0):
        raise ValueError(f"--tol must be in [{TOL_MIN:g}, 1) (absolute error of e and 1 - e^2, relative of w_m*); "
                         f"got {tol!r}")
    V_max = real_scalar(V_max, "--V-max")
    Vc = impact.V_c
    lim = v1_star_limit(impact.eps_y, impact.nu) * Vc
    if not (V_max > 0 and V_max <= lim * (1 + 1e-12)):
        raise ValueError(f"--V-max = {V_max!r} m/s is outside (0, {lim:.6g}] m/s: the model ends at "
                         f"w_m* = 425 for this pair (V_c = {Vc:.6g} m/s)")
    v_top = min(V_max / Vc, v1_star_limit(impact.eps_y, impact.nu))
    curves = _curves(impact.eps_y, impact.nu, v_top)
    knots = [0.0, v_top] + [x for x in (1.0,) + JUMP if x < v_top]
    v = place_rows(lambda x: _values(curves, x), knots, tol, MAX_ROWS)
    vals = _direct(v, impact.eps_y, impact.nu)
    # measure: linear interpolation of the exact row values against the exact solver in between
    t = _interior(v[:-1], v[1:], CHECKS_PER_INTERVAL)
    ref = _direct(t.ravel(), impact.eps_y, impact.nu).reshape(-1, *t.shape)
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
                V_max=V_max, v1_star_max=v_top)


COLUMN_DOC = {
    "V_m_s": "impact speed V (m/s)", "V1_star": "V/V_c (-)",
    **{f"e_{m.name}": f"coefficient of restitution, {m.label} (-)" for m in _unloading.MODELS.values()},
    **{f"loss_{m.name}": f"1 - e^2, {m.label} (-)" for m in _unloading.MODELS.values()},
    "omega_m_m": "maximum interference w_m (m)", "omega_m_star": "w_m/omega_c (-)",
}


def _header(pair, res):
    prov = provenance()
    return {"fastrest_version": prov["fastrest_version"], "references": prov["references"],
            "source": "fastrest.direct (exact solver); rows placed with fastrest.curve",
            "pair": {k: v for k, v in pair.items() if v is not None}, "critical": res["critical"],
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


def write_velocity(out, pairs, tol, V_max=None):
    """Compute every pair's table, then write ``out``.csv (one pair) or ``out``_<name>.csv (several)
    and ``out``.json (all pairs); nothing is written unless every pair succeeds. Returns
    (list of (pair, result), list of paths)."""
    results = []
    for p in pairs:
        where = f"--pairs, pair {p.get('name')!r}: " if len(pairs) > 1 or p.get("name") else ""
        imp = impact_of(p, where)
        vm = p.get("V_max") if p.get("V_max") is not None else V_max
        if vm is None:
            raise ValueError(f"{where}--V-max is required (the largest impact speed, m/s)")
        try:
            results.append((p, velocity_table(imp, vm, tol)))
        except ValueError as exc:
            raise ValueError(f"{where}{exc}") from None
    base = str(out)
    for ext in (".csv", ".json"):
        if base.endswith(ext):
            base = base[: -len(ext)]
    files = {}
    if len(results) == 1:
        files[base + ".csv"] = csv_text(*results[0])
        doc = json_obj(*results[0])
    else:
        for p, r in results:
            files[f"{base}_{p['name']}.csv"] = csv_text(p, r)
        doc = {"pairs": {p["name"]: json_obj(p, r) for p, r in results}}
    files[base + ".json"] = json.dumps(doc, indent=1) + "\n"
    # every temporary file is written before any is renamed into place
    from contextlib import ExitStack
    with ExitStack() as stack:
        for path, text in files.items():
            tmp = stack.enter_context(atomic_path(path, "--out"))
            with open(tmp, "w", encoding="utf-8", newline="\n") as fh:
                fh.write(text)
    return results, list(files)
