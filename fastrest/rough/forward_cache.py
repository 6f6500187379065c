"""A surface's forward tables: built for its summits' material only as far as its impacts need."""
from __future__ import annotations

from collections.abc import Callable
from typing import Any
from numpy.typing import ArrayLike, NDArray
from ..forward import ForwardData
import warnings

import numpy as np

from .. import forward as fw
from .._validation import ValidityWarning, real_scalar
from ..limits import interference_limit, interference_limit_message
from ..loading import resolve as resolve_loading
from ..unloading import unloading_code
from .common import NEEDS_TABLE, OK

__all__ = ["ForwardCache"]


class ForwardCache:
    """The :class:`fastrest.forward.ForwardData` of one material and loading law, one per unloading
    model, grown on demand.

    Parameters
    ----------
    eps_y : float
        Sy/E' of the summits (-).
    nu : float
        Poisson's ratio of the summits (-).
    et_ratio : float, optional
        Tangent modulus over Young's modulus Et/E of the summits (-), 0 <= et_ratio < 1; default 0.
    loading : {None, "jackson-green", "ghaednia"}, optional
        The summits' loading law (:mod:`fastrest.loading`); None picks it from ``et_ratio``
        (Jackson-Green at 0, Ghaednia et al. 2019 above).

    Raises
    ------
    TypeError
        ``et_ratio`` is not a real number.
    ValueError
        ``et_ratio`` outside [0, 1), an unknown ``loading``, or et_ratio > 0 with a law without
        hardening.

    Notes
    -----
    Tables built for different w_max hold bit-identical cells where both are defined
    (:func:`fastrest.forward.forward_data`), so results never depend on which table the cache
    happens to hold.

    Examples
    --------
    >>> from fastrest.rough.forward_cache import ForwardCache
    >>> cache = ForwardCache(0.005, 0.3)
    >>> cache.get("jcg", w_max=30.0).w_max >= 30.0
    True
    >>> ForwardCache(0.005, 0.3, et_ratio=0.01).get("brake", w_max=30.0).law  # Ghaednia et al.
    1
    """

    # defaults of a cache pickled before strain hardening (its __dict__ lacks them)
    et_ratio: float = 0.0
    loading: str = "jackson-green"

    def __init__(self, eps_y: float, nu: float, et_ratio: float = 0.0, loading: str | None = None) -> None:
        self.eps_y, self.nu = eps_y, nu
        self.et_ratio = float(real_scalar(et_ratio, "et_ratio"))
        #: The loading law's public name (resolved: never None).
        self.loading = resolve_loading(loading, self.et_ratio).name
        self._data: dict[Any, ForwardData] = {}

    def limit(self, extrapolate: bool = False) -> float:
        """The model's largest w* (-) for this material and law: 425, or a/R = 1 with ``extrapolate``
        (:func:`fastrest.limit`)."""
        return interference_limit(self.eps_y, self.nu, extrapolate=extrapolate, et_ratio=self.et_ratio,
                                  loading=self.loading)

    def get(self, unloading: str = "jcg", *, w_max: float = 0.0, extrapolate: bool = False) -> ForwardData:
        """The table of one unloading model serving at least w* <= ``w_max``.

        Parameters
        ----------
        unloading : {"jcg", "etsion", "brake"}
            Unloading model (JGM eq 35, 33, or Brake's).
        w_max : float
            Largest w* (-) to serve; the held table is rebuilt larger when shorter (up to the
            model's range: a larger w_max is cut there, not refused).
        extrapolate : bool
            The model's range is a/R = 1 rather than w* = 425.

        Returns
        -------
        fastrest.forward.ForwardData

        Raises
        ------
        ValueError
            Unknown unloading model.
        """
        code = unloading_code(unloading)
        data = self._data.get(code)
        if data is None or data.w_max < w_max:
            lim = self.limit(extrapolate)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)  # issued once, by the surface
                data = fw.forward_data(self.eps_y, self.nu, unloading, w_max=min(max(w_max, 2.0), lim),
                                       extrapolate=extrapolate, et_ratio=self.et_ratio, loading=self.loading,
                                       contact_cells=False)
            self._data[code] = data
        return data

    def solve(self, run: Callable[[ForwardData, float], NDArray[np.float64]], w_guess: float, unloading: str,
              extrapolate: bool, where: Callable[[int], str],
              note: Callable[[float], str] | None = None) -> NDArray[np.float64]:
        """Run a solver, growing the table until no impact needs more of it.

        Parameters
        ----------
        run : callable
            ``run(data, w_model)`` -> the solver's (8, n) output (row 0 status, row 1 w* needed).
        w_guess : float
            w* (-) to build a missing table to.
        unloading, extrapolate
            As :meth:`get`.
        where : callable
            ``where(k)``: text naming impact k (its V1 and M), for messages.
        note : callable, optional
            ``note(k)``: text added to the message of impact k; with it, the message names the
            model's end rather than the solver's w* (a statistical surface's trial point).

        Returns
        -------
        ndarray
            The solver's output once every impact is solved.

        Raises
        ------
        ValueError
            An impact drives summits past the model's range (w* = 425, or a/R = 1).
        RuntimeError
            The solver failed (a bug).
        """
        lim = self.limit(extrapolate)
        data = self._data.get(unloading_code(unloading))
        if data is None:
            data = self.get(unloading, w_max=min(w_guess, lim), extrapolate=extrapolate)
        while True:
            out = run(data, lim)
            need = out[0] == NEEDS_TABLE
            if not np.any(need):
                break
            w_need = float(out[1, need].max())
            if data.w_max >= lim:  # the model's range ends first
                k = int(np.flatnonzero(need)[0])
                # a statistical solver's w* is a trial point's, not the impact's (its note says more)
                what = interference_limit_message(lim * (1 + 1e-15) if note else max(w_need, lim * (1 + 1e-15)),
                                                  self.eps_y, self.nu, extrapolate)
                raise ValueError(f"the impact at {where(k)} drives summits to a w* that {what}"
                                 + (note(k) if note else ""))
            data = self.get(unloading, w_max=min(lim, max(1.25 * w_need, 2.0 * data.w_max)),
                            extrapolate=extrapolate)
        if np.any(out[0] != OK):
            raise RuntimeError("rough-surface solver did not converge (please report)")
        return out
