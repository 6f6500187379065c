"""The batch functions of :mod:`fastrest.cuda`: one point (or contact) per GPU thread on device
arrays, through the :mod:`fastrest.jit` functions (re-exported by :mod:`fastrest.cuda`)."""
from typing import Any, Callable

from .. import jit as _frj
from ..force_law import StackedLaws
from ..curve_data import CurveData
from ..forward import ForwardData
from ..scene import SceneData
from ..tables import TableData
from .._deprecation import renamed
from .._doc import doc, fill, paragraphs
from ._device import _check_array, _check_code, _check_data, _check_out, _check_state, _launch

__all__ = ["omega_m_curve", "e_curve", "loss_curve", "omega_m_material", "e_material", "loss_material",
           "omega_m_table", "e_table", "loss_table", "contact_force", "contact_force_stacked"]

# The parameters v1_star, out and stream of the batch functions, written once (fastrest._doc; in the
# templates below, formatted first, ``{{name}}`` is such a paragraph).
_DOC = paragraphs(
    v1_star_points="""
        v1_star : device array
            1-D float64 normalised impact speeds V1/V_c (-).
        """,
    out_stream_points="""
        out : device array, optional
            1-D float64 of the length of ``v1_star``, written in place; allocated when not given.
        stream : numba.cuda stream, optional
            Stream of the launch (keyword-only; default the default stream). The call returns at once.
        """,
    out_stream="""
        out : device array, optional
            1-D float64 of length n, written in place; allocated when not given.
        stream : numba.cuda stream, optional
            Stream of the launch (keyword-only; default the default stream). The call returns at once.
        """,
)

# --- batch functions --------------------------------------------------------------------------

_CURVE_DOC = """{what} of one material at each V1* of a device array, on the GPU.

Parameters
----------
data : CurveData
    A curve's data on the device: ``fastrest.cuda.to_device(fastrest.curve(...))``.
{{v1_star_points}}
{{out_stream_points}}

Returns
-------
device array
    ``out``: {what} (-) per point, {unit}; NaN where :func:`fastrest.jit.{name}` gives NaN
    (V1* < 0, NaN or > the curve's ``v_max``), exactly as on the CPU.

Raises
------
TypeError
    ``data`` not a CurveData, or one with host arrays; ``v1_star`` or ``out`` a host array or not
    float64.
ValueError
    ``v1_star`` or ``out`` not 1-D, or of different lengths.

Notes
-----
One thread per point runs :func:`fastrest.jit.{name}` (JGM {eqs}), the CPU's code compiled for the
GPU: the same numbers bit for bit (bench/GPU.md).

Examples
--------
>>> import numpy as np, fastrest, fastrest.cuda
>>> d = fastrest.cuda.to_device(fastrest.curve(0.005, 0.33, v_max=100.0))
>>> v = fastrest.cuda.to_device(np.array([0.5, 10.0, 200.0]))
>>> fastrest.cuda.{name}(d, v).copy_to_host().round(6)
{example}
"""


def _curve_function(name: str, what: str, unit: str, eqs: str, example: str) -> Callable[..., Any]:
    def f(data: CurveData, v1_star: Any, out: Any = None, *, stream: Any = 0) -> Any:
        _check_data(data, CurveData, "data", "a CurveData")
        _check_array(v1_star, "v1_star")
        n = v1_star.shape[0]
        out = _check_out(out, n, stream)
        _launch(name, "point", n, stream, data, v1_star, out)
        return out

    f.__name__ = f.__qualname__ = name
    f.__doc__ = fill(_CURVE_DOC.format(what=what, name=name, unit=unit, eqs=eqs, example=example), _DOC)
    return f


omega_m_curve = _curve_function("omega_m_curve", "Normalised maximum interference w_m*", "omega_m/omega_c",
                                "eq (29)", "array([0.574349, 6.549856,      nan])")
e_curve = _curve_function("e_curve", "Coefficient of restitution e", "rebound over impact speed",
                          "eqs (16), (38)", "array([1.      , 0.828733,      nan])")
loss_curve = _curve_function("loss_curve", "Dissipated fraction 1 - e^2", "of the impact energy",
                             "eq (38)", "array([0.      , 0.313202,      nan])")


_MATERIAL_DOC = """{what} of each point's material of a scene at its V1*, on the GPU.

Parameters
----------
scene : SceneData
    A scene's data on the device: ``fastrest.cuda.to_device(fastrest.scene(...))``.
{{v1_star_points}}
material : device array
    1-D integer (any integer dtype) material index of each point into the scene, of the length of
    ``v1_star``.
{{out_stream_points}}

Returns
-------
device array
    ``out``: {what} (-) per point; NaN where :func:`fastrest.jit.{name}` gives NaN (an index
    outside the scene, V1* < 0, NaN or past the material's ``v_max``), exactly as on the CPU.

Raises
------
TypeError
    ``scene`` not a SceneData, or one with host arrays; an array on the host, ``v1_star`` or
    ``out`` not float64, ``material`` not integer.
ValueError
    An array not 1-D, or lengths that differ.

Notes
-----
One thread per point runs :func:`fastrest.jit.{name}` (JGM {eqs}), the CPU's code.

Examples
--------
>>> import numpy as np, fastrest, fastrest.cuda
>>> sc = fastrest.cuda.to_device(fastrest.scene([(0.005, 0.33), (0.001, 0.25)], v_max=300.0))
>>> v = fastrest.cuda.to_device(np.array([10.0, 300.0, 10.0]))
>>> k = fastrest.cuda.to_device(np.array([0, 1, 2]))
>>> fastrest.cuda.{name}(sc, v, k).copy_to_host().round(6)
{example}
"""


def _material_function(name: str, what: str, eqs: str, example: str) -> Callable[..., Any]:
    def f(scene: SceneData, v1_star: Any, material: Any, out: Any = None, *, stream: Any = 0) -> Any:
        _check_data(scene, SceneData, "scene", "a SceneData")
        _check_array(v1_star, "v1_star")
        n = v1_star.shape[0]
        _check_array(material, "material", "i", 1, n)
        out = _check_out(out, n, stream)
        _launch(name, "material", n, stream, scene, v1_star, material, out)
        return out

    f.__name__ = f.__qualname__ = name
    f.__doc__ = fill(_MATERIAL_DOC.format(what=what, name=name, eqs=eqs, example=example), _DOC)
    return f


omega_m_material = _material_function("omega_m_material", "Normalised maximum interference w_m*", "eq (29)",
                                      "array([  6.549856, 126.263984,        nan])")
e_material = _material_function("e_material", "Coefficient of restitution e", "eqs (16), (38)",
                                "array([0.828733, 0.405336,      nan])")
loss_material = _material_function("loss_material", "Dissipated fraction 1 - e^2", "eq (38)",
                                   "array([0.313202, 0.835703,      nan])")


_TABLE_DOC = """{what} at each point's (V1*, eps_y, nu) from a table, on the GPU.

Parameters
----------
tab : TableData
    A table's data on the device: ``fastrest.cuda.to_device(fastrest.load_table())``.
{{v1_star_points}}
eps_y, nu : device array
    1-D float64 Sy/E' (-) and Poisson's ratio (-) of each point, of the length of ``v1_star``.
{{unloading_param}}
{{out_stream_points}}

Returns
-------
device array
    ``out``: {what} (-) per point; NaN where :func:`fastrest.jit.{name}` gives NaN (negative or NaN
    speed, a material outside the table, a point past w_m* = 425 or a/R = 1{nan_model}), exactly as
    on the CPU.

Raises
------
TypeError
    ``tab`` not a TableData, or one with host arrays; an array on the host or not float64{bad_model}.
ValueError
    An array not 1-D, or lengths that differ.

Notes
-----
One thread per point runs :func:`fastrest.jit.{name}` (JGM {eqs}), the CPU's code; it needs the
table kernels to compile for CUDA (docs/gpu.md).

Examples
--------
>>> import numpy as np, fastrest, fastrest.cuda
>>> tab = fastrest.cuda.to_device(fastrest.load_table())
>>> v, eps_y, nu = (fastrest.cuda.to_device(np.array(x)) for x in ([10.0, 10.0], [0.005, 0.05], [0.33, 0.33]))
>>> fastrest.cuda.{name}(tab, v, eps_y, nu{call}).copy_to_host().round(6)
{example}
"""

_MODEL_PARAM = """unloading : int, optional
    Unloading model code of every point: :data:`fastrest.jit.JCG` (eq 35, the default),
    :data:`~fastrest.jit.ETSION` (eqs 33-34) or :data:`~fastrest.jit.BRAKE`.
"""


def _table_function(name: str, what: str, eqs: str, example: str, with_model: bool) -> Callable[..., Any]:
    def check(tab, v1_star, eps_y, nu):
        _check_data(tab, TableData, "tab", "a TableData")
        _check_array(v1_star, "v1_star")
        n = v1_star.shape[0]
        _check_array(eps_y, "eps_y", "f", 1, n)
        _check_array(nu, "nu", "f", 1, n)
        return n

    if with_model:
        def f(tab: TableData, v1_star: Any, eps_y: Any, nu: Any, unloading: int = _frj.JCG, out: Any = None, *,
              stream: Any = 0) -> Any:
            n = check(tab, v1_star, eps_y, nu)
            code = _check_code(unloading)
            out = _check_out(out, n, stream)
            _launch(name, "table_model", n, stream, tab, v1_star, eps_y, nu, code, out)
            return out
    else:
        def f(tab: TableData, v1_star: Any, eps_y: Any, nu: Any, out: Any = None, *,  # type: ignore[misc]
              stream: Any = 0) -> Any:
            n = check(tab, v1_star, eps_y, nu)
            out = _check_out(out, n, stream)
            _launch(name, "table", n, stream, tab, v1_star, eps_y, nu, out)
            return out

    f.__name__ = f.__qualname__ = name
    f.__doc__ = fill(_TABLE_DOC.format(
        what=what, name=name, eqs=eqs, example=example,
        nan_model=", or a model the table does not hold" if with_model else "",
        bad_model="; ``unloading`` not an integer" if with_model else "",
        call=", fastrest.jit.JCG" if with_model else ""), _DOC, unloading_param=_MODEL_PARAM if with_model else "")
    return f


omega_m_table = _table_function("omega_m_table", "Normalised maximum interference w_m*", "eq (29)",
                                "array([6.549856,      nan])", False)
e_table = _table_function("e_table", "Coefficient of restitution e", "eqs (16), (38)",
                          "array([0.828733,      nan])", True)
loss_table = _table_function("loss_table", "Dissipated fraction 1 - e^2", "eq (38)",
                             "array([0.313202,      nan])", True)


@renamed(law="data")
@doc(_DOC)
def contact_force(data: ForwardData, state: Any, w: Any, out: Any = None, *, stream: Any = 0) -> Any:
    """One time step of many contacts of one material: the normal force of each, with its history.

    Parameters
    ----------
    data : ForwardData
        A contact law's data on the device: ``fastrest.cuda.to_device(fastrest.contact_law(...))``
        (normalised: w = omega/omega_c, P* = P/P_c). ``law=`` is a deprecated name of it.
    state : device array
        (n, :data:`fastrest.jit.STATE_SIZE`) float64 history, one row per contact (zeros for a
        virgin contact: :func:`new_state`); updated in place.
    w : device array
        1-D float64 interference of each contact at this step, omega/omega_c (-).
    {out_stream}

    Returns
    -------
    device array
        ``out``: P* = P/P_c (-) of each contact; NaN (and the row set to NaN) where
        :func:`fastrest.jit.contact_force` gives NaN (w NaN or infinite, past the law's ``w_max``).

    Raises
    ------
    TypeError
        ``data`` not a contact law's data (ForwardData), or one with host arrays; an array on the
        host or not float64.
    ValueError
        ``w`` or ``out`` not 1-D, lengths that differ, or ``state`` not (n, STATE_SIZE).

    Notes
    -----
    One thread per contact runs :func:`fastrest.jit.contact_force` (JGM eqs 9, 14 loading, 32 with
    the unloading model's residual): loading bit for bit as on the CPU; unloading through
    libdevice's ``pow``, within ~1e-9 relative of the CPU's libm (bench/GPU.md measures it). In a
    DEM code, call :func:`fastrest.jit.contact_force` inside your own step kernel instead
    (docs/examples/dem_gpu.py): one launch per step for the force alone moves the state twice.

    Examples
    --------
    >>> import numpy as np, fastrest, fastrest.cuda
    >>> data = fastrest.cuda.to_device(fastrest.contact_law(0.005, 0.33, w_max=30.0))
    >>> state = fastrest.cuda.new_state(2)
    >>> fastrest.cuda.contact_force(data, state, fastrest.cuda.to_device(np.array([10.0, -1.0]))).copy_to_host().round(6)
    array([25.647583,  0.      ])
    >>> fastrest.cuda.contact_force(data, state, fastrest.cuda.to_device(np.array([5.0, 0.5]))).copy_to_host().round(6)
    array([2.401153, 0.353553])
    """
    _check_data(data, ForwardData, "data", "a contact law's data (ForwardData)")
    _check_array(w, "w")
    n = w.shape[0]
    _check_state(state, n)
    out = _check_out(out, n, stream)
    _launch("contact_force", "contact", n, stream, data, state, w, out)
    return out


@doc(_DOC)
def contact_force_stacked(laws: StackedLaws, material: Any, state: Any, w: Any, out: Any = None, *,
                          stream: Any = 0) -> Any:
    """One time step of many contacts of several materials (:func:`contact_force` per material).

    Parameters
    ----------
    laws : StackedLaws
        Stacked laws on the device: ``fastrest.cuda.to_device(fastrest.force_law.stack_laws([...]))``.
    material : device array
        1-D integer material index of each contact into ``laws``.
    state : device array
        (n, :data:`fastrest.jit.STATE_SIZE`) float64 history, one row per contact; updated in place.
    w : device array
        1-D float64 interference of each contact, omega/omega_c of its material's law (-).
    {out_stream}

    Returns
    -------
    device array
        ``out``: P* (-) of each contact; NaN (and the row NaN) where
        :func:`fastrest.jit.contact_force_stacked` gives NaN (also a material outside ``laws``).

    Raises
    ------
    TypeError
        ``laws`` not a StackedLaws, or one with host arrays; an array on the host, ``w``/``out``
        not float64 or ``material`` not integer.
    ValueError
        Arrays not 1-D, lengths that differ, or ``state`` not (n, STATE_SIZE).

    Notes
    -----
    One thread per contact runs :func:`fastrest.jit.contact_force_stacked` (see
    :func:`contact_force`).

    Examples
    --------
    >>> import numpy as np, fastrest, fastrest.cuda
    >>> from fastrest.force_law import stack_laws
    >>> laws = fastrest.cuda.to_device(stack_laws([fastrest.contact_law(0.005, 0.33), fastrest.contact_law(0.002, 0.3)]))
    >>> k = fastrest.cuda.to_device(np.array([0, 1]))
    >>> w = fastrest.cuda.to_device(np.array([10.0, 10.0]))
    >>> fastrest.cuda.contact_force_stacked(laws, k, fastrest.cuda.new_state(2), w).copy_to_host().round(6)
    array([25.647583, 25.880413])
    """
    _check_data(laws, StackedLaws, "laws", "a StackedLaws (fastrest.force_law.stack_laws)")
    _check_array(w, "w")
    n = w.shape[0]
    _check_array(material, "material", "i", 1, n)
    _check_state(state, n)
    out = _check_out(out, n, stream)
    _launch("contact_force_stacked", "stacked", n, stream, laws, material, state, w, out)
    return out


