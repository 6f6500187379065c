"""Functions to call from your own ``@numba.njit`` code (rough-surface, multi-asperity, DEM loops).

Build the data once in Python, pass it into your jitted function, and call these inside it::

    import numba, numpy as np, fastrest
    from fastrest import jit as frj

    data = fastrest.curve(0.005, 0.33, v_max=200.0).data     # CurveData (a namedtuple)

    @numba.njit(parallel=True)
    def dissipated(data, v1_star, energy):
        total = 0.0
        for i in numba.prange(v1_star.size):
            total += energy[i] * frj.loss_curve(data, v1_star[i])
        return total

All functions take V1* = V1/V_c (dimensionless) and return NaN for input outside the data's
domain (negative or NaN speed, V1* > v_max, material outside a table, a table's point past
w_m* = 425 or a/R = 1): check with ``x != x`` or
``np.isnan`` if your code can produce such input. Tables: ``fastrest.load_table().data``;
``unloading`` is :data:`JCG` (eq 35), :data:`ETSION` (eq 33) or :data:`BRAKE` (Brake 2015).

Time-stepping codes: :func:`contact_force` (``law.data`` of :func:`fastrest.contact_law`, a state
row of :data:`STATE_SIZE` per contact) gives the normal force with history, and
:func:`critical_scales` the critical values of a contact from the two bodies' properties (the
same code as :class:`fastrest.Impact`). See docs/examples/dem_wall.py.
"""
import numpy as np

from ._jit import jit
from .critical import CriticalScales, critical_scales
from .curve_data import CurveData, e_curve, loss_curve, omega_m_curve
from .scene import SceneData, scene_value
from .force_law import STATE_SIZE, contact_force, hertz_contact_time
from .tables import TableData, table_value
from .unloading import BRAKE, ETSION, JCG

# inline="always": inlined into the caller's loop, the table's arrays are not reference-counted
# per call (measured: e_table in a user loop 250-310 -> 130 ns per point, as the batch kernel).

__all__ = ["CurveData", "SceneData", "TableData", "omega_m_scene", "e_scene", "loss_scene", "JCG", "ETSION",
           "BRAKE", "omega_m_curve", "e_curve", "loss_curve", "omega_m_table", "e_table", "loss_table",
           "STATE_SIZE", "contact_force", "hertz_contact_time", "CriticalScales", "critical_scales"]


@jit(inline=True)
def omega_m_table(tab, v1_star, eps_y, nu):
    """w_m* at (V1*, eps_y, nu) from a table's :class:`TableData`; NaN outside its domain."""
    return table_value(tab, 0, v1_star, eps_y, nu)


@jit(inline=True)
def e_table(tab, v1_star, eps_y, nu, unloading):
    """e at (V1*, eps_y, nu); ``unloading`` = JCG, ETSION or BRAKE; NaN for a model the table
    does not hold, and outside the table."""
    if not unloading >= 0:
        return np.nan
    return table_value(tab, 1 + 2 * unloading, v1_star, eps_y, nu)


@jit(inline=True)
def loss_table(tab, v1_star, eps_y, nu, unloading):
    """1 - e^2 at (V1*, eps_y, nu); ``unloading`` = JCG, ETSION or BRAKE; NaN for a model the
    table does not hold, and outside the table."""
    if not unloading >= 0:
        return np.nan
    return table_value(tab, 2 + 2 * unloading, v1_star, eps_y, nu)


@jit(inline=True)
def omega_m_scene(scene, material, v1_star):
    """w_m* of material index ``material`` of a :class:`fastrest.curve.SceneData`; NaN outside."""
    return scene_value(scene, 0, material, v1_star)


@jit(inline=True)
def e_scene(scene, material, v1_star):
    """e of material index ``material`` of a scene at V1*; NaN outside its curve."""
    return scene_value(scene, 1, material, v1_star)


@jit(inline=True)
def loss_scene(scene, material, v1_star):
    """1 - e^2 of material index ``material`` of a scene at V1*; NaN outside its curve."""
    return scene_value(scene, 2, material, v1_star)
