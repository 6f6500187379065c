"""Conventions every comparison model shares: validated inputs in, a float or an array out."""
import numpy as np

from .._validation import broadcast_named, check_finite_result, check_velocity
from ..impact import Impact

__all__ = ["V_STAR_UNIT", "finite_out", "broadcast", "refuse_zero_speed", "check_v_star", "check_impact"]

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


def check_impact(impact):
    """TypeError unless ``impact`` is a :class:`fastrest.Impact`."""
    if not isinstance(impact, Impact):
        raise TypeError(f"impact must be a fastrest.Impact, got {type(impact).__name__}")
