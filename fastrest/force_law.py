"""The contact law in the time domain: normal force from interference, with history.

DEM and transient multi-asperity codes integrate the equations of motion and ask, at every time
step, for the force of each contact at its current interference. The JGM ingredients answer it
(normalised by the critical values of eqs 4-7: w = omega/omega_c, P* = P/P_c):

* **virgin loading** (w above the largest interference reached so far, w_max): the Jackson-Green
  law, Hertz P* = w^1.5 up to w = 1.9 (eq 14), JG's eq (9) above (it drops by ~0.16 % at 1.9);
  with strain hardening (``et_ratio`` = Et/E > 0) Ghaednia et al.'s (2019) law instead
  (:mod:`fastrest.loading`), the same at Et/E = 0 bit for bit;
* **unloading and reloading** below w_max: elastic, eq (32), through (w_max, P*(w_max)) and the
  residual interference w_res*(w_max) of the unloading model (eq 35 JCG, eq 33 Etsion, or
  Brake's), P* = P_max ((w - w_res)/(w_max - w_res))^1.5, and 0 at or below w_res (the contact
  has separated; the residual dent stays in the state). Passing w_max again continues on the
  JG law. The elastic branch is a function of w alone: a closed unload/reload cycle below w_max
  returns exactly the work put in.
* **gaps**: w <= 0 before the first contact, or at or below w_res after it, gives 0. One corner
  of the model: just above w* = 1.9, where the JG force exceeds Hertz's (nu below about 0.32)
  and the model's e exceeds 1, Etsion's and Brake's w_res* is slightly negative (down to about
  -0.01): the branch then pushes until w = w_res* < 0, as the model (and tmdsimpy) has it, so
  that the rebound equals the model's e.

One impact loaded to w_m and unloaded dissipates F(w_m) - P_m (w_m - w_res), in U_c units, which
is (1 - e^2) V1*^2 of the energy balance (eq 38): integrated in time, this law reproduces the e of
:func:`fastrest.curve` (tests/test_force_law.py; step counts in docs/model.md section 10). The
elastic branch stores and returns energy without loss, so the energy a contact has dissipated is a
function of its largest interference alone: :func:`dissipated_energy` reads it from the state.

The loading force above w = 1.9 is read from bit-indexed degree-5 cells fitted to eq (9)
(:func:`fastrest.forward.P_table_forward`, ~1e-14 relative), and the unloading model's residual
from cells beside them (:mod:`fastrest.law_cells`), the law's data being the material's
:class:`fastrest.forward.ForwardData`.

From Numba: ``law.data`` and :func:`contact_force` (re-exported by :mod:`fastrest.jit`), one
state row of :data:`STATE_SIZE` float64 per contact, zeros for a virgin contact. Several materials
in one loop: :func:`stack_laws` and :func:`contact_force_stacked`, indexed by material. The
energy each contact has dissipated: :func:`dissipated_energy` and :func:`dissipated_energy_stacked`.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any
from numpy.typing import ArrayLike, NDArray
import math
from collections import namedtuple

import numpy as np

from ._jit import jit
from ._validation import (as_float_array, check_bool, check_count, check_finite_positive, check_eps_y, check_nu,
                          kernel_array, real_scalar)
from .loading.jackson_green import W_SWITCH, area_exponent
from . import loading as _loading
from .loading import p_star_above, resolve as resolve_loading
from .critical import c_of_nu
from .energy import f_star_kernel, omega_m_kernel
from .forward import ForwardData, P_table_forward, forward_data, loss_forward
from .law_cells import elastic_back, law_step, law_step_branching, material_law
from .limits import interference_limit, raise_interference_out_of_range, raise_out_of_range, w_upper_model
from .scene import material_index
from . import unloading as _unloading

__all__ = ["STATE_SIZE", "MAX_CONTACTS", "check_state_count", "contact_force", "ContactLaw", "contact_law", "hertz_contact_time", "StackedLaws",
           "stack_laws", "contact_force_stacked", "dissipated_energy", "dissipated_energy_stacked"]

#: Values of history per contact: w_max (largest interference so far), P*(w_max), w_res* and
#: delta = w_max - w_res* of the unloading model at w_max (set with w_max at every loading step, so
#: a row with w_max > 0 and delta = 0 is no history of a law and is refused).
STATE_SIZE = 4
#: Most contacts :meth:`ContactLaw.new_state` allocates at once (32 GB of history rows).
MAX_CONTACTS = 10**9


def check_state_count(n: object, free_bytes: int | None = None, where: str = "in memory") -> int:
    """``n`` as a number of contacts whose history rows (:data:`STATE_SIZE` float64 each) fit,
    checked before anything is allocated (:meth:`ContactLaw.new_state`, ``fastrest.cuda.new_state``).

    Parameters
    ----------
    n : int
        Number of contacts, a whole number >= 0: at most :data:`MAX_CONTACTS` without
        ``free_bytes``, else as many as fit in ``free_bytes``.
    free_bytes : int, optional
        Bytes available (a GPU's free memory); None: host memory, at most ``MAX_CONTACTS`` rows.
    where : str
        Where the rows go, for the message ("on the GPU").

    Returns
    -------
    int

    Raises
    ------
    TypeError
        ``n`` is not a number.
    ValueError
        ``n`` is not a whole number >= 0, or its rows need more than ``free_bytes`` (or more than
        ``MAX_CONTACTS`` rows without it); the message names n and the bytes.

    Examples
    --------
    >>> from fastrest.force_law import check_state_count
    >>> check_state_count(3.0)
    3
    >>> check_state_count(1000, 16000, "on the GPU")
    Traceback (most recent call last):
    ...
    ValueError: n = 1000 contacts need 32000 bytes of history rows (32 bytes each), more than the 16000 bytes free on the GPU
    """
    try:
        n = check_count(n, "n", 0, 2**1024)  # a whole number >= 0 (any float); then the bytes its rows need
    except ValueError:
        raise ValueError(f"n (number of contacts) must be a whole number >= 0; got {n!r}") from None
    need = STATE_SIZE * 8
    if free_bytes is None and n > MAX_CONTACTS:
        raise ValueError(f"n = {n} contacts need {n * need} bytes of history rows ({need} bytes each); at "
                         f"most n = {MAX_CONTACTS} ({MAX_CONTACTS * need} bytes) are allocated at once")
    if free_bytes is not None and n * need > free_bytes:
        raise ValueError(f"n = {n} contacts need {n * need} bytes of history rows ({need} bytes each), more "
                         f"than the {free_bytes} bytes free {where}")
    return n


@jit(inline=True)
def contact_force(data, state, w):
    """Normal force P* = P/P_c at interference w = omega/omega_c, updating the contact's history.

    Parameters
    ----------
    data : ForwardData
        ``ContactLaw.data`` of the material (:func:`contact_law`).
    state : float64 array of :data:`STATE_SIZE`
        This contact's history; zeros for a virgin contact. Updated in place.
    w : float
        Current interference (-); w <= 0 is a gap (force 0; after a contact, below w_res*). An
        integer or float32 is taken as float64.

    Returns
    -------
    float
        P* (-). NaN for NaN or infinite w, past the law's end (``data.w_max``: w* = 425, a/R = 1 or the end of
        the unloading model), a state whose w_max = state[0] is negative, NaN or past the law's
        end, or positive with delta = state[3] <= 0 (no history of this law); the state is then set to NaN (the contact's history is lost: every
        later call gives NaN until the row is zeroed). A jit kernel: it never raises.

    Notes
    -----
    Virgin loading (w above the largest interference so far): the Jackson-Green law, Hertz w^1.5
    up to w = 1.9 (JGM eq 14) and eq (9) above (Ghaednia et al.'s with hardening,
    ``data.et_ratio`` > 0), from the cells of ``data.p_rows`` (~1e-14 relative). Below the maximum: elastic unloading and reloading, JGM eq (32), through the
    maximum point and the unloading model's residual interference (eq 35, eqs 33-34 or Brake's,
    read from cells beside P*'s to 3.3e-14 and stored with w_max at every loading step);
    0 at or below w_res*. No branch: every case is computed and one chosen by selects
    (:mod:`fastrest.law_cells`), so a step-major DEM loop does not mispredict
    (bench/DEM_LOOP.md). See docs/model.md section 10. Inlined into the calling jitted loop; also
    exported as :func:`fastrest.jit.contact_force`.

    Examples
    --------
    >>> import fastrest
    >>> from fastrest.jit import contact_force
    >>> law = fastrest.contact_law(0.005, 0.33, w_max=30.0)
    >>> state = law.new_state()
    >>> round(contact_force(law.data, state, 10.0), 6)  # loading
    25.647583
    >>> round(contact_force(law.data, state, 5.0), 6)  # unloading, eq (32)
    2.401153
    >>> state.round(6)  # w_max, P*(w_max), w_res*, w_max - w_res*
    array([10.      , 25.647583,  3.701334,  6.298666])
    """
    rows = data.law_rows
    return law_step(rows, 0, rows.shape[0] - 1, data.w_max, state, np.float64(w))


@jit(inline=True)
def _contact_force_sequential(data, state, w):
    """:func:`contact_force` with branches (bit for bit the same): for one contact stepped through
    time (:meth:`ContactLaw.force`, :func:`impact_in_time`), where it is the faster one."""
    rows = data.law_rows
    return law_step_branching(rows, 0, rows.shape[0] - 1, data.w_max, state, np.float64(w))


StackedLaws = namedtuple("StackedLaws", ["model", "eps_y", "nu", "w_max", "shift", "base", "p_rows",
                                         "omega_c", "P_c", "law", "et_ratio", "f_rows", "law_rows", "law_first",
                                         "law_last"])
StackedLaws.__doc__ = """The contact laws of several materials in one Numba-friendly data: arrays indexed by material.

Build it with :func:`stack_laws` (not by hand) and pass it, with a material index per contact, to
:func:`contact_force_stacked` inside a ``numba.prange`` loop: a tuple or list of ``ContactLaw.data``
cannot be indexed by a run-time material index in Numba code (the laws' rows differ in length),
this can.

Parameters
----------
model : int64 ndarray
    Unloading model code of each material's law (:data:`fastrest.jit.JCG` ...).
eps_y, nu : float64 ndarray
    The materials (-).
w_max : float64 ndarray
    Largest interference w* each law serves (-).
shift, base : int64 ndarray
    Cell-index parameters of each material's bit-indexed cells in ``p_rows``.
p_rows : ndarray
    (n, 8) float64: every material's rows of P* (:class:`fastrest.forward.ForwardData`), one after
    the other.
omega_c, P_c : float64 ndarray
    Each law's units (m, N; 1.0 for a normalised law): :func:`contact_force_stacked` returns P* in
    units of P_c at w = omega/omega_c, as :func:`contact_force` does; a DEM code whose contacts of
    one material differ in radius computes omega_c and P_c per contact
    (:func:`fastrest.jit.critical_scales`).
law : int64 ndarray
    Loading law code of each material (:data:`fastrest.jit.JACKSON_GREEN`,
    :data:`fastrest.jit.GHAEDNIA`).
et_ratio : float64 ndarray
    Tangent modulus over Young's modulus Et/E of each material (-); 0 for Jackson-Green.
f_rows : ndarray
    (n, 8) float64: every material's rows of the loading energy F, placed as ``p_rows``
    (:func:`dissipated_energy_stacked` reads them).
law_rows : ndarray
    (n, 16) float64: every material's ``law_rows`` (:mod:`fastrest.law_cells`), one after the
    other (:func:`contact_force_stacked` reads them).
law_first, law_last : int64 ndarray
    Material k's law rows are ``law_first[k] .. law_first[k] + law_last[k]``.

Examples
--------
>>> import fastrest
>>> from fastrest.force_law import stack_laws
>>> laws = stack_laws([fastrest.contact_law(0.005, 0.33), fastrest.contact_law(0.002, 0.3, "etsion")])
>>> laws.eps_y, laws.model
(array([0.005, 0.002]), array([0, 1]))
"""


@jit(inline=True)
def contact_force_stacked(laws, material, state, w):
    """:func:`contact_force` of material ``material`` of stacked laws: several materials in one loop.

    Parameters
    ----------
    laws : StackedLaws
        The materials' laws, from :func:`stack_laws`.
    material : int
        Index of the contact's material in ``laws`` (its position in the list given to
        :func:`stack_laws`); an integer or an integer-valued float.
    state : float64 array of :data:`STATE_SIZE`
        This contact's history; zeros for a virgin contact. Updated in place.
    w : float
        Current interference w = omega/omega_c (-) of the contact.

    Returns
    -------
    float
        P* (-), bit for bit what :func:`contact_force` gives with that material's ``law.data``.
        NaN (and the state set to NaN, as for any input outside the law) for a material index out
        of range, a fraction or a non-finite one, and wherever :func:`contact_force` gives NaN. A
        jit kernel: it never raises.

    Notes
    -----
    The same code as :func:`contact_force` (JGM eqs 9, 14 loading; eq 32 with eq 35, 33-34 or
    Brake's unloading), reading the material's fields from the stacked arrays. For a DEM loop over
    contacts of several materials inside ``numba.prange`` (docs/model.md section 10; the example
    docs/examples/dem_wall.py). Inlined into the calling jitted loop; also exported as
    :func:`fastrest.jit.contact_force_stacked`.

    Examples
    --------
    >>> import fastrest
    >>> from fastrest.force_law import contact_force_stacked, stack_laws
    >>> steel, alu = fastrest.contact_law(0.005, 0.33), fastrest.contact_law(0.004, 0.33)
    >>> laws = stack_laws([steel, alu])
    >>> state = steel.new_state()
    >>> round(contact_force_stacked(laws, 1, state, 10.0), 6) == round(float(alu.force([10.0])[0]), 6)
    True
    >>> contact_force_stacked(laws, 2, steel.new_state(), 10.0)  # no material 2
    nan
    """
    # material_index: -1 for a fraction, a negative or non-finite index (then NaN, no branch)
    first, last, end = material_law(laws.law_first, laws.law_last, laws.w_max, material_index(material))
    return law_step(laws.law_rows, first, last, end, state, np.float64(w))


@jit(inline=True)
def dissipated_energy(data, state):
    """Energy the contact has dissipated so far, over U_c, from its history row (-).

    Parameters
    ----------
    data : ForwardData
        ``ContactLaw.data`` of the material (:func:`contact_law`), the law that built ``state``.
    state : float64 array of :data:`STATE_SIZE`
        The contact's history, as :func:`contact_force` leaves it (not changed).

    Returns
    -------
    float
        D = F(w_max) - P*(w_max) (w_max - w_res*) (-) in units of U_c = (2/5) P_c omega_c (JGM
        eq 24): the loading work to the largest interference reached minus what the elastic
        branch through it returns. 0 for a virgin row (zeros) and for w_max <= 1 (elastic; also
        for w_max <= 1.9 with Etsion or Brake unloading). NaN for a row that is NaN (history
        lost), has w_max < 0 or w_max past the law's ``w_max``, or an unknown unloading model (a
        jit kernel: it never raises).

    Notes
    -----
    :func:`fastrest.forward.loss_forward` at w_max = ``state[0]``: JGM eqs (25), (38) with
    eq (32) and the unloading model's w_res*, without cancellation. The elastic branch (eq 32)
    is a function of w alone, so unloading and reloading below w_max dissipate nothing and D
    depends on w_max only: the work the contact has received is D plus the energy it stores at
    its current interference. After one impact at V1* (loaded to w_m*, separated),
    D = F(w_m*) - R = (1 - e^2) V1*^2 (eq 38). In joules: D (2/5) P_c omega_c, or D U_c with
    U_c from :func:`fastrest.jit.critical_scales`. Inlined into the calling jitted loop; also
    exported as :func:`fastrest.jit.dissipated_energy`.

    Examples
    --------
    >>> import fastrest
    >>> from fastrest.jit import contact_force, dissipated_energy
    >>> law = fastrest.contact_law(0.005, 0.33, w_max=30.0)
    >>> state = law.new_state()
    >>> dissipated_energy(law.data, state)  # virgin
    0.0
    >>> p = contact_force(law.data, state, 6.549856322605)  # loaded to w_m* of V1* = 10
    >>> p = contact_force(law.data, state, 2.0)             # unloading: nothing more is lost
    >>> round(dissipated_energy(law.data, state), 6)  # (1 - e^2) V1*^2 = 0.313202 * 100
    31.320232
    """
    if not state[1] == state[1]:  # a row whose P*(w_max) is NaN lost its history
        return np.nan
    return loss_forward(data, state[0])


@jit(inline=True)
def dissipated_energy_stacked(laws, material, state):
    """:func:`dissipated_energy` of a contact of material ``material`` of stacked laws (-).

    Parameters
    ----------
    laws : StackedLaws
        The materials' laws, from :func:`stack_laws`.
    material : int
        Index of the contact's material in ``laws``; an integer or an integer-valued float.
    state : float64 array of :data:`STATE_SIZE`
        The contact's history, as :func:`contact_force_stacked` leaves it (not changed).

    Returns
    -------
    float
        D (-) in units of U_c, bit for bit what :func:`dissipated_energy` gives with that
        material's ``law.data``; NaN for a material index out of range, a fraction or a
        non-finite one, and wherever :func:`dissipated_energy` gives NaN (a jit kernel: it never
        raises).

    Notes
    -----
    JGM eqs (25), (38) as :func:`dissipated_energy`, reading the material's fields from the
    stacked arrays. Inlined into the calling jitted loop; also exported as
    :func:`fastrest.jit.dissipated_energy_stacked`.

    Examples
    --------
    >>> import fastrest
    >>> from fastrest.force_law import contact_force_stacked, dissipated_energy_stacked, stack_laws
    >>> laws = stack_laws([fastrest.contact_law(0.005, 0.33), fastrest.contact_law(0.004, 0.3, "brake")])
    >>> state = fastrest.contact_law(0.005, 0.33).new_state()
    >>> p = contact_force_stacked(laws, 0, state, 6.549856322605)
    >>> round(dissipated_energy_stacked(laws, 0, state), 6)
    31.320232
    >>> dissipated_energy_stacked(laws, 2, state)  # no material 2
    nan
    """
    k = material_index(material)
    if k < 0 or k >= laws.eps_y.size:
        return np.nan
    eps_y, nu = laws.eps_y[k], laws.nu[k]
    data = ForwardData(laws.model[k], eps_y, nu, c_of_nu(nu), area_exponent(eps_y), laws.w_max[k], laws.shift[k],
                       laws.base[k], laws.f_rows, laws.p_rows, laws.law[k], laws.et_ratio[k], laws.law_rows)
    return dissipated_energy(data, state)


def stack_laws(laws: Sequence[ContactLaw]) -> StackedLaws:
    """One :class:`StackedLaws` holding several materials' contact laws, for
    :func:`contact_force_stacked` in a parallel DEM loop.

    Parameters
    ----------
    laws : sequence of ContactLaw
        1 to 65536 laws (:func:`contact_law` or :meth:`fastrest.Impact.contact_law`), possibly of
        different unloading models and ``w_max``; material k of the result is ``laws[k]``.

    Returns
    -------
    StackedLaws
        Arrays indexed by material; the rows of every law, concatenated (the laws' own arrays are
        copied, so the result does not change if they are rebuilt).

    Raises
    ------
    TypeError
        ``laws`` is not a sequence of :class:`ContactLaw`.
    ValueError
        No law, or more than 65536.

    Notes
    -----
    The force of material k is computed by the code of :func:`contact_force` on ``laws[k].data``
    (docs/model.md section 10): the results are the same bit for bit.

    Examples
    --------
    >>> import numba, numpy as np, fastrest
    >>> from fastrest import jit as frj
    >>> from fastrest.force_law import stack_laws
    >>> laws = stack_laws([fastrest.contact_law(0.005, 0.33), fastrest.contact_law(0.002, 0.25)])
    >>> @numba.njit(parallel=True)
    ... def forces(laws, material, states, w, out):
    ...     for i in numba.prange(w.size):  # one contact per i, of material material[i]
    ...         out[i] = frj.contact_force_stacked(laws, material[i], states[i], w[i])
    >>> out = np.empty(2)
    >>> forces(laws, np.array([0, 1]), np.zeros((2, frj.STATE_SIZE)), np.array([10.0, 10.0]), out)
    >>> out.round(6)
    array([25.647583, 26.233655])
    """
    if isinstance(laws, ContactLaw) or not hasattr(laws, "__len__") or isinstance(laws, (str, bytes)):
        raise TypeError(f"laws must be a sequence of ContactLaw (fastrest.contact_law), got {type(laws).__name__}")
    laws = list(laws)
    for k, law in enumerate(laws):
        if not isinstance(law, ContactLaw):
            raise TypeError(f"laws[{k}] must be a ContactLaw (fastrest.contact_law), got {type(law).__name__}")
    if not 1 <= len(laws) <= 65536:
        raise ValueError(f"laws must hold 1 to 65536 contact laws; got {len(laws)}")
    sizes = [law.data.p_rows.shape[0] for law in laws]
    offset = np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(np.int64)
    law_sizes = [law.data.law_rows.shape[0] for law in laws]
    return StackedLaws(
        model=np.array([law.data.model for law in laws], dtype=np.int64),
        law=np.array([law.data.law for law in laws], dtype=np.int64),
        et_ratio=np.array([law.data.et_ratio for law in laws], dtype=np.float64),
        eps_y=np.array([law.data.eps_y for law in laws], dtype=np.float64),
        nu=np.array([law.data.nu for law in laws], dtype=np.float64),
        w_max=np.array([law.data.w_max for law in laws], dtype=np.float64),
        shift=np.array([law.data.shift for law in laws], dtype=np.int64),
        base=np.array([law.data.base for law in laws], dtype=np.int64) - offset,
        p_rows=np.ascontiguousarray(np.concatenate([law.data.p_rows for law in laws]), dtype=np.float64),
        f_rows=np.ascontiguousarray(np.concatenate([law.data.f_rows for law in laws]), dtype=np.float64),
        law_rows=np.ascontiguousarray(np.concatenate([law.data.law_rows for law in laws]), dtype=np.float64),
        law_first=np.concatenate([[0], np.cumsum(law_sizes)[:-1]]).astype(np.int64),
        law_last=np.array(law_sizes, dtype=np.int64) - 1,
        omega_c=np.array([law.omega_c for law in laws], dtype=np.float64),
        P_c=np.array([law.P_c for law in laws], dtype=np.float64))


@jit
def _force_path(data, state, w, out):
    for i in range(w.size):
        out[i] = _contact_force_sequential(data, state, w[i])


@jit
def _dissipated_rows(data, rows, out):
    for i in range(out.size):
        out[i] = dissipated_energy(data, rows[i])


@jit
def hertz_contact_time(v1_star):
    """Duration of a Hertz impact at V1*, in the law's time unit omega_c/V_c (-).

    Parameters
    ----------
    v1_star : float
        Normalised impact speed V1/V_c (-), > 0.

    Returns
    -------
    float
        tau_c (-); in seconds t_c = tau_c omega_c/V_c. NaN for V1* <= 0, infinite or NaN (a jit
        function: it never raises).

    Notes
    -----
    tau_c = 2 I V1*^(-1/5), I = int_0^1 (1 - x^2.5)^(-1/2) dx = Gamma(7/5) Gamma(1/2)/Gamma(9/10):
    the Hertz impact (JGM eqs 14, 19) in the normalised time tau = t V_c/omega_c, equal to the
    classic t_c = 2.868 (m'^2/(R' E'^2 V1))^(1/5). The JG contact lasts somewhat longer. Use it to
    choose a time step (docs/model.md section 10); also exported as
    :func:`fastrest.jit.hertz_contact_time`.

    Examples
    --------
    >>> from fastrest.force_law import hertz_contact_time
    >>> round(hertz_contact_time(1.0), 6)
    2.943275
    >>> round(hertz_contact_time(10.0), 6)
    1.857081
    """
    v = np.float64(v1_star)
    if not (v > 0.0 and v < math.inf):  # tau_c would be inf (V1* = 0) or 0 (V1* = inf)
        return math.nan
    return 2.0 * _HERTZ_HALF_TIME * v ** -0.2


_HERTZ_HALF_TIME = math.gamma(1.4) * math.sqrt(math.pi) / math.gamma(0.9)


#: Below this V1* an impact is integrated in scaled units (:func:`impact_in_time`).
SCALE_BELOW = 2.0**-5


@jit
def _law_formula(data, w):
    """P*(w) of the loading law by its formulas: Hertz up to 1.9 (eq 14), eq (9) above (the
    hardening law of ``data.law``/``data.et_ratio``, :func:`fastrest.loading.p_star_above`)."""
    if w <= W_SWITCH:
        return w * math.sqrt(w)
    return p_star_above(data.law, w, data.eps_y, data.nu, c_of_nu(data.nu), area_exponent(data.eps_y), data.et_ratio)


@jit
def _overshoot_force(data, state, w):
    """Virgin loading past the law's end ``data.w_max`` during :func:`impact_in_time`: eq (9)
    itself (Hertz up to 1.9), the law's analytic continuation. A step near the maximum
    interference of an impact at a speed the model accepts overshoots it by O(dt^2); the force
    there is the formula's, as for every other speed, instead of NaN."""
    p = _law_formula(data, w)
    _, delta = _unloading.residual(data.model, w, w - 1.0, p, data.eps_y, data.nu, data.law, data.et_ratio)
    state[0] = w
    state[1] = p
    state[2] = w - delta  # as the law writes it (w_res* to rounding)
    state[3] = delta
    return p


@jit
def impact_in_time(data, v1_star, steps_per_contact, locate_switch, state):
    """One impact integrated in time with velocity Verlet and :func:`contact_force`.

    Normalised equation of motion: d^2w/dtau^2 = -(5/4) P*(w), tau = t V_c/omega_c, from w = 0 at
    speed V1*; the step is ``hertz_contact_time(v1_star) / steps_per_contact``. With
    ``locate_switch`` the step that crosses w = 1.9 on virgin loading (where the JG law jumps by
    ~0.16 %) is split there, which keeps the scheme second order; without, it is first order.

    The caller checks that V1* reaches w_m* <= ``data.w_max`` (:meth:`ContactLaw.impact`); a step
    that still passes ``data.w_max`` on virgin loading (the scheme overshoots the maximum
    interference by O(dt^2)) takes the law's formula there (:func:`_overshoot_force`). Below
    :data:`SCALE_BELOW` (Hertz contact only, w_m* < 1/16) the impact is integrated in units scaled
    by powers of two, w = 2^(4k) x, tau = 2^(-k) s, V1* = 2^(5k) V' with V' in (2^-10, 2^-5]: the
    Hertz law is invariant under it and the scaling is exact, so tiny speeds (down to the smallest
    double) integrate without forces underflowing.

    Returns (e, w_max, steps): rebound speed over impact speed, largest interference, steps taken;
    e is NaN if the force was NaN (a NaN input, or the unloading model's end passed). ``state``
    (STATE_SIZE) is reset and left as the contact's final history.
    """
    for k in range(STATE_SIZE):
        state[k] = 0.0
    scale = 0
    if v1_star < SCALE_BELOW:
        scale = int(math.ceil(math.log2(v1_star) / 5.0)) + 1
        while math.ldexp(v1_star, -5 * scale) > SCALE_BELOW:  # log2's rounding
            scale += 1
    v0 = math.ldexp(v1_star, -5 * scale)
    dt = hertz_contact_time(v0) / steps_per_contact
    w_end = data.w_max
    w = 0.0
    v = v0
    a = 0.0
    n = 0
    e = np.nan
    while n < 1000 * steps_per_contact:
        n += 1
        h = dt
        w_new = w + v * h + 0.5 * a * h * h
        if locate_switch and w < W_SWITCH and w_new > W_SWITCH and w >= state[0]:
            # land exactly on w = 1.9 (the root of w + v t + a t^2/2 = 1.9 in (0, h)), then restart
            # from there with the JG side's acceleration
            c = w - W_SWITCH
            disc = v * v - 2.0 * a * c
            t1 = -2.0 * c / (v + math.sqrt(disc))
            a1 = -1.25 * _contact_force_sequential(data, state, W_SWITCH)
            v += 0.5 * (a + a1) * t1
            w = W_SWITCH
            a = -1.25 * (P_table_forward(data, np.nextafter(W_SWITCH, math.inf)) if w_end > W_SWITCH
                         else _law_formula(data, np.nextafter(W_SWITCH, math.inf)))
            h = dt - t1
            w_new = w + v * h + 0.5 * a * h * h
        if w_new > w_end and w_new > state[0] and w_new > W_SWITCH:
            p = _overshoot_force(data, state, w_new)
        elif state[0] > w_end:  # unloading from an overshoot: the law refuses such a row; its branch
            p = elastic_back(state[0], state[1], state[3], w_new)
        else:
            p = _contact_force_sequential(data, state, w_new)
        a_new = -1.25 * p
        v += 0.5 * (a + a_new) * h
        w = w_new
        a = a_new
        if p != p:
            break  # NaN: the interference it tried is returned
        if p == 0.0 and v < 0.0 and n > 1:
            e = -v / v0
            break
    w_top = state[0] if e == e else w
    if scale != 0:
        for k in (0, 2, 3):
            state[k] = math.ldexp(state[k], 4 * scale)
        state[1] = math.ldexp(state[1], 6 * scale)
        w_top = math.ldexp(w_top, 4 * scale)
    return e, w_top, n


class ContactLaw:
    """The time-domain contact law of one material and unloading model (see the module doc).

    Build with :func:`contact_law` (normalised) or :meth:`fastrest.Impact.contact_law`
    (dimensional: interferences in m, forces in N), which validate their inputs; the constructor
    itself does not. Instances pickle.

    Parameters
    ----------
    eps_y, nu : float
        Material (-): eps_y = Sy/E' > 0, 0 <= nu < 0.5.
    unloading : str
        Unloading model name (``"jcg"``, ``"etsion"``, ``"brake"``).
    extrapolate : bool
        Whether the law was built past w* = 425 (used in error messages).
    data : ForwardData
        The material's forward map, from :func:`fastrest.forward.forward_data`.
    omega_c : float, optional
        Interference unit (m), default 1.0 (normalised).
    P_c : float, optional
        Force unit (N), default 1.0 (normalised).

    Attributes
    ----------
    eps_y, nu : float
        Material (-).
    unloading : str
        Unloading model name.
    et_ratio : float
        Tangent modulus over Young's modulus Et/E (-) of the loading law (0: elastic-perfectly plastic).
    loading : str
        Loading law name (:mod:`fastrest.loading`): ``"jackson-green"`` or ``"ghaednia"``.
    w_max : float
        Largest interference w* = omega/omega_c the law serves (-).
    omega_c, P_c : float
        Units of :meth:`force`: its interferences are divided by ``omega_c`` and its forces
        multiplied by ``P_c`` (1.0 and 1.0 for a normalised law).
    data : ForwardData
        For :func:`fastrest.jit.contact_force` in Numba code.

    Notes
    -----
    The Jackson-Green loading law (JGM eqs 8-15), or Ghaednia et al.'s (2019) with strain
    hardening (:mod:`fastrest.loading`), with elastic unloading and reloading (eq 32) through the
    residual interference of the unloading model (eq 35, eqs 33-34 or Brake's); see the module
    docstring and docs/model.md section 10. The repr shows ``et_ratio`` where it is not 0 and
    ``loading`` where it is not the one ``et_ratio`` picks.

    Examples
    --------
    >>> import fastrest
    >>> law = fastrest.contact_law(0.005, 0.33, w_max=30.0)
    >>> law
    ContactLaw(eps_y=0.005, nu=0.33, unloading='jcg', w_max=30.0)
    >>> fastrest.contact_law(0.005, 0.33, "brake", w_max=30.0, et_ratio=0.01)
    ContactLaw(eps_y=0.005, nu=0.33, unloading='brake', w_max=30.0, et_ratio=0.01)
    >>> law.force([0.0, 10.0, 5.0, 10.0]).round(6)  # load, unload, reload
    array([ 0.      , 25.647583,  2.401153, 25.647583])
    """

    def __init__(self, eps_y: float, nu: float, unloading: str, extrapolate: bool, data: Any, omega_c: float = 1.0,
                 P_c: float = 1.0) -> None:
        self.eps_y, self.nu, self.unloading, self.extrapolate = eps_y, nu, unloading, extrapolate
        self.data, self.omega_c, self.P_c = data, float(omega_c), float(P_c)
        self.w_max = data.w_max
        self.et_ratio = float(data.et_ratio)
        self.loading = _loading.NAMES[data.law]

    def __repr__(self) -> str:
        units = "" if self.omega_c == 1.0 and self.P_c == 1.0 else f", omega_c={self.omega_c!r} m, P_c={self.P_c!r} N"
        # hardening shown only where it is not the default (existing reprs, and doctests, unchanged)
        hard = f", et_ratio={self.et_ratio!r}" if self.et_ratio != 0.0 else ""
        if self.loading != resolve_loading(None, self.et_ratio).name:
            hard += f", loading={self.loading!r}"
        return (f"ContactLaw(eps_y={self.eps_y!r}, nu={self.nu!r}, unloading={self.unloading!r}, "
                f"w_max={self.w_max!r}{hard}{units})")

    def new_state(self, n: int | None = None) -> NDArray[np.float64]:
        """Zeros: the history of ``n`` virgin contacts, for :func:`contact_force` and :meth:`force`.

        Parameters
        ----------
        n : int, optional
            Number of contacts, a whole number in [0, 1e9]; None (default): one contact.

        Returns
        -------
        ndarray
            float64 zeros of shape (n, :data:`STATE_SIZE`), or (:data:`STATE_SIZE`,) for ``n=None``.

        Raises
        ------
        TypeError
            ``n`` is not a number.
        ValueError
            ``n`` is not a whole number in [0, 1e9].

        Examples
        --------
        >>> import fastrest
        >>> law = fastrest.contact_law(0.005, 0.33, w_max=30.0)
        >>> law.new_state(), law.new_state(3).shape
        (array([0., 0., 0., 0.]), (3, 4))
        """
        return np.zeros(STATE_SIZE if n is None else (check_state_count(n), STATE_SIZE))

    def force(self, interference: ArrayLike, state: NDArray[np.float64] | None = None) -> float | NDArray[np.float64]:
        """Forces along a path of interferences in time order, from a virgin contact.

        Parameters
        ----------
        interference : array_like
            Interferences in time order: w* (-) for a normalised law, omega (m) for one from
            :meth:`fastrest.Impact.contact_law`. Values <= 0 are gaps (force 0).
        state : ndarray, optional
            A contact's history (:meth:`new_state`) to start from instead of a virgin contact;
            updated in place.

        Returns
        -------
        ndarray
            P* (-), or P (N) for a dimensional law, at each point.

        Raises
        ------
        TypeError
            Non-numbers.
        ValueError
            NaN or infinite interference, or one past the law's end (the message names it); a
            ``state`` that is not a writeable C-contiguous float64 array of shape
            (:data:`STATE_SIZE`,), or no history of this law (as :meth:`dissipated_energy`).

        Notes
        -----
        Runs :func:`contact_force` (JGM eqs 9, 14 loading, eq 32 unloading) along the path.

        Examples
        --------
        >>> import fastrest
        >>> law = fastrest.contact_law(0.005, 0.33, w_max=30.0)
        >>> law.force([0.0, 1.0, 10.0, 5.0, 0.5]).round(6)  # 0.5 is below w_res*: separated
        array([ 0.      ,  1.      , 25.647583,  2.401153,  0.      ])
        """
        x = as_float_array(interference, "interference")
        w = np.ascontiguousarray(x, dtype=np.float64).ravel() / self.omega_c
        bad = ~np.isfinite(w)
        if bad.any():
            raise ValueError(f"interference must be finite; got {float(w[bad][0] * self.omega_c)!r}")
        if state is None:
            state = self.new_state()
        else:
            if not (isinstance(state, np.ndarray) and state.dtype == np.float64 and state.shape == (STATE_SIZE,)
                    and state.flags.c_contiguous):
                raise ValueError(f"state must be a float64 array of shape ({STATE_SIZE},) (ContactLaw.new_state())")
            if not state.flags.writeable:
                raise ValueError("state is updated in place (the contact's history): it must be a writeable "
                                 "array; got a read-only one (pass state.copy())")
            self._check_history(state.reshape(1, STATE_SIZE), state.shape)
        out = np.empty(w.size)
        _force_path(self.data, state, w, out)
        if np.isnan(out).any():
            i = int(np.flatnonzero(np.isnan(out))[0])
            if w[i] > self.w_max and self.w_max < self._full_limit():
                raise ValueError(f"interference = {float(w[i] * self.omega_c)!r} is beyond this law's w_max = "
                                 f"{self.w_max!r} (in units of omega_c = {self.omega_c!r}): build it with a "
                                 "larger w_max (contact_law(..., w_max=...))")
            raise_interference_out_of_range(max(w[i], self.w_max * (1 + 1e-15)), self.eps_y, self.nu,
                                            self.extrapolate, "interference", self.unloading)
        return (out * self.P_c).reshape(x.shape)

    def dissipated_energy(self, state: ArrayLike) -> float | NDArray[np.float64]:
        """Energy one contact, or many, has dissipated so far, from its history (:func:`dissipated_energy`).

        Parameters
        ----------
        state : array_like
            A contact's history row (:data:`STATE_SIZE`,) or rows (..., :data:`STATE_SIZE`), as
            :meth:`force` or :func:`contact_force` with this law left them (not changed).

        Returns
        -------
        float or ndarray
            The dissipated energy of each row: in units of U_c (-) for a normalised law
            (``omega_c`` = ``P_c`` = 1), in joules for a dimensional one
            (:meth:`fastrest.Impact.contact_law`: D (2/5) P_c omega_c, equal to D U_c of
            :class:`fastrest.Impact` to rounding). A float for one row, else an array of the
            rows' shape without the last axis.

        Raises
        ------
        TypeError
            Non-numbers.
        ValueError
            A last axis that is not :data:`STATE_SIZE` long; a row that is no history of this
            law (NaN: history lost; w_max < 0 or past the law's ``w_max``; the message names the
            row).

        Notes
        -----
        D = F(w_max) - P*(w_max) (w_max - w_res*), JGM eqs (25), (32), (38): see
        :func:`dissipated_energy`. It depends on the largest interference only (the elastic
        branch returns what it stores).

        Examples
        --------
        >>> import fastrest
        >>> law = fastrest.contact_law(0.005, 0.33, w_max=30.0)
        >>> state = law.new_state()
        >>> law.force([6.549856322605, 0.0], state).round(6)  # loaded to w_m* of V1* = 10, separated
        array([14.530473,  0.      ])
        >>> round(law.dissipated_energy(state), 6)  # (1 - e^2) V1*^2, in units of U_c
        31.320232
        """
        x = as_float_array(state, "state")
        if x.ndim == 0 or x.shape[-1] != STATE_SIZE:
            raise ValueError(f"state must have a last axis of {STATE_SIZE} values (ContactLaw.new_state()); "
                             f"got shape {x.shape}")
        rows = kernel_array(x).reshape(-1, STATE_SIZE)  # a read-only state: copied, no new signature
        self._check_history(rows, x.shape)
        out = np.empty(rows.shape[0])
        _dissipated_rows(self.data, rows, out)
        if np.isnan(out).any():
            self._refuse_history(rows, x.shape, int(np.flatnonzero(np.isnan(out))[0]))
        unit = 1.0 if self.omega_c == 1.0 and self.P_c == 1.0 else 0.4 * self.P_c * self.omega_c
        out *= unit
        return float(out[0]) if x.ndim == 1 else out.reshape(x.shape[:-1])

    def _check_history(self, rows, shape):
        """Refuse a state row that is no history of this law (:meth:`force` and
        :meth:`dissipated_energy`, one rule): w_max = state[0] NaN, < 0 or past the law's w_max,
        or P*(w_max) = state[1] NaN (the history was lost), or w_max > 0 with delta = state[3] <= 0
        (delta is set with w_max at every loading step)."""
        w_top, p_top, delta = rows[:, 0], rows[:, 1], rows[:, 3]
        bad = ~((w_top >= 0.0) & (w_top <= self.w_max) & (p_top == p_top) & ((delta > 0.0) | (w_top == 0.0)))
        if bad.any():
            self._refuse_history(rows, shape, int(np.flatnonzero(bad)[0]))

    def _refuse_history(self, rows, shape, i):
        where = "state" if len(shape) == 1 else f"state row {tuple(int(j) for j in np.unravel_index(i, shape[:-1]))}"
        raise ValueError(f"{where} = {rows[i].tolist()} is no history of this law: w_max = state[0] must be "
                         f"finite, >= 0 and <= the law's w_max = {self.w_max!r} (in units of omega_c), "
                         "P*(w_max) = state[1] a number (a NaN row: the contact's history was lost; start "
                         "again from ContactLaw.new_state()), and delta = state[3] > 0 once w_max > 0 (a row "
                         "with w_max > 0 and delta = 0 was written by fastrest 0.2 or earlier while its "
                         "contact was loading: it is refused, not read as a wrong branch)")

    def _full_limit(self):
        """The largest w* a law of this material, model and loading law could serve."""
        return interference_limit(self.eps_y, self.nu, extrapolate=self.extrapolate, unloading=self.unloading,
                                  et_ratio=self.et_ratio, loading=self.loading)

    def _raise_too_fast(self, v):
        """The ValueError for a V1* whose maximum interference w_m* (JGM eq 29) passes the law's end."""
        if self.w_max < self._full_limit():
            v_top = math.sqrt(f_star_kernel(self.w_max, self.eps_y, self.nu, self.data.law, self.data.et_ratio))
            raise ValueError(f"v1_star = {v!r} gives w_m* beyond this law's w_max = {self.w_max!r}: it takes "
                             f"0 < v1_star <= {v_top:.10g} (V1*^2 = F(w_max), JGM eq 29); build the law with a "
                             "larger w_max (contact_law(..., w_max=...))")
        raise_out_of_range(v, self.eps_y, self.nu, self.extrapolate, "v1_star", unloading=self.unloading,
                           et_ratio=self.et_ratio, loading=self.loading)

    def impact(self, v1_star: float, *, steps_per_contact: int = 2000, locate_switch: bool = True) -> dict[str, Any]:
        """e of one impact at V1* integrated in time with this law (:func:`impact_in_time`).

        For checking a time step: compare with :func:`fastrest.curve` ``.e(v1_star)``, or
        :func:`fastrest.direct.e_exact` with the law's ``et_ratio`` and ``loading``.

        Parameters
        ----------
        v1_star : float
            Normalised impact speed V1/V_c (-), finite and > 0, up to the speed whose w_m* is the
            law's ``w_max`` (:func:`fastrest.limit` for a law built to the model's
            end). Speeds below 2^-5 are integrated in scaled units (exact for the Hertz law), so
            tiny ones (1e-300) give e = 1 to the scheme's accuracy.
        steps_per_contact : int, optional
            Velocity-Verlet steps per Hertz contact duration (:func:`hertz_contact_time`), a whole
            number in [10, 1e8]; default 2000.
        locate_switch : bool, optional
            Split the step that crosses w = 1.9 on virgin loading there (second order; default
            True). False: a plain fixed-step loop, first order at the force jump.

        Returns
        -------
        dict
            ``"e"`` (rebound over impact speed, -), ``"omega_m_star"`` (largest interference w*
            the integration reached, -: the energy balance's w_m* plus the scheme's O(dt^2)
            error, so near the limit speed it can pass ``w_max`` slightly, where the step takes
            the law's formula), ``"steps"`` (int) and the contact's final ``"state"`` (ndarray).

        Raises
        ------
        TypeError
            ``v1_star`` or ``steps_per_contact`` not a single real number; ``locate_switch`` not
            True or False.
        ValueError
            v1_star not finite and > 0, or past the speed whose w_m* (JGM eq 29) reaches the law's
            end ``w_max`` (the message names that speed; the same rule as :mod:`fastrest.direct`,
            so every speed the direct solver and the curves accept integrates, whatever
            ``steps_per_contact``); ``steps_per_contact`` not a whole number in [10, 1e8].

        Notes
        -----
        The normalised equation of motion d^2w/dtau^2 = -(5/4) P*(w) (JGM eqs 24, 28:
        tau = t V_c/omega_c); integrated finely enough it reproduces the e of the energy balance,
        eqs (29), (38) (errors per step count: docs/model.md section 10).

        Examples
        --------
        >>> import fastrest
        >>> law = fastrest.contact_law(0.005, 0.33, w_max=30.0)
        >>> r = law.impact(10.0, steps_per_contact=1000)
        >>> round(r["e"], 6), round(fastrest.direct.e_exact(10.0, 0.005, 0.33), 6)
        (0.828732, 0.828733)
        """
        v = real_scalar(v1_star, "v1_star")
        if not (math.isfinite(v) and v > 0.0):
            raise ValueError(f"v1_star must be finite and > 0; got {v!r}")
        n = real_scalar(steps_per_contact, "steps_per_contact")
        if not (n.is_integer() and 10 <= n <= 1e8):
            raise ValueError(f"steps_per_contact must be a whole number in [10, 1e8]; got {steps_per_contact!r}")
        if not omega_m_kernel(v, self.eps_y, self.nu, self.w_max, self.data.law, self.data.et_ratio) >= 0.0:  # the direct solver's rule
            self._raise_too_fast(v)
        state = self.new_state()
        e, wm, steps = impact_in_time(self.data, v, int(n), check_bool(locate_switch, "locate_switch"), state)
        if not e == e:
            raise ValueError(f"the impact at V1* = {v!r} with {int(n)} steps per contact left the law "
                             f"(interference {wm!r}, state {state.tolist()}): the unloading model's "
                             "residual is undefined there; take more steps")
        return {"e": float(e), "omega_m_star": float(wm), "steps": int(steps), "state": state}


def contact_law(eps_y: float, nu: float, unloading: str = "jcg", *, w_max: float | None = None, extrapolate: bool = False,
                omega_c: float = 1.0, P_c: float = 1.0, et_ratio: float = 0.0, loading: str | None = None) -> ContactLaw:
    """Build the time-domain :class:`ContactLaw` of one material (normalised: w = omega/omega_c,
    P* = P/P_c).

    Parameters
    ----------
    eps_y : float
        Sy/E' (-), > 0 (validated 0.0005-0.01).
    nu : float
        Poisson's ratio of the yielding material, 0 <= nu < 0.5 (validated 0.2-0.45).
    unloading : {"jcg", "etsion", "brake"}
        Unloading model (residual interference), JGM eq (35), eqs (33)-(34), or Brake's.
    w_max : float, optional
        Largest interference w* to serve (-); only the cells up to it are built. Default: the
        model's end (w* = 425, or a/R = 1 / the unloading model's end if earlier).
    extrapolate : bool
        Allow w* past 425 up to a/R = 1 (and the unloading model's end).
    omega_c : float, optional
        Interference unit (m), finite and > 0: :meth:`ContactLaw.force` divides its input by it.
        Default 1.0 (a normalised law); :meth:`fastrest.Impact.contact_law` passes the impact's.
    P_c : float, optional
        Force unit (N), finite and > 0: :meth:`ContactLaw.force` multiplies P* by it. Default 1.0.
    et_ratio : float, optional
        Tangent modulus over Young's modulus Et/E (-) of the yielding material, 0 <= et_ratio < 1;
        default 0 (elastic-perfectly plastic). In Numba code from two bodies' properties:
        :func:`fastrest.jit.yield_et_ratio`.
    loading : {None, "jackson-green", "ghaednia"}, optional
        The loading law (:mod:`fastrest.loading`); None (default) picks Jackson-Green for
        et_ratio = 0 and Ghaednia et al. (2019) otherwise (equal bit for bit at 0).

    Returns
    -------
    ContactLaw

    Raises
    ------
    TypeError
        eps_y, nu, w_max, omega_c, P_c or et_ratio not a single real number; ``extrapolate`` not
        True or False.
    ValueError
        eps_y not finite and > 0; nu outside [0, 0.5); an unknown ``unloading`` or ``loading``;
        et_ratio outside [0, 1), or > 0 with ``loading="jackson-green"``; w_max negative, not
        finite, or past the model's end (w* = 425, a/R = 1 or the unloading model's end: the
        message names it); omega_c or P_c not finite and > 0.

    Warns
    -----
    ValidityWarning
        eps_y or nu outside the validated 0.0005 <= eps_y <= 0.01, 0.2 <= nu <= 0.45; JCG or
        Etsion unloading with et_ratio > 0 (fitted to elastic-perfectly plastic finite elements;
        Brake's is the peers' pairing with hardening).

    Notes
    -----
    JGM eqs (8)-(15) for loading (Ghaednia et al. 2019 with hardening), (32) with (35), (33)-(34)
    or Brake's rule for unloading, built on :func:`fastrest.forward.forward_data` (docs/model.md
    section 10).

    Examples
    --------
    >>> import fastrest
    >>> law = fastrest.contact_law(0.005, 0.33, "etsion")
    >>> law.unloading, law.w_max
    ('etsion', 425.0)
    >>> round(float(law.force([10.0])[0]), 6)
    25.647583
    """
    eps_y = real_scalar(eps_y, "eps_y")
    nu = real_scalar(nu, "nu")
    extrapolate = check_bool(extrapolate, "extrapolate")
    check_eps_y(eps_y)
    check_nu(nu)
    omega_c = float(check_finite_positive(real_scalar(omega_c, "omega_c"), "omega_c", "(m, or 1.0 for a normalised law)"))
    P_c = float(check_finite_positive(real_scalar(P_c, "P_c"), "P_c", "(N, or 1.0 for a normalised law)"))
    model = _unloading.get(unloading)
    et_ratio = real_scalar(et_ratio, "et_ratio")
    law = resolve_loading(loading, et_ratio)
    lim = float(w_upper_model(eps_y, nu, bool(extrapolate), model.code, law.code, et_ratio))
    if w_max is None:
        w_max = lim
    else:
        w_max = real_scalar(w_max, "w_max")
        if not (w_max >= 0.0 and math.isfinite(w_max)):
            raise ValueError(f"w_max must be finite and >= 0 (normalised interference); got {w_max!r}")
        if w_max > lim:
            raise_interference_out_of_range(w_max, eps_y, nu, extrapolate, "w_max", model.name)
    data = forward_data(eps_y, nu, model.name, w_max=w_max, extrapolate=bool(extrapolate), et_ratio=et_ratio,
                        loading=law.name)
    return ContactLaw(eps_y, nu, model.name, bool(extrapolate), data, omega_c, P_c)
