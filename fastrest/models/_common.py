"""Conventions every comparison model shares: validated inputs in, a float or an array out."""
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from .._doc import paragraphs
from .._validation import broadcast_named, check_eps_y, check_finite_result, check_nu, check_velocity
from ..impact import Impact

__all__ = ["V_STAR_UNIT", "MODEL_DOC", "finite_out", "broadcast", "refuse_zero_speed", "check_v_star",
           "v_star_inputs", "check_impact"]

#: The docstring paragraphs the comparison models share (:func:`fastrest._doc.doc`): every model
#: returns e, refuses what is not real with TypeError, and most take V1* and eps_y.
MODEL_DOC = paragraphs(
    params_v1_eps_y="""
        Parameters
        ----------
        v1_star : float or array_like
            V1 / V_c, V_c of JGM eq (28); finite and >= 0 (dimensionless).
        eps_y : float or array_like
            Sy / E' (dimensionless), > 0.
        """,
    params_kernel="""
        Parameters
        ----------
        v1_star : float
            V1 / V_c, V_c of JGM eq (28) (dimensionless).
        eps_y : float
            Sy / E' (dimensionless).
        """,
    returns_kernel="""
        Returns
        -------
        float
            e (dimensionless); NaN unless v1_star is finite and >= 0 and eps_y finite and > 0
            (no validation, no warnings).
        """,
    returns="""
        Returns
        -------
        float or ndarray
            e (dimensionless).

        Raises
        ------
        """,
    returns_e="""
        {returns}
        TypeError
            An input is not real.
        """,
    returns_e_impact="""
        {returns}
        TypeError
            ``impact`` is not a :class:`fastrest.Impact`, or V1 is not real.
        """,
)

#: Unit text of v1_star in error messages.
V_STAR_UNIT = "(dimensionless, V1/V_c with V_c of JGM eq 28)"


def finite_out(a, *inputs):
    """A 0-d result becomes a Python float; arrays are returned as they are. A result that is not
    finite (the formula overflowed double precision) raises ValueError naming ``inputs``, (name,
    value) pairs, instead of being returned."""
    a = np.asarray(a, dtype=np.float64)
    check_finite_result(a, "e", inputs)
    return float(a) if a.ndim == 0 else a


def broadcast(*named):
    """np.broadcast_arrays of (array, name) pairs, with a ValueError naming the parameters whose
    shapes differ."""
    broadcast_named(*named)
    return np.broadcast_arrays(*(a for a, _ in named))


def refuse_zero_speed(V1, name, eq):
    """Power laws in 1/V1 are infinite at V1 = 0: refuse it (ValueError) rather than return inf."""
    if np.any(V1 == 0.0):
        raise ValueError(f"{name} must be > 0 for {eq}: the formula is infinite at {name} = 0 "
                         "(it has no elastic range of its own; see the docstring)")


def check_v_star(v1_star):
    """v1_star as a float array, finite and >= 0 (TypeError / ValueError naming it)."""
    return check_velocity(v1_star, "v1_star", V_STAR_UNIT)


_MATERIAL_CHECKS: dict[str, Callable[[object], NDArray[np.float64]]] = {"eps_y": check_eps_y, "nu": check_nu}


def v_star_inputs(v1_star, **material):
    """v1_star and the material parameters ``material`` (``eps_y=``, ``nu=``), each checked in that
    order (TypeError / ValueError naming it), as float arrays broadcast together."""
    return broadcast((check_v_star(v1_star), "v1_star"), *((_MATERIAL_CHECKS[k](x), k) for k, x in material.items()))


def check_impact(impact):
    """TypeError unless ``impact`` is a :class:`fastrest.Impact`."""
    if not isinstance(impact, Impact):
        raise TypeError(f"impact must be a fastrest.Impact, got {type(impact).__name__}")
