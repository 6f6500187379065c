"""Tables built to a requested accuracy, and the error of a table against the direct solver.

The measurement (:func:`measure` and the sample it starts from, :func:`adversarial_points`) is
:mod:`fastrest.tables.accuracy`, re-exported here: see that module for how a table's stated error
is found and what it is relative to.

:func:`build_to_tolerance` refines the table's node counts until the measured error meets ``tol``:
each block of V1* cells whose error is too large gets more nodes in C(nu) eps_y (the error of the
6-point stencil falls like h^6); where that stopped helping, finer V1* cells (the fine region
extended, if the worst point lies just above it), then more nodes in nu, then more cells per octave.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any
import math

from .._deprecation import keyword_only
from .accuracy import (DEFAULT_TOL, SAFETY, SIGN_CHANGE_FLOOR, AccuracyWarning, adversarial_points, local_search,
                       measure, meets, sample_points, warn_if_inaccurate, worst)
from .generation import generate
from .grid import normalise_grid
from .table import Table

__all__ = ["AccuracyWarning", "DEFAULT_TOL", "SAFETY", "SIGN_CHANGE_FLOOR", "adversarial_points", "sample_points",
           "local_search", "measure", "meets", "worst", "build_to_tolerance", "warn_if_inaccurate"]


@keyword_only("max_rounds", "progress", "log")
def build_to_tolerance(grid: dict[str, Any] | None, tol: float, *, max_rounds: int = 5, progress: Any = False,
                       log: Callable[[str], object] | None = None) -> tuple[Any, ...]:
    """Generate a table, refining its node counts until its measured error meets a tolerance.

    Parameters
    ----------
    grid : dict or None
        The starting grid (:func:`~fastrest.tables.normalise_grid`).
    tol : float
        Relative error asked (sign-changing losses: see the module doc); met within
        :data:`SAFETY` x tol by the worst :func:`measure` finds (its sample, a point in every hump
        of the worst cells, and the local maxima climbed from the worst distinct humps).
    max_rounds : int
        Refinements tried.
    progress : None or bool
        Progress bar while generating (:func:`~fastrest.tables.generate`).
    log : callable, optional
        Called with one line per round.

    Returns
    -------
    gen, table, errors, grid : GeneratedTable, Table, dict, dict
        The arrays, the table, its errors (as :func:`measure`) and the grid reached.

    Raises
    ------
    ValueError
        ``max_rounds`` refinements do not reach ``tol``: the message names the error reached, where,
        and what to change.

    Examples
    --------
    >>> gen, t, errors, g = build_to_tolerance(dict(eps_y_min=0.004, eps_y_max=0.006, n_eps_y=6, nu_min=0.3,
    ...     nu_max=0.35, n_nu=6, bits_per_octave=1, eps_y_blocks=[], n_eps_y_energy=6), 1e-5)
    >>> meets(errors, 1e-5)
    True
    """
    g = normalise_grid(grid)
    target = tol * SAFETY
    prev: list[float] | None = None
    for rnd in range(max_rounds + 1):
        gen = generate(g, progress=progress)
        table = Table(gen)
        errors = measure(table)
        if log is not None:
            name, err, lim = worst(errors, target)
            log(f"round {rnd}: worst {name} {err:.2e} (limit {lim:.1e}); eps_y blocks "
                f"{g['eps_y_blocks']}, top {g['n_eps_y']}, nu {g['n_nu']}")
        if meets(errors, target):
            return gen, table, errors, g
        if rnd == max_rounds:
            break
        # per block: the worst ratio of error to limit over every quantity
        nb = len(gen.blocks)
        ratio = [max(d["by_block"][b] / target for d in errors.values()) for b in range(nb)]
        outside = max(d["max_error"] / target for d in errors.values())
        if max(ratio) <= 1.0 < outside:
            break  # the excess is below the switch or in the material edges: node counts cannot help
        refine_other = False
        for b, r in enumerate(ratio):
            if r <= 1.0:
                continue
            if prev is not None and r > 0.5 * prev[b]:
                refine_other = True  # more material nodes stopped helping: cells or nu
                continue
            factor = min(1.6, max(1.15, 1.1 * r ** (1.0 / 6.0)))
            blocks = [list(x) for x in g["eps_y_blocks"]]
            if b < len(blocks):
                blocks[b][1] = int(math.ceil(blocks[b][1] * factor))
                g = normalise_grid(g, eps_y_blocks=blocks)
            else:
                g = normalise_grid(g, n_eps_y=int(math.ceil(g["n_eps_y"] * factor)))
        if refine_other:
            v_worst = errors[worst(errors, target)[0]]["at_v1_star"]
            fine = g["fine_v1_star_max"]
            if fine <= v_worst < 4.0 * fine and fine < 2.0**20:
                g = normalise_grid(g, fine_v1_star_max=2.0 * fine)   # finer V1* cells there
            elif g["n_nu"] < 12:
                g = normalise_grid(g, n_nu=g["n_nu"] + 2)
            else:
                g = normalise_grid(g, bits_per_octave=min(10, g["bits_per_octave"] + 1))
            prev = None
            continue
        prev = ratio
    name, err, lim = worst(errors, target)
    d = errors[name]
    raise ValueError(
        f"could not build a table within tol = {tol:g} in {max_rounds} refinements: {name} has "
        f"{d['metric']} error {err:.3g} (limit {lim:.3g} = {SAFETY:g} tol) at V1* = {d['at_v1_star']:.6g}, eps_y = "
        f"{d['at_eps_y']:.6g}, nu = {d['at_nu']:.6g} with eps_y blocks {g['eps_y_blocks']}, n_eps_y "
        f"{g['n_eps_y']}, n_nu {g['n_nu']}. Ask for a larger tol, a narrower eps_y/nu range, or more "
        "cells per octave (bits_per_octave)")
