"""Unloading models: each one unit, registered here by name; every consumer asks the registry.

A model is a module of this package with

* ``NAME``, ``SHORT``, ``LABEL``, ``EQUATION``, ``REFERENCE``: its public name and citation;
* ``OMEGA_END``: the w_m* where the model itself ends (``inf`` if it does not), and ``CELLS_END``:
  how far curves may tabulate it (short of an end where e behaves like a square root);
* ``residual(wm, wm1, p, eps_y, nu, law, et_ratio) -> (w_res*, delta)``: the residual
  interference after loading to w_m* = wm (wm1 = w_m* - 1 computed without cancellation,
  p = P_m*) under loading law ``law`` (:mod:`fastrest.loading`), delta = w_m* - w_res*;
* ``restitution(f, wm, wm1, p, eps_y, nu, law, et_ratio) -> (e^2, 1 - e^2, w_res*, delta, R_res/R)``
  for an impact of loading energy f = F(w_m*) = V1*^2 past the elastic limit (w_m* > 1);

all ``@jit(inline=True)`` scalar kernels. Unloading and reloading below w_m* follow eq (32) through
(w_m*, P_m*) and w_res* (:mod:`fastrest.unloading.elastic`), the same for every model here.

To add a model: write its module and list it in :data:`_UNITS` and in the three dispatchers
below (its code is its position). Python code names a model by string (``unloading="jcg"``) and
gets its :class:`UnloadingModel` from :func:`get`; jitted code passes the integer ``code``, and an
unknown code gives NaN.
"""
from __future__ import annotations

from typing import Any
import math
from dataclasses import dataclass

import numpy as np

from .._jit import jit
from .._validation import ValidityWarning, warn
from ..loading import p_star_unchecked, valid as law_valid
from . import brake, elastic, etsion, jcg

__all__ = ["UnloadingModel", "MODELS", "NAMES", "JCG", "ETSION", "BRAKE", "get"]

_UNITS = (jcg, etsion, brake)
# Integer codes of the unloading models for jitted code: a model's code is its position in _UNITS.
#: Code of the Jackson-Chusoipin-Green unloading model (JGM eq 35) in jitted code (``unloading=JCG``).
JCG = 0
#: Code of Etsion et al.'s unloading model (JGM eqs 33-34) in jitted code (``unloading=ETSION``).
ETSION = 1
#: Code of Brake's (2015) unloading model in jitted code (``unloading=BRAKE``).
BRAKE = 2
N_MODELS = len(_UNITS)


@dataclass(frozen=True)
class UnloadingModel:
    """An unloading model as Python code sees it (the kernels live in its module).

    Built once per registered unit (:data:`MODELS`); get one with :func:`get`. Frozen; pickles.

    Parameters
    ----------
    name : str
        Public name (``unloading=`` argument).
    short : str
        Display name (``JCG``, ``Etsion``, ...).
    code : int
        Integer passed to jitted kernels (``fastrest.jit.JCG`` etc.).
    label, equation, reference : str
        What it is, its equation (short, for messages) and where it comes from.
    omega_end : float
        w_m* at which the model ends (``inf`` if never): past it e is undefined.
    cells_end : float
        Largest w_m* a curve tabulates (the cells cannot follow e near an end).
    fits_hardening : bool
        Whether the model is meant for strain-hardening materials (Brake); the others were fitted
        to elastic-perfectly plastic finite elements and warn (ValidityWarning) when Et/E > 0.

    Notes
    -----
    ``"jcg"``: Jackson, Chusoipin & Green (2005) fit, JGM eq (35), ends at w_m* = 10017.5;
    ``"etsion"``: Etsion, Kligerman & Kadin (2005), JGM eqs (33)-(34); ``"brake"``: Brake (2015) as
    tmdsimpy implements it (docs/model.md section 11). The last two never end.

    Examples
    --------
    >>> from fastrest import unloading
    >>> m = unloading.get("jcg")
    >>> m.code, m.short, m.equation, round(m.omega_end, 4)
    (0, 'JCG', 'eq 35', 10017.5236)
    """

    name: str
    short: str
    code: int
    label: str
    equation: str
    reference: str
    omega_end: float
    cells_end: float
    fits_hardening: bool = False


#: The registered models by name, in code order: {"jcg": UnloadingModel(...), "etsion": ..., ...}.
MODELS = {u.NAME: UnloadingModel(u.NAME, u.SHORT, k, u.LABEL, u.EQUATION, u.REFERENCE, float(u.OMEGA_END),
                                  float(u.CELLS_END), bool(u.FITS_HARDENING))
          for k, u in enumerate(_UNITS)}
#: Names of the unloading models (``"jcg"``, ``"etsion"``, ``"brake"``), in code order.
NAMES = tuple(MODELS)


def get(unloading: str | UnloadingModel) -> UnloadingModel:
    """The registered :class:`UnloadingModel` called ``unloading``.

    Parameters
    ----------
    unloading : str or UnloadingModel
        A model name, one of :data:`NAMES` (``"jcg"``, ``"etsion"``, ``"brake"``), or a model
        (returned as registered).

    Returns
    -------
    UnloadingModel

    Raises
    ------
    ValueError
        Anything else, including an integer code (the message lists the names).

    Notes
    -----
    Every API taking ``unloading=`` asks here; JGM eq (35) is ``"jcg"``, eqs (33)-(34)
    ``"etsion"``, Brake (2015) ``"brake"``.

    Examples
    --------
    >>> from fastrest import unloading
    >>> unloading.get("etsion").code == unloading.ETSION
    True
    >>> unloading.get("hertz")
    Traceback (most recent call last):
        ...
    ValueError: unloading must be one of ('jcg', 'etsion', 'brake'); got 'hertz'
    """
    if isinstance(unloading, UnloadingModel):
        return MODELS[unloading.name]
    if isinstance(unloading, str) and unloading in MODELS:
        return MODELS[unloading]
    raise ValueError(f"unloading must be one of {NAMES}; got {unloading!r}")


def warn_if_unfitted(model, et_ratio):
    """ValidityWarning where a model fitted to elastic-perfectly plastic finite elements (JCG, Etsion)
    unloads a hardening material (any Et/E > 0): it is used as it stands, an extrapolation; Brake's,
    the peers' pairing with Ghaednia et al. (2019), is not warned about."""
    if not get(model).fits_hardening and np.any(np.asarray(et_ratio) > 0.0):
        warn(f"{get(model).short} unloading was fitted to elastic-perfectly plastic finite elements; with "
             f"strain hardening (Et/E > 0) it is an extrapolation (unloading='brake' is the pairing the "
             f"hardening law's peers use)", ValidityWarning)


def unloading_code(unloading):
    """The kernels' integer code of the model called ``unloading`` (ValueError if unknown)."""
    return get(unloading).code


# --- the dispatchers: the one place that maps a code to its unit ----------------------------------

@jit(inline=True)
def residual(code, wm, wm1, p, eps_y, nu, law, et_ratio):
    """(w_res*, delta = w_m* - w_res*) of model ``code`` after loading to (wm, p); NaNs if unknown."""
    if code == JCG:
        return jcg.residual(wm, wm1, p, eps_y, nu, law, et_ratio)
    if code == ETSION:
        return etsion.residual(wm, wm1, p, eps_y, nu, law, et_ratio)
    if code == BRAKE:
        return brake.residual(wm, wm1, p, eps_y, nu, law, et_ratio)
    return np.nan, np.nan


@jit(inline=True)
def restitution(code, f, wm, wm1, p, eps_y, nu, law, et_ratio):
    """(e^2, 1 - e^2, w_res*, delta, R_res/R) of model ``code`` (w_m* > 1); NaNs if unknown."""
    if code == JCG:
        return jcg.restitution(f, wm, wm1, p, eps_y, nu, law, et_ratio)
    if code == ETSION:
        return etsion.restitution(f, wm, wm1, p, eps_y, nu, law, et_ratio)
    if code == BRAKE:
        return brake.restitution(f, wm, wm1, p, eps_y, nu, law, et_ratio)
    return np.nan, np.nan, np.nan, np.nan, np.nan


@jit
def omega_end(code):
    """w_m* where model ``code`` ends (inf if never); NaN for an unknown code."""
    if code == JCG:
        return jcg.OMEGA_END
    if code == ETSION:
        return etsion.OMEGA_END
    if code == BRAKE:
        return brake.OMEGA_END
    return np.nan


@jit
def restitution_kernel(v, wm, wm1, eps_y, nu, model, law, et_ratio):
    """(e, 1 - e^2, w_res*, R_res/R) at impact speed v = V1* with maximum interference wm.

    ``wm1`` is wm - 1 computed accurately by the caller; V1* <= 1 (wm1 <= 0) is elastic: e = 1.
    NaN in, or an unknown ``model`` code, gives NaN out.
    """
    if not (wm >= 0.0 and v >= 0.0):
        return np.nan, np.nan, np.nan, np.nan
    if wm1 <= 0.0:
        if not (model >= 0 and model < N_MODELS and law_valid(law, et_ratio)):
            return np.nan, np.nan, np.nan, np.nan
        return 1.0, 0.0, 0.0, 1.0
    p = p_star_unchecked(law, wm, eps_y, nu, et_ratio)
    e2, loss, w_res, _, r_res = restitution(model, v * v, wm, wm1, p, eps_y, nu, law, et_ratio)
    return math.sqrt(e2), loss, w_res, r_res
