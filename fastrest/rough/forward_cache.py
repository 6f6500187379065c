"""A surface's forward tables: built for its summits' material only as far as its impacts need."""
from __future__ import annotations

from collections.abc import Callable
from typing import Any
from numpy.typing import ArrayLike, NDArray
from ..forward import ForwardData
import warnings

import numpy as np

from .. import forward as fw
from .._validation import ValidityWarning
from ..limits import interference_limit, interference_limit_message
from ..unloading import unloading_code
from .common import NEEDS_TABLE, OK

__all__ = ["ForwardCache"]


class ForwardCache:
    """The :class:`fastrest.forward.ForwardData` of one material, one per unloading model, grown on
    demand.

    Parameters
    ----------
    eps_y : float
        Sy/E' of the summits (-).
    nu : float
        Poisson's ratio of the summits (-).

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
    """

    def __init__(self, eps_y: float, nu: float) -> None:
        self.eps_y, self.nu = eps_y, nu
        self._data: dict[Any, ForwardData] = {}

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
            lim = interference_limit(self.eps_y, self.nu, extrapolate=extrapolate)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)  # issued once, by the surface
                data = fw.forward_data(self.eps_y, self.nu, unloading, w_max=min(max(w_max, 2.0), lim),
                                       extrapolate=extrapolate)
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
            ``note(need)``: text added to the message.

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
        lim = interference_limit(self.eps_y, self.nu, extrapolate=extrapolate)
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
                what = interference_limit_message(max(w_need, lim * (1 + 1e-15)), self.eps_y, self.nu,
                                                  extrapolate)
                raise ValueError(f"the impact at {where(k)} drives summits to a w* that {what}"
                                 + (note(w_need) if note else ""))
            data = self.get(unloading, w_max=min(lim, max(1.25 * w_need, 2.0 * data.w_max)),
                            extrapolate=extrapolate)
        if np.any(out[0] != OK):
            raise RuntimeError("rough-surface solver did not converge (please report)")
        return out
