"""The mapping between a table's arrays (:class:`~fastrest.tables.generation.GeneratedTable`) and the
axes, datasets and attributes of its file (docs/table-format.md), with the checks that tie a read
file's arrays to its grid before anything sized by the file is allocated."""
from __future__ import annotations

import os
from typing import Any
import numpy as np

from .. import unloading as _unloading
from .._validation import EPS_Y_VALIDATED, NU_VALIDATED, OMEGA_M_STAR_MAX
from .._version import __version__
from ..loading.jackson_green import W_SWITCH, omega_star_limit_kernel
from ..energy import GL_ORDER, PANEL_WIDTH, V_SWITCH
from ..interpolation import CHEB_U, DEGREE
from ..limits import speed_limit
from ..cells import jg_nodes
from .generation import GeneratedTable
from .axes import Block, cell_layout, energy_eps_y_axis, eps_y_blocks, nu_axis, omega_axis
from .grid import OMEGA_GRID_HERTZ, OMEGA_GRID_JG, QUANTITIES, QUANTITY_META, normalise_grid
from .hdf5 import FORMAT_VERSION, write_table
from .hdf5_read import read_table
from .file import TableFileError

__all__ = ["MODEL_ATTRS", "MAX_NODES", "MAX_V1_STAR_TOP", "write_generated", "read_generated"]

#: Provenance attributes of every table file.
MODEL_ATTRS = {
    "title": "fastrest table: Jackson-Green-Marghitu (2010) coefficient of restitution",
    "references": "Jackson R.L., Green I., Marghitu D.B. (2010) Nonlinear Dyn. 60:217-229, "
                  "doi:10.1007/s11071-009-9591-z",
    "source": "fastrest direct solver (composite Gauss-Legendre quadrature + Newton)",
    "model": {"paper": "Jackson, Green & Marghitu 2010", "doi": "10.1007/s11071-009-9591-z",
              "loading": "Jackson & Green 2005 elasto-plastic law, JGM eqs 8-15",
              "energy": "JGM eqs 22-31", "restitution": "JGM eq 38",
              **{f"unloading_{m.name}": m.label for m in _unloading.MODELS.values()}},
}
#: Largest node count a file's attributes may declare (checked before anything is allocated).
MAX_NODES = 100000
#: Largest V1* a file's cells may reach.
MAX_V1_STAR_TOP = 2.0**20


def write_generated(gen: GeneratedTable, path: str | os.PathLike[str], errors: dict[str, dict[str, Any]] | None = None) -> str:
    """Write a table's arrays to a table file, atomically (docs/table-format.md).

    Parameters
    ----------
    gen : GeneratedTable
        The arrays (:func:`~fastrest.tables.generate`).
    path : str or path-like
        The file; replaced atomically (:func:`fastrest.tables.hdf5.write_table`).
    errors : dict, optional
        The measured error (:func:`fastrest.tables.error.measure`), stored as ``measured_error``.

    Returns
    -------
    str
        The SHA-256 digest of the file's bytes after its header.

    Raises
    ------
    OSError
        Naming the file, if it cannot be written; the old file is then unchanged.

    Examples
    --------
    >>> import tempfile, os
    >>> from fastrest.tables import generate
    >>> gen = generate(dict(eps_y_min=0.004, eps_y_max=0.006, n_eps_y=6, nu_min=0.3, nu_max=0.35, n_nu=6,
    ...                     bits_per_octave=1, eps_y_blocks=[], n_eps_y_energy=6), progress=False)
    >>> with tempfile.TemporaryDirectory() as d:
    ...     digest = write_generated(gen, os.path.join(d, "t.h5"))
    ...     back, attrs = read_generated(os.path.join(d, "t.h5"))
    >>> bool((back.W_star[:, :, :20] == gen.W_star[:, :, :20]).all())
    True
    """
    g = gen.grid
    ncell = gen.edges.shape[0]
    axes = {
        "eps_y": (gen.eps_y, "1", "yield strain Sy/E' (JGM eq 11)"),
        "nu": (gen.nu, "1", "Poisson's ratio of the yielding material"),
        "cell": (gen.edges[:, 0], "1", "V1* = V1/V_c at the start of each interpolation cell"),
        "node": (CHEB_U, "1", "Chebyshev-Lobatto point of the cell, in [-1, 1] across the cell (-1 and 1: its edges)"),
        "omega_star": (gen.omega_star, "1", "normalised interference omega/omega_c"),
    }
    datasets = {
        "W_star": (gen.W_star, ("eps_y", "nu", "omega_star"), "1",
                   "normalised elasto-plastic energy (W_ep)* = 1 - F(w*), JGM eq 25"),
        "v1_star_max": (gen.v1_star_max, ("eps_y", "nu"), "1", "V1* at which w_m* = 425"),
        "cell_end": (gen.edges[:, 1], ("cell",), "1", "V1* at the end of each cell"),
        "v1_star_nodes": (gen.nodes, ("cell", "node"), "1", "V1* of each tabulated point"),
    }
    for k, b in enumerate(gen.blocks):
        axes[f"c_eps_y_{k}"] = (b.c_eps_y, "1", f"C(nu) eps_y (JGM eqs 5, 11): grid axis of block {k} of cells")
        axes[f"cell_{k}"] = (gen.edges[b.cell0:b.cstop, 0], "1",
                             f"V1* at the start of each cell of block {k} (and of the next block's first cell, "
                             "for the blend across the boundary)")
        for q, name in enumerate(QUANTITIES):
            units, long_name = QUANTITY_META[name]
            datasets[f"{name}_{k}"] = (b.values[q], (f"c_eps_y_{k}", "nu", f"cell_{k}", "node"), units,
                                       f"{long_name}; block {k} of cells")
    attrs = dict(MODEL_ATTRS)
    attrs.update({
        "grid": g,
        "cells": {"bits_per_octave": g["bits_per_octave"], "fine_bits_per_octave": g["fine_bits_per_octave"],
                  "fine_v1_star_max": g["fine_v1_star_max"], "degree": DEGREE, "count": ncell,
                  "first_key_fine": int(gen.base_fine), "first_key": int(gen.base),
                  "v1_star_top": float(gen.v_top),
                  "blocks": [[b.cell0, b.cell1, b.n] for b in gen.blocks]},
        "quadrature": {"rule": "composite Gauss-Legendre in ln w", "order": GL_ORDER,
                       "panel_width_ln_w": PANEL_WIDTH, "newton_step_tolerance_ln_w": 1e-9},
        "validated_range": {"eps_y": list(EPS_Y_VALIDATED), "nu": list(NU_VALIDATED),
                            "omega_m_star_max": OMEGA_M_STAR_MAX},
        "history": f"built by fastrest {__version__} (fastrest build)",
        "unloading_models": ",".join(_unloading.NAMES),
    })
    if errors is not None:
        attrs["measured_error"] = errors
    return write_table(path, axes, datasets, attrs)


def read_generated(path: str | os.PathLike[str]) -> tuple[GeneratedTable, dict[str, Any]]:
    """Read a table file into its arrays and root attributes.

    Parameters
    ----------
    path : str or path-like
        A table file.

    Returns
    -------
    gen : GeneratedTable
        The arrays, as :func:`~fastrest.tables.generate` made them.
    attrs : dict
        The root attributes (grid, cells, provenance, measured error).

    Raises
    ------
    TableFileError
        Naming the file, and nothing else, for a damaged, foreign or hostile file: the file is
        verified (:func:`fastrest.tables.hdf5_read.read_table`: digest, structure), then its format
        version, and that every array has the dtype (float64), dimensions, shape and finiteness the
        grid attributes imply, with the counts checked before anything sized by them is allocated.

    Examples
    --------
    >>> from fastrest.tables import default_table_path
    >>> gen, attrs = read_generated(default_table_path())
    >>> attrs["unloading_models"]
    'jcg,etsion,brake'
    """
    td = read_table(path)
    a = td.attrs
    if a.get("format_version") != FORMAT_VERSION:
        raise TableFileError(
            f"{path}: table format version {a.get('format_version')} is older than this fastrest's "
            f"({FORMAT_VERSION}); rebuild it with `fastrest build`")
    try:
        g = normalise_grid(a["grid"])
        cells = a["cells"]
        ds = td.datasets
        held = str(a.get("unloading_models", "jcg,etsion")).split(",")  # files before Brake: two models
        if held != list(_unloading.NAMES[:len(held)]) or not held:
            raise ValueError(f"unloading models {held} are not a prefix of this fastrest's {_unloading.NAMES}")
        quantities = QUANTITIES[:1 + 2 * len(held)]
        _check_file_arrays(td, g, cells, quantities)
        n_blocks = len(cells["blocks"])
        blocks = tuple(Block(cell0=int(c0), cell1=int(c1), cstop=int(c1) + (k < n_blocks - 1), n=int(n),
                             c_eps_y=td.axes[f"c_eps_y_{k}"],
                             values=np.stack([ds[f"{q}_{k}"] for q in quantities]))
                       for k, (c0, c1, n) in enumerate(cells["blocks"]))
        gen = GeneratedTable(grid=g, eps_y=td.axes["eps_y"], nu=td.axes["nu"], v_top=float(cells["v1_star_top"]),
                             base_fine=cells["first_key_fine"], base=cells["first_key"],
                             edges=np.stack([td.axes["cell"], ds["cell_end"]], 1), nodes=ds["v1_star_nodes"],
                             blocks=blocks, omega_star=td.axes["omega_star"], W_star=ds["W_star"],
                             v1_star_max=ds["v1_star_max"])
        if cells["degree"] != DEGREE or not np.array_equal(td.axes["node"], CHEB_U):
            raise ValueError("cell polynomial degree or nodes differ from this fastrest's")
        _check_axes_match_grid(gen)
    except Exception as exc:  # whatever a damaged or hostile file provokes: a file error
        raise TableFileError(f"{path}: not a valid fastrest restitution table "
                             f"({type(exc).__name__}: {exc})") from exc
    return gen, a


def _check_file_arrays(td, g, cells, quantities):
    """Datasets, dims, dtypes, shapes and finiteness of a read file against its grid attributes;
    the counts the grid declares must equal the stored ones (bounded by the file's size) before
    :func:`_check_axes_match_grid` allocates arrays of those sizes."""
    blocks = cells["blocks"]
    if not (isinstance(blocks, list) and 1 <= len(blocks) <= 64 and all(
            isinstance(b, list) and len(b) == 3 and all(type(x) is int and 0 <= x <= MAX_NODES for x in b)
            for b in blocks)):
        raise ValueError(f"cells: blocks must be up to 64 [cell0, cell1, n] of integers; got {str(blocks)[:200]}")
    counts = [g["n_eps_y"], g["n_nu"], g["n_eps_y_energy"]] + [n for _, n in g["eps_y_blocks"]]
    if not all(1 <= n <= MAX_NODES for n in counts):
        raise ValueError(f"grid: node counts {counts} outside [1, {MAX_NODES}]")
    v_top = cells["v1_star_top"]
    if not (type(v_top) is float and V_SWITCH < v_top <= MAX_V1_STAR_TOP):
        raise ValueError(f"cells: v1_star_top = {v_top!r} outside ({V_SWITCH:.6g}, {MAX_V1_STAR_TOP:g}]")
    ncell = blocks[-1][1]
    if cells["count"] != ncell or blocks[0][0] != 0 or any(b[0] != a[1] or b[1] <= b[0]
                                                            for a, b in zip(blocks, blocks[1:])):
        raise ValueError("cells: blocks do not cover the cells one after another")
    want = {"eps_y": (), "nu": (), "cell": (), "node": (), "omega_star": (),
            "W_star": ("eps_y", "nu", "omega_star"), "v1_star_max": ("eps_y", "nu"),
            "cell_end": ("cell",), "v1_star_nodes": ("cell", "node")}
    for k in range(len(blocks)):
        want.update({f"c_eps_y_{k}": (), f"cell_{k}": ()})
        want.update({f"{q}_{k}": (f"c_eps_y_{k}", "nu", f"cell_{k}", "node") for q in quantities})
    got = dict.fromkeys(td.axes, ())
    got.update(td.dims)
    if got != want:
        raise ValueError(f"datasets and dimensions {sorted(got.items())} differ from the layout of "
                         f"a restitution table")
    sizes = {"eps_y": g["n_eps_y_energy"], "nu": g["n_nu"], "cell": ncell, "node": DEGREE + 1,
             "omega_star": OMEGA_GRID_HERTZ + OMEGA_GRID_JG}
    for k, (c0, c1, n) in enumerate(blocks):
        # every block but the last also stores the next block's first cell (the blend)
        sizes.update({f"c_eps_y_{k}": n, f"cell_{k}": c1 - c0 + (k < len(blocks) - 1)})
    for name, n in sizes.items():
        if td.axes[name].shape != (n,):
            raise ValueError(f"axis {name!r} has shape {td.axes[name].shape}, the attributes say ({n},)")
    for name, values in {**td.axes, **td.datasets}.items():
        if values.dtype != np.float64:
            raise ValueError(f"{name!r} has dtype {values.dtype}, not float64")
        if name != "W_star" and not np.isfinite(values).all():
            raise ValueError(f"{name!r} holds NaN or infinite values")
    # Plausibility (a file with recomputed checksums can hold any finite numbers): w_m* > 1 above
    # the elastic range, 0 < e < 2, and each loss equal to 1 - e^2 to rounding
    for k in range(len(blocks)):
        if not (td.datasets[f"omega_m_star_{k}"] > 1.0).all():
            raise ValueError(f"'omega_m_star_{k}' holds values <= 1 (the table starts above the elastic range)")
        for q in quantities[1::2]:
            e, loss = td.datasets[f"{q}_{k}"], td.datasets[f"loss{q[1:]}_{k}"]
            if not ((e > 0.0) & (e < 2.0) & (np.abs(loss - (1.0 - e * e)) <= 1e-12)).all():
                raise ValueError(f"'{q}_{k}' or 'loss{q[1:]}_{k}' is not a coefficient of restitution and its "
                                 "1 - e^2")
    # W* = 1 - F is NaN exactly past the end of the law (a/R = 1), where the generator leaves it so
    w, e, n = td.axes["omega_star"], td.axes["eps_y"], td.axes["nu"]
    lim = np.array([[omega_star_limit_kernel(x, y) for y in n] for x in e])[:, :, None]
    past = (w > W_SWITCH) & (w >= lim * (1 + 1e-12))
    before = (w <= W_SWITCH) | (w < lim * (1 - 1e-12))
    ws = td.datasets["W_star"]
    if np.isinf(ws).any() or not np.isnan(ws[past]).all() or np.isnan(ws[before]).any():
        raise ValueError("'W_star' holds NaN or infinite values where the law is defined")


def _check_axes_match_grid(gen):
    """The checksum covers the arrays; this ties the grid attributes to them."""
    g = gen.grid
    nus = nu_axis(g)
    base_fine, base, edges = cell_layout(g, gen.v_top)
    blocks = eps_y_blocks(g, edges)
    if [(b.cell0, b.cell1, b.n) for b in blocks] != [(b.cell0, b.cell1, b.n) for b in gen.blocks]:
        raise ValueError("blocks of cells do not match the grid attributes")
    for b, got in zip(blocks, gen.blocks):
        if got.values.shape[1:] != (b.n, nus.size, b.cstop - b.cell0, DEGREE + 1):
            raise ValueError("a block's values do not have the shape of the grid attributes")
    v_max = np.array([[speed_limit(e, n) for n in gen.nu] for e in gen.eps_y])
    checks = [("nu", nus, gen.nu), ("eps_y", energy_eps_y_axis(g), gen.eps_y), ("cell", edges, gen.edges),
              ("omega_star", omega_axis(), gen.omega_star),
              ("v1_star_nodes", jg_nodes(edges, gen.v_top).reshape(gen.nodes.shape), gen.nodes),
              ("v1_star_max", v_max, gen.v1_star_max)]
    checks += [(f"c_eps_y_{k}", b.c_eps_y, got.c_eps_y) for k, (b, got) in enumerate(zip(blocks, gen.blocks))]
    for name, want, got in checks:
        if want.shape != got.shape or not np.allclose(want, got, rtol=1e-12, atol=0):
            raise ValueError(f"axis {name!r} does not match the grid attributes")
    if base != gen.base or base_fine != gen.base_fine:
        raise ValueError("cell keys do not match the grid attributes")
