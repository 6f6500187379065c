"""Impacts of many rough surfaces: here, or one Dask task per surface (:func:`sweep`)."""
from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from concurrent.futures import CancelledError
from typing import TYPE_CHECKING, Any
from numpy.typing import ArrayLike, NDArray

if TYPE_CHECKING:
    from .heights import GreenwoodWilliamson
import math
import time

import numba
import numpy as np

from .._validation import as_float_array, check_bool, check_finite_positive, warn
from ..materials import Material
from ..unloading import unloading_code
from .common import check_speeds
from .heights import gaussian_summits
from .result import RoughImpact
from .surface import RoughSurface

__all__ = ["sweep", "surface_from_params", "SweepResults", "worker_threads"]

#: What :func:`sweep` records for a surface it cannot build or evaluate (``on_error="report"``):
#: the errors of the model's domain and of its inputs. Anything else (MemoryError, a bug) raises.
SURFACE_ERRORS = (ValueError, TypeError, ArithmeticError)

#: Rounds of :func:`sweep` on a Dask cluster: surfaces whose task or data was lost with a worker
#: (a ``CancelledError``, or an ``OSError`` while scattering) are submitted again, with their arrays
#: scattered afresh, up to this many rounds in all (1, 2, 4 s apart).
SWEEP_ATTEMPTS = 4


class SweepResults(list[Any]):
    """The list of :class:`RoughImpact` that :func:`sweep` returns, with the surfaces it could not do.

    Parameters
    ----------
    results : iterable of RoughImpact
        One per surface, in the order of the sweep's ``surfaces``.
    errors : list of (int, Exception), optional
        The failed surfaces: (index into ``surfaces``, the exception its build or impact raised).

    Attributes
    ----------
    errors : list of (int, Exception)
        Empty when every surface succeeded. A failed surface's entry in the list is a
        RoughImpact of ``kind = "failed"`` whose results (e, loss, d_min, ...) are NaN.
    ok : ndarray of bool
        Per surface: True where it succeeded.

    Examples
    --------
    >>> import fastrest
    >>> from fastrest import rough
    >>> steel = fastrest.Material(E=200e9, nu=0.3, Sy=1e9)
    >>> specs = [dict(material=steel, R_a=1e-4, gw=dict(eta=1e10, sigma=20e-9, A_n=1e-4)),
    ...          dict(material=steel, R_a=-1.0, gw=dict(eta=1e10, sigma=20e-9, A_n=1e-4))]  # R_a < 0
    >>> out = rough.sweep(specs, 0.1, 0.01)
    >>> out.ok, out[1].kind, out[1].e
    (array([ True, False]), 'failed', nan)
    >>> out.errors[0][0], type(out.errors[0][1]).__name__
    (1, 'ValueError')
    """

    def __init__(self, results: Iterable[Any] = (), errors: Iterable[tuple[int, BaseException]] | None = None) -> None:
        super().__init__(results)
        self.errors = list(errors or [])

    @property
    def ok(self) -> NDArray[np.bool_]:
        bad = {i for i, _ in self.errors}
        return np.array([i not in bad for i in range(len(self))], dtype=bool)

    def __reduce__(self):
        return (SweepResults, (list(self), self.errors))


def _failed(v, m, unloading):
    """The RoughImpact of a surface that failed: NaN results of the shape of V1."""
    def nan():
        return math.nan if v.ndim == 0 else np.full(v.shape, math.nan)

    V1 = float(v) if v.ndim == 0 else v.copy()
    with np.errstate(over="ignore"):
        energy_in = 0.5 * m * np.square(v)   # inf past the largest double, as RoughSurface.impact refuses
    return RoughImpact(V1=V1, M=m, unloading=unloading, V1_star=nan(), e=nan(), loss=nan(), d_min=nan(),
                       force_max=nan(), n_contact=nan(), n_yielded=nan(), dissipated=nan(),
                       energy_in=energy_in if v.ndim else float(energy_in), w_star_max=nan(),
                       kind="failed")


def surface_from_params(material: Material | None = None, R_a: Any = None, heights: ArrayLike | None = None,
                        gw: GreenwoodWilliamson | dict[str, Any] | None = None, gaussian: Sequence[Any] | None = None, E: float | None = None,
                        nu: float | None = None, Sy: float | None = None, et_ratio: float | None = None,
                        loading: str | None = None, radii: ArrayLike | None = None) -> RoughSurface:
    """Build a :class:`RoughSurface` from plain parameters: the default factory of :func:`sweep`.

    Parameters
    ----------
    material : fastrest.Material, optional
        The summits' material; or give ``E``, ``nu``, ``Sy``.
    R_a : float
        Summit radius (m), > 0 (or ``radii``).
    heights : array_like, optional
        Explicit summit heights (m).
    radii : array_like, optional
        Each explicit summit's radius (m), instead of ``R_a`` (:class:`RoughSurface`).
    gw : GreenwoodWilliamson or dict, optional
        Statistical description.
    gaussian : (int, float) or (int, float, int), optional
        (n, sigma, seed): n heights of standard deviation sigma (m) drawn by
        :func:`gaussian_summits` where the task runs (nothing large is shipped).
    E, nu, Sy : float, optional
        Young's modulus (Pa), Poisson's ratio (-), yield strength (Pa), without ``material``.
    et_ratio : float, optional
        Strain hardening Et/E of the summits (-), 0 <= et_ratio < 1; default None: the
        material's own Et/E (0 without ``material``).
    loading : {None, "jackson-green", "ghaednia"}, optional
        The summits' loading law; None picks it from ``et_ratio`` (:class:`RoughSurface`).

    Returns
    -------
    RoughSurface

    Raises
    ------
    ValueError
        Neither ``material`` nor all of E, nu, Sy; both ``heights`` and ``gaussian``; or what
        :class:`RoughSurface` refuses (``et_ratio`` outside [0, 1) among them).

    Notes
    -----
    One of ``heights``, ``gw``, ``gaussian`` describes the surface (docs/rough.md sections 3-4).

    Examples
    --------
    >>> from fastrest import rough
    >>> s = rough.surface_from_params(E=200e9, nu=0.3, Sy=1e9, R_a=1e-4, gaussian=(100, 50e-9, 1))
    >>> s.kind, s.n_summits
    ('explicit', 100)
    >>> rough.surface_from_params(E=200e9, nu=0.3, Sy=1e9, R_a=1e-4, gaussian=(100, 50e-9, 1),
    ...                           et_ratio=0.02).law.name
    'ghaednia'
    """
    if material is None:
        if E is None or nu is None or Sy is None:
            raise ValueError("give material= or all of E, nu, Sy")
        material = Material(E=E, nu=nu, Sy=Sy)
    if gaussian is not None:
        if heights is not None:
            raise ValueError("give only one of heights= and gaussian=")
        heights = gaussian_summits(*gaussian)
    return RoughSurface(material, R_a, heights=heights, gw=gw, radii=radii, et_ratio=et_ratio, loading=loading)


def worker_threads() -> int | None:
    """Threads of the Dask worker running the calling task (its ``threads_per_worker``), or None
    outside a Dask worker (or without ``distributed``).

    Returns
    -------
    int or None
        The worker's thread count; :func:`sweep` runs each task's Numba kernels on that many.

    Examples
    --------
    >>> from fastrest.rough.sweeps import worker_threads
    >>> worker_threads() is None  # here, not in a Dask worker's task
    True
    """
    try:
        from distributed import get_worker
    except ImportError:
        return None
    try:
        worker = get_worker()
    except ValueError:  # not in a worker's task
        return None
    n = getattr(worker, "nthreads", None)
    if n is None:
        n = getattr(getattr(worker, "state", None), "nthreads", None)
    return int(n) if n else None


def _sweep_task(factory, params, array_keys, *args):
    """One parameter set (module-level, so Dask can ship it by reference); with ``report`` (the
    last argument) an error of :data:`SURFACE_ERRORS` is returned, not raised. In a Dask worker,
    Numba's kernels run on the worker's own threads (``threads_per_worker``), not on every core
    of the machine in every worker."""
    k = len(array_keys)
    params = dict(params)
    params.update(zip(array_keys, args[:k]))
    V1, M, unloading, extrapolate, report = args[k:]
    threads = worker_threads()
    before = numba.get_num_threads()
    if threads is not None:  # numba's setting is per calling thread: this task's only
        most = int(getattr(numba.config, "NUMBA_NUM_THREADS"))  # numba.config's names are set at run time
        numba.set_num_threads(max(1, min(threads, most)))
    try:
        surface = factory(**params)
        return surface.impact(V1, M, unloading, extrapolate=extrapolate)
    except SURFACE_ERRORS as exc:
        if not report:
            raise
        return exc
    finally:
        numba.set_num_threads(before)


def _rebuild_surface(material, R_a=None, heights=None, gw=None, et_ratio=None, loading=None, radii=None):
    """Factory for RoughSurface objects sent to Dask (their :meth:`RoughSurface.params`)."""
    return RoughSurface(material, R_a, heights=heights, gw=gw, radii=radii, et_ratio=et_ratio, loading=loading)


def sweep(surfaces: Iterable[Any], V1: ArrayLike, M: float, unloading: str = "jcg", *, extrapolate: bool = False,
          factory: Callable[..., RoughSurface] = surface_from_params, client: Any = None, scatter_min: int = 100_000,
          on_error: str = "report") -> SweepResults:
    """Impacts of many surfaces (or parameter sets) at the speeds ``V1``.

    Parameters
    ----------
    surfaces : sequence of RoughSurface or of dict
        Each dict holds keyword arguments of ``factory`` (default :func:`surface_from_params`:
        material or E/nu/Sy, R_a, and heights, gw or gaussian=(n, sigma, seed); optionally
        et_ratio and loading, the summits' strain hardening and loading law).
    V1 : float or array_like
        Impact speeds (m/s), > 0; the same for every surface.
    M : float or sequence of float
        Mass of the flat (kg), > 0: one value, or one per surface.
    unloading : {"jcg", "etsion", "brake"}
        Unloading model, as in :meth:`RoughSurface.impact`.
    extrapolate : bool
        As in :meth:`RoughSurface.impact`.
    factory : callable
        Module-level function building a RoughSurface from a dict (must pickle for Dask).
    client : dask.distributed.Client, optional
        Run one task per surface on this cluster. Arrays with at least ``scatter_min`` elements
        (explicit heights) and V1 are scattered once each (the same array object is shipped once
        even if several parameter sets use it). A worker lost mid-sweep does not
        fail it: its tasks run elsewhere, and surfaces whose data or task was lost are submitted
        again (:data:`SWEEP_ATTEMPTS` rounds). In each worker, the task's Numba kernels run on
        the worker's ``threads_per_worker`` threads, not on every core of
        the machine in every worker. Without a client everything runs here, on Numba's threads.
    scatter_min : int
        Smallest array (elements) scattered rather than sent with its task.
    on_error : {"report", "raise"}
        What a surface that cannot be built or evaluated does (a ValueError, TypeError or
        ArithmeticError from ``factory`` or :meth:`RoughSurface.impact`: a speed past the model's
        limit, a bad parameter): "report" (default) records it in ``errors`` and the sweep goes on;
        "raise" raises it (the first one, for a local sweep).

    Returns
    -------
    SweepResults
        A list of :class:`RoughImpact` in the order of ``surfaces``; the same numbers with or
        without a client (the kernels sum in fixed blocks, so thread counts do not change the
        result). Its ``errors`` lists (index, exception) of the surfaces that failed, whose
        entries are RoughImpacts of ``kind = "failed"`` with NaN results; ``ok`` is a boolean
        array per surface.

    Raises
    ------
    ValueError
        A mass out of range, a number of masses that does not match the surfaces, an unknown
        unloading model or ``on_error``; with ``on_error="raise"``, what a surface's impact
        refuses.
    TypeError
        A surface that is neither a RoughSurface nor a dict, a factory that is not callable, or a
        non-numeric V1 or M (with ``on_error="raise"``, a factory's TypeError too).

    Notes
    -----
    Each impact is :meth:`RoughSurface.impact` (docs/rough.md section 8, "Sweeps").

    Examples
    --------
    >>> import fastrest
    >>> from fastrest import rough
    >>> steel = fastrest.Material(E=200e9, nu=0.3, Sy=1e9)
    >>> specs = [dict(material=steel, R_a=1e-4, gw=dict(eta=1e10, sigma=s, A_n=1e-4)) for s in (20e-9, 50e-9)]
    >>> [r.kind for r in rough.sweep(specs, [0.01, 0.1], 0.01)]
    ['statistical', 'statistical']

    A surface that fails does not stop the others (``on_error="raise"`` to raise instead):

    >>> specs.append(dict(material=steel, R_a=1e-4, gw=dict(eta=1e10, sigma=-1.0, A_n=1e-4)))
    >>> out = rough.sweep(specs, [0.01, 0.1], 0.01)
    >>> [r.kind for r in out], [i for i, _ in out.errors], out[2].e
    (['statistical', 'statistical', 'failed'], [2], array([nan, nan]))
    """
    if isinstance(surfaces, (RoughSurface, dict, str, bytes)) or not isinstance(surfaces, Iterable):
        raise TypeError("surfaces must be a sequence of RoughSurface objects or of dicts of parameters; "
                        f"got {type(surfaces).__name__}")
    surfaces = list(surfaces)
    Ma = as_float_array(M, "M")
    if Ma.ndim == 0:
        masses = [float(Ma)] * len(surfaces)
    else:
        masses = [float(m) for m in Ma.ravel()]
        if Ma.ndim != 1 or len(masses) != len(surfaces):
            raise ValueError(f"M has {len(masses)} values for {len(surfaces)} surfaces")
    for m in masses:
        check_finite_positive(m, "M", "(kg, mass of the flat)")
    flat, shape = check_speeds(V1)   # the same V1 for every surface
    v = flat.reshape(shape)
    unloading_code(unloading)
    check_bool(extrapolate, "extrapolate")
    if not callable(factory):
        raise TypeError("factory must be a callable building a RoughSurface from a dict")
    if on_error not in ("report", "raise"):
        raise ValueError(f"on_error must be 'report' or 'raise'; got {on_error!r}")
    report = on_error == "report"
    specs = []
    for s in surfaces:
        if isinstance(s, RoughSurface):
            specs.append(s.params())
        elif isinstance(s, dict):
            specs.append(dict(s))
        else:
            raise TypeError("surfaces must be RoughSurface objects or dicts of parameters")
    if client is None:
        out: list[Any] = []
        for s, spec, m in zip(surfaces, specs, masses):
            try:
                surface = s if isinstance(s, RoughSurface) else factory(**spec)
                out.append(surface.impact(v, m, unloading, extrapolate=extrapolate))
            except SURFACE_ERRORS as exc:
                if not report:
                    raise
                out.append(exc)
        return _results(out, v, masses, unloading)
    tasks = []  # (factory, small parameters, names of big arrays, the arrays, M)
    for s, spec, m in zip(surfaces, specs, masses):
        small, keys, arrays = {}, [], []
        for key, val in spec.items():
            if isinstance(val, np.ndarray) and val.size >= scatter_min:
                keys.append(key)
                arrays.append(val)
            else:
                small[key] = val
        tasks.append((factory if not isinstance(s, RoughSurface) else _rebuild_surface, small, keys, arrays, m))
    done: list[Any] = [None] * len(tasks)
    todo = list(range(len(tasks)))
    last: BaseException | None = None
    for attempt in range(SWEEP_ATTEMPTS):
        if attempt:
            time.sleep(0.5 * 2.0**attempt)  # the scheduler notices a lost worker (its nanny restarts it)
        try:
            futures = _submit(client, [tasks[i] for i in todo], v, unloading, extrapolate, report)
        except OSError as exc:  # a worker lost while scattering to it (distributed's CommClosedError)
            last = exc
            continue
        lost = []
        for i, future in zip(todo, futures):
            try:
                done[i] = future.result()
            except CancelledError as exc:  # data or task lost with a worker: submitted again
                lost.append(i)
                last = exc
        del futures  # release this round's scattered data
        if not lost:
            return _results(done, v, masses, unloading)
        todo = lost
    assert last is not None  # every round lost a surface
    raise last


def _submit(client, tasks, v, unloading, extrapolate, report):
    """Submit one :func:`_sweep_task` per task, V1 and the big arrays scattered once each.

    Not ``broadcast``: replicating to a worker that dies meanwhile never returns. A scattered array
    lost with its worker cancels the tasks that need it; :func:`sweep` submits them again."""
    # hash=False: a fresh key per sweep (a key shared with an earlier sweep of the same data is
    # released when that sweep's future is collected, cancelling these tasks: "lost dependencies")
    v_future = client.scatter(v, hash=False)
    shipped = {}  # id(array) -> future: each big array is scattered once
    futures = []
    for fac, small, keys, arrays, m in tasks:
        scattered = []
        for val in arrays:
            if id(val) not in shipped:
                shipped[id(val)] = (client.scatter(val, hash=False), val)  # keep val alive for the id
            scattered.append(shipped[id(val)][0])
        futures.append(client.submit(_sweep_task, fac, small, keys, *scattered, v_future, m, unloading,
                                     extrapolate, report, pure=False))
    return futures


def _results(out, v, masses, unloading):
    """SweepResults from the per-surface results, where an exception marks a failed surface."""
    errors = [(i, r) for i, r in enumerate(out) if isinstance(r, BaseException)]
    if errors:
        i, exc = errors[0]
        # two lines at most: the first error's first line, cut; the whole of each is in .errors
        reason = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
        reason = reason if len(reason) <= 120 else reason[:117] + "..."
        warn(f"{len(errors)} of {len(out)} surfaces failed and have NaN results (the first, surfaces[{i}]: "
             f"{type(exc).__name__}: {reason});\nsee the result's .errors (each surface's whole error) and .ok, or "
             "on_error='raise'", RuntimeWarning)
    return SweepResults([_failed(v, m, unloading) if isinstance(r, BaseException) else r
                         for r, m in zip(out, masses)], errors)
