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

All functions take V1* = V1/V_c (dimensionless); every scalar argument may be a float64, float32
or an integer (converted to float64; model codes and material indices may be integer-valued
floats). They return NaN for input outside the data's domain (negative or NaN speed, V1* > v_max,
material outside a table, a table's point past w_m* = 425 or a/R = 1, a result that would not be
finite) and never raise: check with ``x != x`` or ``np.isnan`` if your code can produce such
input. Tables: ``fastrest.load_table().data``;
``unloading`` is :data:`JCG` (eq 35), :data:`ETSION` (eq 33) or :data:`BRAKE` (Brake 2015).

Build the data in Python and pass it in as an argument (as above): the table kernels read a
TableData's arrays through data pointers, which needs the arrays alive for the whole call. These
functions are inlined into your code; with ``@numba.njit(cache=True)`` your cached function keeps
the fastrest code it was compiled with until its own file changes (Numba's cache checks only that
file): clear your ``__pycache__/*.nbi``/``*.nbc`` (or set ``NUMBA_CACHE_DIR``) after updating fastrest.

Time-stepping codes: :func:`contact_force` (``law.data`` of :func:`fastrest.contact_law`, a state
row of :data:`STATE_SIZE` per contact) gives the normal force with history, and
:func:`critical_scales` the critical values of a contact from the two bodies' properties (the
same code as :class:`fastrest.Impact`). See docs/examples/dem_wall.py.
"""
import numpy as np

from ._jit import jit
from .critical import CriticalScales, critical_scales
from .curve_data import CurveData, e_curve, loss_curve, omega_m_curve
from .scene import SceneData, material_index, scene_value
from .force_law import STATE_SIZE, contact_force, hertz_contact_time
from .tables import TableData, table_value
from .unloading import BRAKE, ETSION, JCG

# inline="always": inlined into the caller's loop; the table kernel reads the table's arrays through
# data pointers, so nothing is reference-counted per call (`python -m bench.stencil`).

__all__ = ["CurveData", "SceneData", "TableData", "omega_m_scene", "e_scene", "loss_scene", "JCG", "ETSION",
           "BRAKE", "omega_m_curve", "e_curve", "loss_curve", "omega_m_table", "e_table", "loss_table",
           "STATE_SIZE", "contact_force", "hertz_contact_time", "CriticalScales", "critical_scales"]


@jit(inline=True)
def omega_m_table(tab, v1_star, eps_y, nu):
    """Normalised maximum interference w_m* at (V1*, eps_y, nu) from a table (-).

    Parameters
    ----------
    tab : TableData
        A table's data, ``fastrest.load_table().data`` (:class:`fastrest.Table`).
    v1_star : float
        Normalised impact speed V1/V_c (-), >= 0.
    eps_y : float
        Sy/E' (-), inside the table's eps_y range (the shipped table: 0.0005-0.01).
    nu : float
        Poisson's ratio (-), inside the table's nu range (the shipped table: 0.2-0.45).

    Returns
    -------
    float
        w_m* (-); NaN outside the table's domain (negative or NaN speed, material outside its
        grid, a point past w_m* = 425 or a/R = 1): a jit kernel, it never raises.

    Notes
    -----
    Interpolates the exact solution of JGM eq (29) (:func:`fastrest.direct.omega_m_star`) stored
    in the table (docs/model.md section 7). Inlined into the calling jitted loop.

    Examples
    --------
    >>> import fastrest
    >>> from fastrest import jit as frj
    >>> tab = fastrest.load_table().data
    >>> round(frj.omega_m_table(tab, 10.0, 0.005, 0.33), 6)  # direct: 6.549856
    6.549856
    >>> frj.omega_m_table(tab, 10.0, 0.05, 0.33)  # outside the table
    nan
    """
    return table_value(tab, 0, v1_star, eps_y, nu)


@jit(inline=True)
def e_table(tab, v1_star, eps_y, nu, unloading):
    """Coefficient of restitution e at (V1*, eps_y, nu) from a table (-).

    Parameters
    ----------
    tab : TableData
        A table's data, ``fastrest.load_table().data`` (:class:`fastrest.Table`).
    v1_star : float
        Normalised impact speed V1/V_c (-), >= 0.
    eps_y : float
        Sy/E' (-), inside the table's eps_y range (the shipped table: 0.0005-0.01).
    nu : float
        Poisson's ratio (-), inside the table's nu range (the shipped table: 0.2-0.45).
    unloading : int
        Unloading model code: :data:`JCG` (eq 35), :data:`ETSION` (eqs 33-34) or :data:`BRAKE`.

    Returns
    -------
    float
        e (-); NaN outside the table's domain (negative or NaN speed, material outside its
        grid, a point past w_m* = 425 or a/R = 1), or a model the table does not hold: a jit
        kernel, it never raises.

    Notes
    -----
    Interpolates the exact e of JGM eqs (16), (38) (:func:`fastrest.direct.e_star`) stored in the
    table. Inlined into the calling jitted loop.

    Examples
    --------
    >>> import fastrest
    >>> from fastrest import jit as frj
    >>> tab = fastrest.load_table().data
    >>> round(frj.e_table(tab, 10.0, 0.005, 0.33, frj.JCG), 6)  # direct: 0.828733
    0.828733
    >>> round(frj.e_table(tab, 10.0, 0.005, 0.33, frj.ETSION), 6)  # direct: 0.865202
    0.865202
    """
    code = material_index(unloading)  # int64; -1 for a fraction, a negative or non-finite code
    if code < 0:
        return np.nan
    return table_value(tab, 1 + 2 * code, v1_star, eps_y, nu)


@jit(inline=True)
def loss_table(tab, v1_star, eps_y, nu, unloading):
    """Dissipated fraction 1 - e^2 at (V1*, eps_y, nu) from a table (-).

    Parameters
    ----------
    tab : TableData
        A table's data, ``fastrest.load_table().data`` (:class:`fastrest.Table`).
    v1_star : float
        Normalised impact speed V1/V_c (-), >= 0.
    eps_y : float
        Sy/E' (-), inside the table's eps_y range (the shipped table: 0.0005-0.01).
    nu : float
        Poisson's ratio (-), inside the table's nu range (the shipped table: 0.2-0.45).
    unloading : int
        Unloading model code: :data:`JCG` (eq 35), :data:`ETSION` (eqs 33-34) or :data:`BRAKE`.

    Returns
    -------
    float
        1 - e^2 (-); NaN outside the table's domain (negative or NaN speed, material outside its
        grid, a point past w_m* = 425 or a/R = 1), or a model the table does not hold: a jit
        kernel, it never raises.

    Notes
    -----
    Interpolates :func:`fastrest.direct.loss_star` (JGM eqs 16, 38, computed without
    cancellation) stored in the table. Inlined into the calling jitted loop.

    Examples
    --------
    >>> import fastrest
    >>> from fastrest import jit as frj
    >>> tab = fastrest.load_table().data
    >>> round(frj.loss_table(tab, 10.0, 0.005, 0.33, frj.JCG), 6)  # direct: 0.313202
    0.313202
    """
    code = material_index(unloading)
    if code < 0:
        return np.nan
    return table_value(tab, 2 + 2 * code, v1_star, eps_y, nu)


@jit(inline=True)
def omega_m_scene(scene, material, v1_star):
    """Normalised maximum interference w_m* of one material of a scene at V1* (-).

    Parameters
    ----------
    scene : SceneData
        A scene's data, ``fastrest.scene(...).data`` (:class:`fastrest.Scene`).
    material : int
        Material index into the scene, 0 <= material < number of materials.
    v1_star : float
        Normalised impact speed V1/V_c (-), 0 <= v1_star <= the scene's v_max.

    Returns
    -------
    float
        w_m* (-); NaN for a material index out of range, a negative or NaN speed, or one above the
        scene's v_max (a jit kernel: it never raises).

    Notes
    -----
    Interpolates the exact solution of JGM eq (29) (:func:`fastrest.direct.omega_m_star`) on the
    material's curve cells (docs/model.md section 7). Inlined into the calling jitted loop.

    Examples
    --------
    >>> import fastrest
    >>> from fastrest import jit as frj
    >>> sc = fastrest.scene([(0.005, 0.33), (0.001, 0.25)], v_max=300.0).data
    >>> round(frj.omega_m_scene(sc, 0, 10.0), 6), round(frj.omega_m_scene(sc, 1, 300.0), 6)
    (6.549856, 126.263984)
    """
    return scene_value(scene, 0, material, v1_star)


@jit(inline=True)
def e_scene(scene, material, v1_star):
    """Coefficient of restitution e of one material of a scene at V1* (-).

    Parameters
    ----------
    scene : SceneData
        A scene's data, ``fastrest.scene(...).data`` (:class:`fastrest.Scene`).
    material : int
        Material index into the scene, 0 <= material < number of materials.
    v1_star : float
        Normalised impact speed V1/V_c (-), 0 <= v1_star <= the scene's v_max.

    Returns
    -------
    float
        e (-) with the scene's unloading model; NaN for a material index out of range, a
        negative or NaN speed, or one above the scene's v_max (a jit kernel: it never raises).

    Notes
    -----
    Interpolates the exact e of JGM eqs (16), (38) (:func:`fastrest.direct.e_star`) on the
    material's curve cells. Inlined into the calling jitted loop.

    Examples
    --------
    JGM check values (docs/model.md section 3):

    >>> import fastrest
    >>> from fastrest import jit as frj
    >>> sc = fastrest.scene([(0.005, 0.33), (0.001, 0.25)], v_max=300.0).data
    >>> round(frj.e_scene(sc, 0, 10.0), 9), round(frj.e_scene(sc, 1, 300.0), 9)
    (0.828732573, 0.405336002)
    >>> frj.e_scene(sc, 2, 10.0)  # no material 2
    nan
    """
    return scene_value(scene, 1, material, v1_star)


@jit(inline=True)
def loss_scene(scene, material, v1_star):
    """Dissipated fraction 1 - e^2 of one material of a scene at V1* (-).

    Parameters
    ----------
    scene : SceneData
        A scene's data, ``fastrest.scene(...).data`` (:class:`fastrest.Scene`).
    material : int
        Material index into the scene, 0 <= material < number of materials.
    v1_star : float
        Normalised impact speed V1/V_c (-), 0 <= v1_star <= the scene's v_max.

    Returns
    -------
    float
        1 - e^2 (-) with the scene's unloading model; NaN for a material index out of range, a
        negative or NaN speed, or one above the scene's v_max (a jit kernel: it never raises).

    Notes
    -----
    Interpolates :func:`fastrest.direct.loss_star` (JGM eqs 16, 38, without cancellation) on the
    material's curve cells. Inlined into the calling jitted loop.

    Examples
    --------
    >>> import fastrest
    >>> from fastrest import jit as frj
    >>> sc = fastrest.scene([(0.005, 0.33), (0.001, 0.25)], v_max=300.0).data
    >>> round(frj.loss_scene(sc, 0, 10.0), 6)
    0.313202
    """
    return scene_value(scene, 2, material, v1_star)
