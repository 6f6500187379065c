"""The contact laws that ``pair_style jgm`` and ``fix wall/jgm`` ask fastrest for.

The plugin holds no copy of the model: when a run starts, its rank 0 writes the material pairs
of the simulation to a request file and runs ``python -m fastrest lammps law``, which builds each
pair's :class:`fastrest.ContactLaw` exactly as :meth:`fastrest.Impact.two_spheres` (two spheres)
or :class:`fastrest.Impact` (a sphere on a flat wall) would, and writes the rows of its cells
(``ContactLaw.data.law_rows``, read by the generated C law of :mod:`fastrest.export.law_c`) with
its critical values per unit reduced radius.

Request file: one line per law, ``KIND E1 nu1 Sy1 Et1 E2 nu2 Sy2 Et2 LABEL``, KIND ``spheres`` or
``flat`` (body 1 is the sphere), moduli and strengths in any one pressure unit, LABEL a word naming
the pair in error messages. Law file (little-endian float64 after the 8-byte :data:`MAGIC`): the number of laws, then per law
its head (:data:`LAW_HEAD`: omega_c/R, P_c/R^2, the end w* of the law, the number of rows n, a_c/R
(critical contact radius, sqrt(A_c/pi)), G* (Mindlin's combined shear modulus,
1/((2 - nu1)/G1 + (2 - nu2)/G2), G = E/(2 (1 + nu)))), the n rows of
:data:`fastrest.law_cells.LAW_ROW` values, and n rows of :data:`AREA_ROW`: [center, 1/half_width,
A* c0..c5] on the same cells (A* = w* up to 1.9, Hertz; JG's A* above). The plugin reads it with
the layout :func:`law_file_header` writes from these definitions.
"""
from __future__ import annotations

import math
import os
import re
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..export._io import check_target, write_files
from ..impact import Impact
from ..interpolation import chebyshev_nodes, fit_cells
from ..law_cells import LAW_ROW
from ..loading import a_star_unchecked
from ..loading.jackson_green import W_SWITCH
from ..materials import Material
from .. import unloading as _unloading

__all__ = ["MAGIC", "LAW_HEAD", "AREA_ROW", "MAX_LAWS", "Request", "read_requests", "area_rows", "law_bytes",
           "write_laws", "law_file_header"]

#: First 8 bytes of a law file.
MAGIC = b"FRJGMLW2"
#: Each law's head in a law file, in order (the plugin's names, ``LawFile::OMEGA_C1`` ...): omega_c/R,
#: P_c/R^2 (pressure unit), the law's end w*, its number of rows, a_c/R, G* (pressure unit).
LAW_HEAD = ("omega_c1", "p_c1", "w_end", "rows", "a_c1", "g_eff")
#: Values of one row of the contact area's cells: [center, 1/half_width, A* c0..c5].
AREA_ROW = 8
#: Most laws one request may ask for.
MAX_LAWS = 4096
_KINDS = ("spheres", "flat")
_LABEL = re.compile(r"^[A-Za-z0-9_./-]{1,80}$")


#: One law asked for: (kind, body 1 (E, nu, Sy, Et), body 2 (E, nu, Sy, Et), label).
Request = tuple[str, tuple[float, ...], tuple[float, ...], str]


def read_requests(path: str | os.PathLike[str]) -> list[Request]:
    """The laws a request file asks for: (kind, body 1 (E, nu, Sy, Et), body 2, label) each.

    Raises
    ------
    ValueError
        A line that is not ``KIND E1 nu1 Sy1 Et1 E2 nu2 Sy2 Et2 LABEL`` (naming the line), no
        line, or more than 4096 laws.
    """
    with open(path, encoding="ascii") as handle:
        lines = [ln.split() for ln in handle.read(1 << 20).splitlines() if ln.strip()]
    if not lines or len(lines) > MAX_LAWS:
        raise ValueError(f"request file {os.fspath(path)!r}: expected 1 to {MAX_LAWS} laws, got {len(lines)}")
    out = []
    for k, f in enumerate(lines, 1):
        if len(f) != 10 or f[0] not in _KINDS or not _LABEL.match(f[9]):
            raise ValueError(f"request file line {k}: expected 'spheres|flat E1 nu1 Sy1 Et1 E2 nu2 Sy2 Et2 LABEL'")
        try:
            v = [float(x) for x in f[1:9]]
        except ValueError:
            raise ValueError(f"request file line {k}: a value is not a number") from None
        if any(math.isnan(x) for x in v):
            raise ValueError(f"request file line {k}: a value is NaN")
        out.append((f[0], tuple(v[:4]), tuple(v[4:]), f[9]))
    return out


def _in_pascal(body, pascal):
    """(E, nu, Sy, Et) in pressure units of ``pascal`` Pa, in Pa."""
    return (body[0] * pascal, body[1], body[2] * pascal, body[3] * pascal)


def _impact(kind, a, b):
    one = Material(a[0], a[1], a[2], Et=a[3])
    two = Material(b[0], b[1], b[2], Et=b[3])
    if kind == "spheres":  # R1 = R2 = 2: reduced radius 1
        impact = Impact.two_spheres(one, 2.0, two, 2.0, mass1=1.0, mass2=1.0)
    else:
        impact = Impact(one, 1.0, flat=two, mass=1.0)
    if not impact.eps_y < 1.0:  # the Python layer computes it (with a ValidityWarning); no DEM run wants it
        raise ValueError(f"yield strength Sy = {impact.Sy:g} >= the combined modulus E' = "
                         f"{impact.critical_values()['E_eff']:g} (JGM eq 1): no material yields there")
    return impact


def area_rows(law: Any) -> NDArray[np.float64]:
    """Rows [center, 1/half_width, A* c0..c5] of the contact area on the cells of ``law.data.law_rows``.

    A* = (a/a_c)^2 is Hertz's w* up to the switch at 1.9 (the rows of cells below it hold exactly
    that line: c0 = center, c1 = half width, so that w* below the first cell extrapolates it
    exactly) and the loading law's A* above, fitted as the P* cells are.
    """
    rows = law.data.law_rows
    half = 1.0 / rows[:, 1]
    edges = np.stack([rows[:, 0] - half, rows[:, 0] + half], axis=1)
    out = np.zeros((rows.shape[0], AREA_ROW))
    out[:, 0], out[:, 1] = rows[:, 0], rows[:, 1]
    low = rows[:, 0] < W_SWITCH
    out[low, 2], out[low, 3] = rows[low, 0], half[low]
    if (~low).any():
        nodes = chebyshev_nodes(edges[~low])
        nodes = np.where(nodes <= W_SWITCH, np.nextafter(W_SWITCH, np.inf), nodes)  # the JG side of 1.9
        values = np.array([[a_star_unchecked(law.data.law, float(x), law.data.eps_y, law.data.nu, law.data.et_ratio)
                            for x in cell] for cell in nodes])
        out[~low, 2:] = fit_cells(edges[~low], values)[:, 2:]
    return out


def _g_eff(a, b):
    """Mindlin's G* = 1/((2 - nu1)/G1 + (2 - nu2)/G2) of bodies (E, nu, ...), G = E/(2 (1 + nu))."""
    return 1.0 / sum((2.0 - body[1]) * 2.0 * (1.0 + body[1]) / body[0] for body in (a, b))


def law_bytes(requests: list[Request], unloading: str, pascal: float = 1.0) -> bytes:
    """The law file of ``requests`` (:func:`read_requests`) with unloading model ``unloading``.

    ``pascal`` is the simulation's pressure unit in Pa (LAMMPS ``units si`` 1, ``cgs`` 0.1,
    ``micro`` 1e3, ``nano`` 1e6): the materials are built in Pa (so that fastrest's messages give
    Pa) and the critical force and G* written back in the simulation's unit.

    Raises
    ------
    ValueError
        An unknown unloading model; ``pascal`` not finite and > 0; a pair fastrest refuses (its
        message, prefixed by the label).
    """
    if unloading not in _unloading.NAMES:
        raise ValueError(f"unloading model {unloading!r} is not one of {', '.join(_unloading.NAMES)}")
    if not (math.isfinite(pascal) and pascal > 0.0):
        raise ValueError(f"pressure unit pascal = {pascal!r} Pa must be finite and > 0")
    parts = [np.array([len(requests)], dtype="<f8")]
    for kind, a, b, label in requests:
        a, b = _in_pascal(a, pascal), _in_pascal(b, pascal)
        try:
            impact = _impact(kind, a, b)
            law = impact.contact_law(unloading)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{label}: {exc}") from None
        rows = np.ascontiguousarray(law.data.law_rows, dtype="<f8")
        head = {"omega_c1": impact.omega_c, "p_c1": impact.P_c / pascal, "w_end": float(law.data.w_max),
                "rows": float(rows.shape[0]), "a_c1": math.sqrt(impact.A_c / math.pi), "g_eff": _g_eff(a, b) / pascal}
        parts += [np.array([head[k] for k in LAW_HEAD], dtype="<f8"), rows.ravel(),
                  area_rows(law).astype("<f8").ravel()]
    return MAGIC + np.concatenate(parts).tobytes()


def write_laws(path: str | os.PathLike[str], requests: list[Request], unloading: str, pascal: float = 1.0) -> str:
    """Write the law file of ``requests`` (pressure unit ``pascal`` Pa) atomically; return its path."""
    check_target(path, "--out", "the law file")
    data = law_bytes(requests, unloading, pascal)
    return write_files({path: data}, "--out", "the law file")[0]


def law_file_header() -> str:
    """C++ header ``jgm_law_file.h``: the law file's layout as the plugin reads it, from this module's
    definitions (:data:`MAGIC`, :data:`LAW_HEAD`, :data:`AREA_ROW`, :data:`MAX_LAWS`) and the row width
    :data:`fastrest.law_cells.LAW_ROW`; ``fastrest lammps build`` writes it beside the generated law."""
    names = "\n".join(f"constexpr int {name.upper()} = {k};" for k, name in enumerate(LAW_HEAD))
    return (f"/* jgm_law_file.h: the layout of fastrest's law file, generated from fastrest.lammps.laws. */\n"
            "#ifndef FASTREST_JGM_LAW_FILE_H\n#define FASTREST_JGM_LAW_FILE_H\n\n#include <cstddef>\n\n"
            "namespace FastrestJGM {\nnamespace LawFile {\n\n"
            f"constexpr char MAGIC[{len(MAGIC) + 1}] = \"{MAGIC.decode('ascii')}\";\n"
            f"constexpr size_t MAGIC_SIZE = {len(MAGIC)};\n"
            f"//! Values of each law's head, and where each is in it\nconstexpr int HEAD = {len(LAW_HEAD)};\n{names}\n"
            f"//! Values of one row of the law's cells, and of its contact area's cells\n"
            f"constexpr int ROW = {LAW_ROW};\nconstexpr int AREA_ROW = {AREA_ROW};\n"
            f"//! Most laws one request may ask for\nconstexpr size_t MAX_LAWS = {MAX_LAWS};\n\n"
            "}    // namespace LawFile\n}    // namespace FastrestJGM\n\n#endif\n")
