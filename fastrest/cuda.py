"""fastrest on an NVIDIA GPU: data on the device, and batch functions for users who write no kernel.

Every :mod:`fastrest.jit` function that compiles for CUDA is called from a ``numba.cuda.jit``
kernel exactly as from ``numba.njit`` code (the same source; docs/gpu.md lists which compile).
This module adds what such code needs around them, and ready-made kernels:

* :func:`to_device` copies a curve's, scene's, table's or contact law's data (a namedtuple of
  arrays: :class:`~fastrest.jit.CurveData`, :class:`~fastrest.jit.SceneData`,
  :class:`~fastrest.jit.TableData`, ``ContactLaw.data``, :class:`~fastrest.jit.StackedLaws`) to
  the GPU once, as the same namedtuple of device arrays: pass it to your kernels (a namedtuple of
  host arrays would be copied again at every launch). :func:`new_state` allocates the history rows
  of many contacts on the device.
* :func:`e_curve`, :func:`e_material`, :func:`e_table` (and their ``omega_m_``/``loss_``
  variants) evaluate one point per GPU thread on device arrays; :func:`contact_force` and
  :func:`contact_force_stacked` advance many contacts by one time step, each with its own state
  row. Every point outside the data's domain gives NaN, exactly as the jit functions do on the CPU.

Needs numba-cuda (``pip install "fastrest[gpu]"``); ``import fastrest`` never does. Under Numba's
CUDA simulator (``NUMBA_ENABLE_CUDASIM=1``, no GPU) everything here runs, slowly, with the CPU's
numbers: there :func:`to_device` leaves the data's arrays in host memory (the simulator runs the
jit functions as compiled CPU code, which cannot read its simulated device arrays).

Arguments and their checks follow the jit functions' order (data, speed, material, model); arrays
must be 1-D device arrays of one length (float64; material indices any integer type), ``out``
float64 of that length (allocated when not given). A host (NumPy) array where a device array is
expected, a wrong dtype, shape or length raises TypeError or ValueError naming the argument.
"""
from typing import Any, Callable

import numpy as np

try:
    import numba_cuda  # type: ignore[import-not-found,unused-ignore]  # noqa: F401  (numba's own numba.cuda is deprecated)
    from numba import cuda as _cuda_module
    from numba import float64 as _f8
    from numba.cuda.core import config as _cuda_config  # type: ignore[import-not-found,unused-ignore]
except ImportError as err:  # pragma: no cover - exercised in a subprocess by tests/test_cuda.py
    raise ImportError('fastrest.cuda needs numba-cuda: pip install "fastrest[gpu]" '
                      f"(import failed: {err})") from err

from . import jit as _frj
from .curve_data import CurveData
from .force_law import STATE_SIZE, StackedLaws
from .forward import ForwardData
from .scene import SceneData
from .tables import TableData

cuda: Any = _cuda_module

__all__ = ["THREADS_PER_BLOCK", "SIMULATOR", "to_device", "new_state", "omega_m_curve", "e_curve", "loss_curve",
           "omega_m_material", "e_material", "loss_material", "omega_m_table", "e_table", "loss_table",
           "contact_force", "contact_force_stacked"]

#: Threads per block of this module's kernels (one point or contact per thread).
THREADS_PER_BLOCK = 256

#: True under Numba's CUDA simulator (``NUMBA_ENABLE_CUDASIM=1`` before numba.cuda was imported).
SIMULATOR = bool(_cuda_config.ENABLE_CUDASIM)

_DATA_TYPES = (CurveData, SceneData, TableData, ForwardData, StackedLaws)



class _SimulatedDeviceArray(np.ndarray):  # type: ignore[type-arg,unused-ignore]
    """A data array "on the device" under the simulator: host memory, marked as copied (used only there)."""


_is_device_array: Callable[[Any], bool]
if SIMULATOR:
    from numba.cuda.simulator.cudadrv.devicearray import is_cuda_ndarray as _is_device_array  # type: ignore[import-not-found,unused-ignore]
else:
    _is_device_array = cuda.is_cuda_array


# --- data on the device -----------------------------------------------------------------------

def to_device(obj: Any, *, stream: Any = 0) -> Any:
    """Copy fastrest data or an array to the GPU.

    Parameters
    ----------
    obj : namedtuple, object with ``.data``, or array_like
        A :class:`~fastrest.jit.CurveData`, :class:`~fastrest.jit.SceneData`,
        :class:`~fastrest.jit.TableData`, contact law data (``ContactLaw.data``, a
        :class:`fastrest.forward.ForwardData`) or :class:`~fastrest.jit.StackedLaws`; or a
        :class:`~fastrest.Curve`, :class:`~fastrest.Scene`, :class:`~fastrest.Table` or
        :class:`~fastrest.ContactLaw` (their ``.data`` is copied); or a NumPy array (speeds V1* (-),
        interferences w (-), material indices, a state array of :data:`fastrest.jit.STATE_SIZE`
        columns ...), copied C-contiguous with its dtype.
    stream : numba.cuda stream, optional
        Stream of the copies (keyword-only; default the default stream).

    Returns
    -------
    namedtuple or device array
        The same namedtuple type with every array field a device array (scalars unchanged): pass
        it to your ``numba.cuda.jit`` kernels and to this module's functions; or the device array.
        Under the simulator the namedtuple's arrays stay in host memory (module docstring).

    Raises
    ------
    TypeError
        ``obj`` is none of the above (the message names its type).

    Examples
    --------
    >>> import numpy as np, fastrest, fastrest.cuda
    >>> d = fastrest.cuda.to_device(fastrest.curve(0.005, 0.33, v_max=100.0))
    >>> type(d).__name__, d.model, d.v_max
    ('CurveData', 0, 100.0)
    >>> fastrest.cuda.to_device(np.array([1.0, 2.0])).copy_to_host()
    array([1., 2.])
    """
    if not isinstance(obj, tuple) and isinstance(getattr(obj, "data", None), _DATA_TYPES):
        obj = obj.data
    if isinstance(obj, _DATA_TYPES):
        return type(obj)(*[_field_to_device(x, stream) for x in obj])
    if isinstance(obj, np.ndarray) or (isinstance(obj, (list, tuple)) and not hasattr(obj, "_fields")):
        a = np.ascontiguousarray(obj)
        if a.dtype.kind not in "biuf":
            raise TypeError(f"to_device: expected a numeric array, got dtype {a.dtype}")
        return cuda.to_device(a, stream=stream)
    if _is_device_array(obj):
        return obj
    raise TypeError("to_device: expected CurveData, SceneData, TableData, ContactLaw data (ForwardData), "
                    f"StackedLaws, a Curve/Scene/Table/ContactLaw or a NumPy array; got {type(obj).__name__}")


def _field_to_device(x, stream):
    if not isinstance(x, np.ndarray):
        return x
    a = np.ascontiguousarray(x)
    if SIMULATOR:
        return a.copy().view(_SimulatedDeviceArray)
    return cuda.to_device(a, stream=stream)


def new_state(n: int, *, stream: Any = 0) -> Any:
    """History rows of ``n`` virgin contacts on the device, for :func:`contact_force`.

    Parameters
    ----------
    n : int
        Number of contacts, >= 0.
    stream : numba.cuda stream, optional
        Stream of the fill (keyword-only).

    Returns
    -------
    device array
        (n, :data:`fastrest.jit.STATE_SIZE`) float64 zeros. Zero a contact's row again when it
        separates for good (a new contact) or after its force was NaN (history lost).

    Raises
    ------
    TypeError
        ``n`` is not an integer.
    ValueError
        ``n`` < 0.

    Examples
    --------
    >>> import fastrest.cuda
    >>> fastrest.cuda.new_state(3).shape
    (3, 4)
    """
    if isinstance(n, (bool, np.bool_)) or not isinstance(n, (int, np.integer)):
        raise TypeError(f"n must be an integer number of contacts, got {type(n).__name__}")
    if n < 0:
        raise ValueError(f"n must be >= 0, got {n}")
    return cuda.to_device(np.zeros((int(n), STATE_SIZE)), stream=stream)


# --- argument checks --------------------------------------------------------------------------

def _check_data(data, types, name, what):
    if not isinstance(data, types):
        hint = " (its .data, moved with fastrest.cuda.to_device)" if hasattr(data, "data") else ""
        raise TypeError(f"{name} must be {what} on the device{hint}; got {type(data).__name__}")
    for field, x in zip(data._fields, data):
        host = isinstance(x, np.ndarray) and not (SIMULATOR and isinstance(x, _SimulatedDeviceArray))
        if host:
            raise TypeError(f"{name} holds host arrays ({name}.{field} is a NumPy array): move it to the GPU once "
                            f"with fastrest.cuda.to_device({name})")


def _check_array(x, name, kind="f", ndim=1, n=None):
    """A device array of dtype kind ``kind`` ('f': float64, 'i': any integer) and ``ndim``."""
    if not _is_device_array(x):
        if isinstance(x, np.ndarray):
            raise TypeError(f"{name} must be a device array, got a NumPy array in host memory: copy it with "
                            f"fastrest.cuda.to_device({name}) (or numba.cuda.to_device)")
        raise TypeError(f"{name} must be a device array (numba.cuda.to_device, fastrest.cuda.to_device), "
                        f"got {type(x).__name__}")
    dt = np.dtype(x.dtype)
    if kind == "f" and dt != np.float64:
        raise TypeError(f"{name} must be float64, got {dt}")
    if kind == "i" and (dt.kind not in "iu"):
        raise TypeError(f"{name} must hold integer material indices, got {dt}")
    if len(x.shape) != ndim:
        raise ValueError(f"{name} must be {ndim}-D, got shape {tuple(x.shape)}")
    if n is not None and x.shape[0] != n:
        raise ValueError(f"{name} must have length {n} (that of v1_star or w), got shape {tuple(x.shape)}")
    return x


def _check_out(out, n, stream):
    if out is None:
        return cuda.device_array(n, dtype=np.float64, stream=stream)
    return _check_array(out, "out", "f", 1, n)


def _check_state(state, n):
    _check_array(state, "state", "f", 2)
    if state.shape != (n, STATE_SIZE):
        raise ValueError(f"state must have shape ({n}, {STATE_SIZE}) (one row of STATE_SIZE per contact, "
                         f"fastrest.cuda.new_state), got {tuple(state.shape)}")


def _check_code(unloading):
    if isinstance(unloading, (bool, np.bool_)) or not isinstance(unloading, (int, np.integer)):
        raise TypeError(f"unloading must be an integer model code (fastrest.jit.JCG, ETSION, BRAKE), "
                        f"got {type(unloading).__name__}")
    return int(unloading)


# --- the kernels: one factory --------------------------------------------------------------------

_KERNELS: dict[tuple[str, str], Any] = {}


def _kernel_function(fn, shape):
    """The Python source of a kernel applying jit function ``fn`` once per thread.

    ``shape``: "point" out[i] = fn(data, v[i]); "material" fn(data, v[i], k[i]); "table"
    fn(data, v[i], a[i], b[i]); "table_model" fn(data, v[i], a[i], b[i], code) with one model
    code for all; "contact" out[i] = fn(data, state row i, w[i]) and "stacked" fn(data, k[i],
    state row i, w[i]) update the row (through a thread-local copy: a row of the device array
    passed to a jit function would not run under the simulator, and the copy sits in registers).
    """
    if shape == "point":
        def kernel(data, v, out):
            i = cuda.grid(1)
            if i < out.size:
                out[i] = fn(data, v[i])
    elif shape == "material":
        def kernel(data, v, k, out):  # type: ignore[misc]
            i = cuda.grid(1)
            if i < out.size:
                out[i] = fn(data, v[i], k[i])
    elif shape == "table":
        def kernel(data, v, a, b, out):  # type: ignore[misc]
            i = cuda.grid(1)
            if i < out.size:
                out[i] = fn(data, v[i], a[i], b[i])
    elif shape == "table_model":
        def kernel(data, v, a, b, code, out):  # type: ignore[misc]
            i = cuda.grid(1)
            if i < out.size:
                out[i] = fn(data, v[i], a[i], b[i], code)
    elif shape == "contact":
        def kernel(data, state, w, out):  # type: ignore[misc]
            i = cuda.grid(1)
            if i < out.size:
                row = cuda.local.array(STATE_SIZE, _f8)
                for j in range(STATE_SIZE):
                    row[j] = state[i, j]
                out[i] = fn(data, row, w[i])
                for j in range(STATE_SIZE):
                    state[i, j] = row[j]
    elif shape == "stacked":
        def kernel(data, k, state, w, out):  # type: ignore[misc]
            i = cuda.grid(1)
            if i < out.size:
                row = cuda.local.array(STATE_SIZE, _f8)
                for j in range(STATE_SIZE):
                    row[j] = state[i, j]
                out[i] = fn(data, k[i], row, w[i])
                for j in range(STATE_SIZE):
                    state[i, j] = row[j]
    else:
        raise ValueError(f"unknown kernel shape {shape!r}")
    kernel.__name__ = kernel.__qualname__ = f"fastrest_{fn.__name__}_{shape}"
    return kernel


def _launch(name, shape, n, stream, *args):
    """Launch the kernel of jit function ``fastrest.jit.<name>`` over ``n`` threads (compiled once)."""
    key = (name, shape)
    if key not in _KERNELS:
        _KERNELS[key] = cuda.jit(_kernel_function(getattr(_frj, name), shape))
    if n > 0:
        blocks = (n + THREADS_PER_BLOCK - 1) // THREADS_PER_BLOCK
        _KERNELS[key][blocks, THREADS_PER_BLOCK, stream](*args)


# --- batch functions --------------------------------------------------------------------------

_CURVE_DOC = """{what} of one material at each V1* of a device array, on the GPU.

Parameters
----------
data : CurveData
    A curve's data on the device: ``fastrest.cuda.to_device(fastrest.curve(...))``.
v1_star : device array
    1-D float64 normalised impact speeds V1/V_c (-).
out : device array, optional
    1-D float64 of the length of ``v1_star``, written in place; allocated when not given.
stream : numba.cuda stream, optional
    Stream of the launch (keyword-only; default the default stream). The call returns at once.

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
    f.__doc__ = _CURVE_DOC.format(what=what, name=name, unit=unit, eqs=eqs, example=example)
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
v1_star : device array
    1-D float64 normalised impact speeds V1/V_c (-).
material : device array
    1-D integer (any integer dtype) material index of each point into the scene, of the length of
    ``v1_star``.
out : device array, optional
    1-D float64 of the length of ``v1_star``, written in place; allocated when not given.
stream : numba.cuda stream, optional
    Stream of the launch (keyword-only). The call returns at once.

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
    f.__doc__ = _MATERIAL_DOC.format(what=what, name=name, eqs=eqs, example=example)
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
v1_star : device array
    1-D float64 normalised impact speeds V1/V_c (-).
eps_y, nu : device array
    1-D float64 Sy/E' (-) and Poisson's ratio (-) of each point, of the length of ``v1_star``.
{model}out : device array, optional
    1-D float64 of the length of ``v1_star``, written in place; allocated when not given.
stream : numba.cuda stream, optional
    Stream of the launch (keyword-only). The call returns at once.

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
    f.__doc__ = _TABLE_DOC.format(
        what=what, name=name, eqs=eqs, example=example, model=_MODEL_PARAM if with_model else "",
        nan_model=", or a model the table does not hold" if with_model else "",
        bad_model="; ``unloading`` not an integer" if with_model else "",
        call=", fastrest.jit.JCG" if with_model else "")
    return f


omega_m_table = _table_function("omega_m_table", "Normalised maximum interference w_m*", "eq (29)",
                                "array([6.549856,      nan])", False)
e_table = _table_function("e_table", "Coefficient of restitution e", "eqs (16), (38)",
                          "array([0.828733,      nan])", True)
loss_table = _table_function("loss_table", "Dissipated fraction 1 - e^2", "eq (38)",
                             "array([0.313202,      nan])", True)


def contact_force(law: ForwardData, state: Any, w: Any, out: Any = None, *, stream: Any = 0) -> Any:
    """One time step of many contacts of one material: the normal force of each, with its history.

    Parameters
    ----------
    law : ForwardData
        A contact law's data on the device: ``fastrest.cuda.to_device(fastrest.contact_law(...))``
        (normalised: w = omega/omega_c, P* = P/P_c).
    state : device array
        (n, :data:`fastrest.jit.STATE_SIZE`) float64 history, one row per contact (zeros for a
        virgin contact: :func:`new_state`); updated in place.
    w : device array
        1-D float64 interference of each contact at this step, omega/omega_c (-).
    out : device array, optional
        1-D float64 of length n, written in place; allocated when not given.
    stream : numba.cuda stream, optional
        Stream of the launch (keyword-only). The call returns at once.

    Returns
    -------
    device array
        ``out``: P* = P/P_c (-) of each contact; NaN (and the row set to NaN) where
        :func:`fastrest.jit.contact_force` gives NaN (w NaN or infinite, past the law's ``w_max``).

    Raises
    ------
    TypeError
        ``law`` not a contact law's data (ForwardData), or one with host arrays; an array on the
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
    >>> law = fastrest.cuda.to_device(fastrest.contact_law(0.005, 0.33, w_max=30.0))
    >>> state = fastrest.cuda.new_state(2)
    >>> fastrest.cuda.contact_force(law, state, fastrest.cuda.to_device(np.array([10.0, -1.0]))).copy_to_host().round(6)
    array([25.647583,  0.      ])
    >>> fastrest.cuda.contact_force(law, state, fastrest.cuda.to_device(np.array([5.0, 0.5]))).copy_to_host().round(6)
    array([2.401153, 0.353553])
    """
    _check_data(law, ForwardData, "law", "a contact law's data (ForwardData)")
    _check_array(w, "w")
    n = w.shape[0]
    _check_state(state, n)
    out = _check_out(out, n, stream)
    _launch("contact_force", "contact", n, stream, law, state, w, out)
    return out


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
    out : device array, optional
        1-D float64 of length n, written in place; allocated when not given.
    stream : numba.cuda stream, optional
        Stream of the launch (keyword-only). The call returns at once.

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
