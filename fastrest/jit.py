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

Arguments come in one order: the data, then the speed, then what picks the material (its eps_y
and nu, or its index in a scene), then the unloading model: ``e_table(tab, v1_star, eps_y, nu,
unloading)``, ``e_material(scene, v1_star, material)``, ``e_curve(data, v1_star)``, as in the
Python API (``Scene.e(v1_star, material)``). All functions take V1* = V1/V_c (dimensionless); every scalar argument may be a float64, float32
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
same code as :class:`fastrest.Impact`). Several materials in one loop (``numba.prange`` over
contacts of different materials): :func:`contact_force_stacked` with the :class:`StackedLaws` of
:func:`stack_laws` (a Python function, also ``fastrest.force_law.stack_laws``: call it before the
loop) and each contact's material index. See
docs/examples/dem_wall.py. The energy a contact has dissipated so far, from its state row:
:func:`dissipated_energy` (:func:`dissipated_energy_stacked`; docs/examples/dem_energy.py). Strain
hardening: a law built with ``et_ratio`` = Et/E > 0 loads along Ghaednia et al.'s (2019) law
(loading law codes :data:`JACKSON_GREEN`, :data:`GHAEDNIA`, in ``law.law``);
:func:`yield_et_ratio` gives Et/E of the body that yields first from the two bodies' properties.
"""
import numpy as np
from numba.extending import overload

from ._deprecation import warn_deprecated
from ._doc import doc, paragraphs
from ._jit import jit
from .critical import CriticalScales, critical_scales, yield_et_ratio
from .curve_data import CurveData, e_curve, loss_curve, omega_m_curve
from .scene import SceneData, material_index, scene_value
from .force_law import (STATE_SIZE, StackedLaws, contact_force, contact_force_stacked, dissipated_energy,
                        dissipated_energy_stacked, hertz_contact_time, stack_laws)
from .loading import GHAEDNIA, JACKSON_GREEN
from .tables import TableData, table_value
from .unloading import BRAKE, ETSION, JCG

# inline="always": inlined into the caller's loop; the table kernel reads the table's arrays through
# data pointers, so nothing is reference-counted per call (`python -m bench.stencil`).

__all__ = ["CurveData", "SceneData", "TableData", "omega_m_material", "e_material", "loss_material", "JCG", "ETSION",
           "BRAKE", "omega_m_curve", "e_curve", "loss_curve", "omega_m_table", "e_table", "loss_table",
           "STATE_SIZE", "contact_force", "hertz_contact_time", "CriticalScales", "critical_scales",
           "StackedLaws", "stack_laws", "contact_force_stacked", "dissipated_energy", "dissipated_energy_stacked", "yield_et_ratio",
           "JACKSON_GREEN", "GHAEDNIA"]

# The parameters and NaN rules of the table and scene kernels below, and their examples' first
# lines, written once (fastrest._doc).
_DOC = paragraphs(
    table_params="""
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
        """,
    table_params_unloading="""
        {table_params}
        unloading : int
            Unloading model code: :data:`JCG` (eq 35), :data:`ETSION` (eqs 33-34) or :data:`BRAKE`.
        """,
    table_nan="""
        NaN outside the table's domain (negative or NaN speed, material outside its grid, a point
        past w_m* = 425 or a/R = 1): a jit kernel, it never raises.
        """,
    table_nan_unloading="""
        NaN outside the table's domain (negative or NaN speed, material outside its grid, a point
        past w_m* = 425 or a/R = 1), or for a model the table does not hold: a jit kernel, it never
        raises.
        """,
    material_params="""
        Parameters
        ----------
        scene : SceneData
            A scene's data, ``fastrest.scene(...).data`` (:class:`fastrest.Scene`).
        v1_star : float
            Normalised impact speed V1/V_c (-), 0 <= v1_star <= the scene's v_max.
        material : int
            Material index into the scene, 0 <= material < number of materials.
        """,
    material_nan="""
        NaN for a material index out of range, a negative or NaN speed, or one above the scene's
        v_max (a jit kernel: it never raises).
        """,
    examples_table="""
        Examples
        --------
        >>> import fastrest
        >>> from fastrest import jit as frj
        >>> tab = fastrest.load_table().data
        """,
    examples_scene="""
        Examples
        --------
        >>> import fastrest
        >>> from fastrest import jit as frj
        >>> sc = fastrest.scene([(0.005, 0.33), (0.001, 0.25)], v_max=300.0).data
        """,
)


@jit(inline=True)
def _model_value(tab, first, v1_star, eps_y, nu, unloading):
    """Quantity ``first + 2 * code`` (e: 1, 1 - e^2: 2) of unloading model ``unloading`` from a table."""
    code = material_index(unloading)  # int64; -1 for a fraction, a negative or non-finite code
    if code < 0:
        return np.nan
    return table_value(tab, first + 2 * code, v1_star, eps_y, nu)


@jit(inline=True)
@doc(_DOC)
def omega_m_table(tab, v1_star, eps_y, nu):
    """Normalised maximum interference w_m* at (V1*, eps_y, nu) from a table (-).

    Interpolates the exact solution of JGM eq (29) (:func:`fastrest.direct.omega_m_exact`) stored
    in the table (docs/model.md section 7).

    {table_params}

    Returns
    -------
    float
        w_m* (-).
        {table_nan}

    {examples_table}
    >>> round(frj.omega_m_table(tab, 10.0, 0.005, 0.33), 6)  # direct: 6.549856
    6.549856
    >>> frj.omega_m_table(tab, 10.0, 0.05, 0.33)  # outside the table
    nan
    """
    return table_value(tab, 0, v1_star, eps_y, nu)


@jit(inline=True)
@doc(_DOC)
def e_table(tab, v1_star, eps_y, nu, unloading):
    """Coefficient of restitution e at (V1*, eps_y, nu) from a table (-).

    Interpolates the exact e of JGM eqs (16), (38) (:func:`fastrest.direct.e_exact`) stored in the
    table.

    {table_params_unloading}

    Returns
    -------
    float
        e (-).
        {table_nan_unloading}

    {examples_table}
    >>> round(frj.e_table(tab, 10.0, 0.005, 0.33, frj.JCG), 6)  # direct: 0.828733
    0.828733
    >>> round(frj.e_table(tab, 10.0, 0.005, 0.33, frj.ETSION), 6)  # direct: 0.865202
    0.865202
    """
    return _model_value(tab, 1, v1_star, eps_y, nu, unloading)


@jit(inline=True)
@doc(_DOC)
def loss_table(tab, v1_star, eps_y, nu, unloading):
    """Dissipated fraction 1 - e^2 at (V1*, eps_y, nu) from a table (-).

    Interpolates :func:`fastrest.direct.loss_exact` (JGM eqs 16, 38, computed without
    cancellation) stored in the table.

    {table_params_unloading}

    Returns
    -------
    float
        1 - e^2 (-).
        {table_nan_unloading}

    {examples_table}
    >>> round(frj.loss_table(tab, 10.0, 0.005, 0.33, frj.JCG), 6)  # direct: 0.313202
    0.313202
    """
    return _model_value(tab, 2, v1_star, eps_y, nu, unloading)


@jit(inline=True)
@doc(_DOC)
def omega_m_material(scene, v1_star, material):
    """Normalised maximum interference w_m* of one material of a scene at V1* (-).

    Interpolates the exact solution of JGM eq (29) (:func:`fastrest.direct.omega_m_exact`) on the
    material's curve cells (docs/model.md section 7).

    {material_params}

    Returns
    -------
    float
        w_m* (-).
        {material_nan}

    {examples_scene}
    >>> round(frj.omega_m_material(sc, 10.0, 0), 6), round(frj.omega_m_material(sc, 300.0, 1), 6)
    (6.549856, 126.263984)
    """
    return scene_value(scene, 0, material, v1_star)


@jit(inline=True)
@doc(_DOC)
def e_material(scene, v1_star, material):
    """Coefficient of restitution e of one material of a scene at V1* (-).

    Interpolates the exact e of JGM eqs (16), (38) (:func:`fastrest.direct.e_exact`) on the
    material's curve cells.

    {material_params}

    Returns
    -------
    float
        e (-) with the scene's unloading model.
        {material_nan}

    {examples_scene}
    >>> round(frj.e_material(sc, 10.0, 0), 9), round(frj.e_material(sc, 300.0, 1), 9)  # JGM check values
    (0.828732573, 0.405336002)
    >>> frj.e_material(sc, 10.0, 2)  # no material 2
    nan
    """
    return scene_value(scene, 1, material, v1_star)


@jit(inline=True)
@doc(_DOC)
def loss_material(scene, v1_star, material):
    """Dissipated fraction 1 - e^2 of one material of a scene at V1* (-).

    Interpolates :func:`fastrest.direct.loss_exact` (JGM eqs 16, 38, without cancellation) on the
    material's curve cells.

    {material_params}

    Returns
    -------
    float
        1 - e^2 (-) with the scene's unloading model.
        {material_nan}

    {examples_scene}
    >>> round(frj.loss_material(sc, 10.0, 0), 6)
    0.313202
    """
    return scene_value(scene, 2, material, v1_star)


# --- deprecated: the scene functions took (scene, material, v1_star) ------------------------------
# Every other function takes the data, then the speed, then the material (e_table(tab, v1_star,
# eps_y, nu, ...), Scene.e(v1_star, material)); the old names keep their old order for one release
# and warn when they are compiled (inside your jitted function: once per signature) or called from
# Python. Argument types cannot tell the two orders apart (both may be integers or floats), hence new
# names rather than a reordered old one.

def _deprecated_scene_function(what, old, new, kernel):
    def deprecated(scene, material, v1_star):
        warn_deprecated(f"fastrest.jit.{old}(scene, material, v1_star)",
                        f"fastrest.jit.{new}(scene, v1_star, material)")
        return kernel(scene, v1_star, material)

    @overload(deprecated, inline="always")
    def _compiled(scene, material, v1_star):
        # FutureWarning: raised while Numba compiles the user's function, where no user line can
        # be blamed, a DeprecationWarning would be hidden by Python's default filters
        warn_deprecated(f"fastrest.jit.{old}(scene, material, v1_star)",
                        f"fastrest.jit.{new}(scene, v1_star, material)", stacklevel=2, category=FutureWarning)

        def impl(scene, material, v1_star):
            return scene_value(scene, what, material, v1_star)

        return impl

    deprecated.__name__ = deprecated.__qualname__ = old
    deprecated.__doc__ = (f"Deprecated: :func:`{new}` with the arguments (scene, v1_star, material).")
    return deprecated


omega_m_scene = _deprecated_scene_function(0, "omega_m_scene", "omega_m_material", omega_m_material)
e_scene = _deprecated_scene_function(1, "e_scene", "e_material", e_material)
loss_scene = _deprecated_scene_function(2, "loss_scene", "loss_material", loss_material)
