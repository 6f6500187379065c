"""The figures of Jackson, Green & Marghitu (2010), drawn from fastrest.

One function per figure of the paper (Figs 2-8; Fig 1 is a sketch). Each takes ``ax=None`` (a
Matplotlib Axes to draw into; by default a new :class:`matplotlib.figure.Figure` is made, without
pyplot, so no GUI backend is ever touched) and returns ``(fig, ax)``. :func:`write_all` writes all
of them as PNG files (``fastrest figures --out DIR``).

Matplotlib is imported only when a figure is drawn, so ``import fastrest`` works without it
(``pip install fastrest[plot]`` installs it).

Every curve is computed with the exact solver (:mod:`fastrest.direct`) or the closed forms of
:mod:`fastrest.models`, and stays inside the model's domain: V1* up to
:func:`fastrest.limit` (w_m* = 425, or a/R = 1 if that comes first).

Modules: :mod:`~fastrest.figures.jgm` (Figs 2-4, the model's own quantities),
:mod:`~fastrest.figures.comparisons` (Figs 5-6, e beside the comparison models) and
:mod:`~fastrest.figures.kharaz` (Figs 7-8, alumina spheres on aluminium and steel: the masses and
moduli used there, which the paper does not give in full, are documented in that module).
"""
from __future__ import annotations

import io
import os
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
from pathlib import Path

from .._validation import check_count
from ..tables.file import check_target, check_target_dir, replace_files
from ._common import EPS_Y_SERIES, TABLE1_EPS_Y, TABLE1_NU
from .comparisons import figure5, figure6
from .hardening import figure_hardening
from .jgm import figure2, figure3, figure4
from .kharaz import ALUMINA, ALUMINA_DENSITY, ALUMINIUM_FLAT, KHARAZ_RADIUS, STEEL_FLAT, figure7, figure8, kharaz_impact

__all__ = ["figure2", "figure3", "figure4", "figure5", "figure6", "figure7", "figure8", "figure_hardening", "kharaz_impact",
           "FIGURES", "MAX_DPI", "write_all", "ALUMINA_DENSITY", "ALUMINA", "ALUMINIUM_FLAT", "STEEL_FLAT", "KHARAZ_RADIUS",
           "TABLE1_EPS_Y", "TABLE1_NU", "EPS_Y_SERIES"]

#: Output file stem -> figure function, in the paper's order.
FIGURES: dict[str, Callable[..., tuple[Figure, Axes]]] = {
    "fig2_energy": figure2,
    "fig3_max_interference": figure3,
    "fig4_residual_interference": figure4,
    "fig5_e_vs_chang_ling": figure5,
    "fig6_unloading_models": figure6,
    "fig7_alumina_on_aluminium": figure7,
    "fig8_alumina_on_steel": figure8,
    "hardening_e": figure_hardening,  # not in JGM: Ghaednia et al. (2019), docs/model.md section 12
}
#: Largest resolution of :func:`write_all`: a 6.4 x 4.8 in figure is then 7680 x 5760 pixels.
MAX_DPI = 1200


def write_all(out_dir: str | os.PathLike[str], *, dpi: int = 150) -> list[Path]:
    """Draw every figure into ``out_dir`` as PNG (created if needed); return the list of paths.

    Files are named after :data:`FIGURES` (``fig2_energy.png`` ...). PNG metadata carry no software
    version (``metadata={"Software": None}``), so the bytes depend only on the data and on the
    Matplotlib version and fonts.

    Parameters
    ----------
    out_dir : str or os.PathLike
        Directory to write into.
    dpi : int
        Resolution of the PNG files (dots per inch), 1 to :data:`MAX_DPI`, keyword-only.

    Returns
    -------
    list of pathlib.Path
        The files written, in the order of :data:`FIGURES`.

    Raises
    ------
    ImportError
        Matplotlib is not installed (``pip install fastrest[plot]``).
    TypeError, ValueError
        ``dpi`` not a whole number in [1, :data:`MAX_DPI`]; ``out_dir`` not a path.
    OSError
        ``out_dir`` cannot be created or written, or a figure's file exists and is not a regular
        file (a directory, FIFO or device is never replaced); naming the path.

    Notes
    -----
    JGM Figs 2-8 (Fig 1 is a sketch), and e with strain hardening (not in JGM); ``fastrest figures
    --out DIR`` calls this. Every argument
    and target is checked, and every figure drawn in memory, before anything is created; the
    files are then written atomically (:func:`fastrest.tables.file.replace_files`).

    Examples
    --------
    >>> import tempfile
    >>> from fastrest.figures import write_all
    >>> [p.name for p in write_all(tempfile.mkdtemp(), dpi=20)][:2]
    ['fig2_energy.png', 'fig3_max_interference.png']
    """
    dpi = check_count(dpi, "dpi", 1, MAX_DPI)
    out = Path(check_target_dir(out_dir, "out_dir", "the figures directory"))
    paths = [out / f"{stem}.png" for stem in FIGURES]
    if out.is_dir():
        for p in paths:
            check_target(p, "out_dir", "the figure")
    images = {}
    for p, fn in zip(paths, FIGURES.values()):
        fig, _ = fn()
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=dpi, metadata={"Software": None})
        images[os.fspath(p)] = buf.getbuffer()
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OSError(exc.errno, f"cannot create the figures directory {os.fspath(out)!r}: {exc.strerror}") from None
    replace_files(images, "out_dir", "the figure")
    return paths
