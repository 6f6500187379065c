"""Impact of a rigid flat on a rough surface of JGM asperities (issue 6).

A rigid flat of mass M moves at V1 towards a rough surface covered with spherical asperities
(summits) of radius R_a, made of the surface's material. Every asperity follows the JGM single-
sphere law on loading and unloads elastically; asperities do not interact and the bulk under them
does not deform (Greenwood-Williamson assumptions). The derivation is in docs/rough.md; in short,
with U_c, P_c, omega_c of one asperity (:class:`fastrest.Impact` with radius R_a, rigid flat):

* summit heights z_i are measured upwards from the mean summit plane; the flat's surface is at
  distance d above that plane; asperity i touches when z_i > d and its interference is
  omega_i = z_i - d, w_i = omega_i / omega_c;
* deepest approach d_min: (1/2) M V1^2 = U_c sum_i F(w_i)   (F: :func:`fastrest.forward.F_forward`);
  the sum grows monotonically as d falls, with slope -sum_i P_c P*(w_i) (the total force);
* energy returned: U_c sum_i R(w_i), R = P*(w)(w - w_res*(w)) (JGM eq 38 with eq 35 or 33), so
  e_s^2 = sum_i R(w_i) / ((1/2) M V1^2); the code evaluates e_s^2 = 1 - sum_i L(w_i)/(V1/V_c)^2
  with L = F - R without cancellation (so an all-elastic impact gives e_s = 1 exactly).

Two descriptions of a surface:

* explicit summit heights (array; :func:`gaussian_summits` draws a Gaussian set);
* statistical (Greenwood & Williamson 1966): summit density eta (1/m^2), height standard deviation
  sigma (m), nominal area A_n (m^2), N = eta A_n summits with a Gaussian (default) or user-supplied
  height pdf; sums become N times integrals over the contacting heights, done by composite
  Gauss-Legendre quadrature split at w* = 0, 1, 1.9.

The inner loops are ``@njit(parallel=True)`` functions calling the public :mod:`fastrest.forward`
kernels, the same path a user's own Numba code would take.
"""
import math
import numbers
import sys
import warnings
from collections import namedtuple
from dataclasses import dataclass, field, fields

import numba as nb
import numpy as np

from . import forward as fw
from ._threads import run_parallel
from ._validation import (OMEGA_M_STAR_MAX, ExtrapolationWarning, ValidityWarning, as_float_array,
                          check_bool, check_finite_positive, real_scalar, warn, warn_if_outside_validated)
from .contact import W_SWITCH
from .interpolation import GAUSS_U, chebyshev_nodes, fit_cells, cell_polynomial
from .limits import interference_limit_message
from .materials import Impact, Material
from .unloading import unloading_code

__all__ = ["RoughSurface", "GreenwoodWilliamson", "RoughImpact", "gaussian_summits", "sweep",
           "surface_from_params", "reference_impact"]

# --- numerical constants ------------------------------------------------------------------------

#: Asperities per block of the explicit sums. Partial sums are taken per fixed block and added in
#: block order, so results do not depend on the number of threads (bit-identical everywhere).
BLOCK = 8192
#: Gauss-Legendre order per quadrature panel of the statistical model.
GL_ORDER = 16
_GL_X, _GL_W = np.polynomial.legendre.leggauss(GL_ORDER)
#: Widest quadrature panel in standardised height s = z / sigma; panels not starting at w* = 0 are
#: also at most a factor 2 wide in w* (F, P* are powers of w*). Chosen by measurement against
#: scipy.integrate.quad (tests/test_rough.py).
PANEL_S = 0.5
#: Gaussian tail cut: heights are integrated up to s_cut = sqrt(max(s_d, 0)^2 + 2 TAIL_L), where the
#: integrand has fallen by exp(-TAIL_L) ~ 3e-20 relative to its value at max(s_d, 0), and (when the
#: flat is below them) from s = -sqrt(2 TAIL_L), below which the pdf is < exp(-TAIL_L) phi(0).
TAIL_L = 45.0
#: Cells per sigma of a tabulated user pdf (degree-5 Chebyshev cells).
PDF_CELLS_PER_SIGMA = 64
_INV_SQRT_2PI = 1.0 / math.sqrt(2.0 * math.pi)
_MAX_ITER = 200
#: Fewest summits (N = eta A_n) of a statistical surface: below it the flat would have to sink
#: tens of standard deviations into the tail of the height distribution to stop.
MIN_SUMMITS = 1e-6
MAX_SUMMITS = 1e30
#: Range of sigma / omega_c (the plasticity index squared) where the statistical model is computed:
#: heights enter the quadrature as w* = (s - s_d) sigma/omega_c, which loses the resolution of s
#: (relative 1e-16 w*/(sigma/omega_c)) when sigma/omega_c is tiny.
RHO_W_RANGE = (1e-6, 1e12)


#: Gaussian heights: the density exp(-s^2/2) underflows soon after s = 37 (1e-298).
S_UNDERFLOW = 36.0
#: The Hertz estimate (the start of every statistical JG solve) stops at this many times the w*
#: where the law ends (a/R = 1): JG summits sink deeper than Hertz ones, so beyond it so does the impact.
HERTZ_CAP = 4.0


def _bad_energy_word(x):
    return "too large" if not x < math.inf else "too small"

# status codes of the solvers
_OK, _NEEDS_TABLE, _FAILED = 0, 1, 2

GWData = namedtuple("GWData", ["kind", "n_total", "rho_w", "s_lo", "s_hi", "inv_h", "pdf_rows"])
GWData.__doc__ = """Numba-friendly statistical surface. kind 0: Gaussian heights, 1: tabulated pdf of
s = z/sigma on uniform cells from s_lo (1/h = inv_h) to s_hi; n_total = eta A_n; rho_w = sigma/omega_c
(w* per unit of s)."""


# =================================================================================================
# Explicit summits
# =================================================================================================

@nb.njit(cache=True)
def _hertz_fp(w):
    p = w * math.sqrt(w)
    return w * p, p


@nb.njit(parallel=True, cache=True)
def _explicit_fp(data, h, x, hertz):
    """(sum F, sum P*) over asperities with w_i = h_i + x > 0, in fixed blocks (deterministic).

    P* (the Newton slope) from the table; ``hertz``: F = w^2.5, P* = w^1.5 (no table).
    """
    n = h.size
    nblock = (n + BLOCK - 1) // BLOCK
    part = np.zeros((nblock, 2))
    for b in nb.prange(nblock):
        sf = 0.0
        sp = 0.0
        for i in range(b * BLOCK, min(n, (b + 1) * BLOCK)):
            w = h[i] + x
            if w > 0.0:
                if hertz:
                    f, p = _hertz_fp(w)
                else:
                    f, p = fw.FP_table_forward(data, w)  # P* (Newton slope) from its table
                sf += f
                sp += p
        part[b, 0] = sf
        part[b, 1] = sp
    sf = 0.0
    sp = 0.0
    for b in range(nblock):
        sf += part[b, 0]
        sp += part[b, 1]
    return sf, sp


@nb.njit(parallel=True, cache=True)
def _explicit_full(data, h, x, out):
    """out = [sum F, sum P*, sum R, sum L, n_contact, n_yielded] at approach x (deterministic blocks)."""
    n = h.size
    nblock = (n + BLOCK - 1) // BLOCK
    part = np.zeros((nblock, 6))
    for b in nb.prange(nblock):
        acc = np.zeros(6)
        for i in range(b * BLOCK, min(n, (b + 1) * BLOCK)):
            w = h[i] + x
            if w > 0.0:
                f, p, r, loss = fw.forward_values(data, w)
                acc[0] += f
                acc[1] += p
                acc[2] += r
                acc[3] += loss
                acc[4] += 1.0
                if w > 1.0:
                    acc[5] += 1.0
        for k in range(6):
            part[b, k] = acc[k]
    for k in range(6):
        out[k] = 0.0
    for b in range(nblock):
        for k in range(6):
            out[k] += part[b, k]


@nb.njit(cache=True)
def _explicit_solve(data, h, energy, x0, hertz, w_cap, clamp):
    """Approach x (= w* of the tallest summit) with sum F(h_i + x) = energy.

    Newton's method on G(x)^0.4 = energy^0.4 (G = sum F; exact in one step for one Hertzian summit),
    slope from the total force (dG/dx = (5/2) sum P*), safeguarded by bisection on the bracket
    G(lo) < energy <= G(hi). Starts at x0 (> 0). Returns (status, x, w_needed): status 1 when a
    trial x lies beyond w_cap (<= data.w_max; w_needed: the x asked for). With ``clamp`` (w_cap is
    the model's limit, no larger table can help) a trial beyond it is moved to w_cap first, and
    status 1 then means the solution itself is beyond the limit.
    """
    target = energy**0.4
    lo = 0.0
    hi = np.inf
    x = x0
    dx_prev = np.inf
    for _ in range(_MAX_ITER):
        if not hertz and x > w_cap:
            if not (clamp and lo < w_cap):
                return _NEEDS_TABLE, x, x
            x = w_cap
        g_sum, p_sum = _explicit_fp(data, h, x, hertz)
        if g_sum >= energy:
            hi = x
        else:
            lo = x
        if g_sum == energy:
            return _OK, x, x
        xn = np.nan
        if g_sum > 0.0 and p_sum > 0.0:
            xn = x - (g_sum**0.4 - target) * g_sum**0.6 / p_sum
            dx = abs(xn - x)
            # converged: a step at rounding level, or steps no longer shrinking quadratically
            if dx <= 4e-16 * x or (dx < 1e-12 * x and dx >= 0.5 * dx_prev):
                return _explicit_done(xn, hertz, w_cap)
            dx_prev = dx
        if not (xn > lo and xn < hi):
            xn = 0.5 * (lo + hi) if hi < np.inf else 2.0 * x
            if hi - lo <= 4e-16 * hi:
                return _explicit_done(xn, hertz, w_cap)
        x = xn
    return _FAILED, x, x


@nb.njit(cache=True)
def _explicit_done(x, hertz, w_cap):
    """Converged at x: fine unless a last step crossed the table's end (then ask for more)."""
    if not hertz and x > w_cap:
        return _NEEDS_TABLE, x, x
    return _OK, x, x


@nb.njit(cache=True)
def _explicit_impacts(data, h, energies, x0, hertz, w_cap, clamp, out):
    """Solve each impact energy (in units of U_c); out[:, k] = status, x, w_needed, sums (6)."""
    acc = np.empty(6)
    for k in range(energies.size):
        status, x, need = _explicit_solve(data, h, energies[k], x0[k], hertz, w_cap, clamp)
        out[0, k] = status
        out[1, k] = x
        out[2, k] = need
        if status == _OK and not hertz:
            _explicit_full(data, h, x, acc)
            for j in range(6):
                out[3 + j, k] = acc[j]


# =================================================================================================
# Statistical (Greenwood-Williamson) surfaces
# =================================================================================================

@nb.njit(cache=True)
def _pdf(g, s):
    """Probability density of the standardised summit height s = z / sigma."""
    if g.kind == 0:
        return math.exp(-0.5 * s * s) * _INV_SQRT_2PI
    if s < g.s_lo or s > g.s_hi:
        return 0.0
    i = int((s - g.s_lo) * g.inv_h)
    if i >= g.pdf_rows.shape[0]:
        i = g.pdf_rows.shape[0] - 1
    return cell_polynomial(g.pdf_rows, i, s)


@nb.njit(cache=True)
def _s_top(g, sd):
    """Upper end of the height integration for the flat at s_d = d / sigma."""
    if g.kind == 0:
        t = max(sd, 0.0)
        return math.sqrt(t * t + 2.0 * TAIL_L)
    return g.s_hi


@nb.njit(cache=True)
def _s_covered(g, w_cap):
    """Smallest s_d whose integration range stays within w* <= w_cap."""
    u = w_cap / g.rho_w  # largest (s - s_d) the table serves
    if g.kind == 1:
        return g.s_hi - u
    two_l = 2.0 * TAIL_L
    if u * u >= two_l:
        return math.sqrt(two_l) - u
    return (two_l - u * u) / (2.0 * u)


@nb.njit(cache=True)
def _gw_integrals(data, g, sd, hertz, full, w_cap, out):
    """Per-summit expectations at s_d: out = [E F, E P*, E R, E L, P(contact), P(w* > 1), w_top].

    Composite Gauss-Legendre in w* over the contacting heights, split at w* = 1 and 1.9; the panel
    starting at w* = 0 uses w* = b u^2 (F ~ w^2.5, P* ~ w^1.5 become polynomials in u); other
    panels are at most PANEL_S wide in s and a factor 2 wide in w*.
    """
    for k in range(7):
        out[k] = 0.0
    r = g.rho_w
    w_a = 0.0
    s_lo = g.s_lo if g.kind == 1 else -math.sqrt(2.0 * TAIL_L)  # Gaussian: also cut below
    if s_lo > sd:
        w_a = (s_lo - sd) * r
    w_b = (_s_top(g, sd) - sd) * r
    if not hertz and w_b > w_cap:
        w_b = w_cap  # rounding only: callers keep s_d >= _s_covered
    out[6] = w_b
    if not w_b > w_a:
        return
    hw = PANEL_S * r
    a = w_a
    for seg in range(3):
        if seg == 0:
            seg_end = 1.0
        elif seg == 1:
            seg_end = W_SWITCH
        else:
            seg_end = w_b
        if seg_end > w_b:
            seg_end = w_b
        if not seg_end > a:
            continue
        p = a
        while p < seg_end:
            if p == 0.0:
                q = min(seg_end, hw)
            else:
                q = min(seg_end, p + hw, 2.0 * p)
            if not q > p:  # a panel below the rounding of p: end the segment (no endless loop)
                q = seg_end
            yielded = p >= 1.0
            for j in range(GL_ORDER):
                if p == 0.0:
                    u = 0.5 * (1.0 + _GL_X[j])
                    w = q * u * u
                    wt = _GL_W[j] * q * u  # 0.5 W_j * 2 q u
                else:
                    c = 0.5 * (p + q)
                    hh = 0.5 * (q - p)
                    w = c + hh * _GL_X[j]
                    wt = hh * _GL_W[j]
                wt *= _pdf(g, sd + w / r) / r
                if hertz:
                    f, pf = _hertz_fp(w)
                    out[0] += wt * f
                    out[1] += wt * pf
                elif full:
                    f, pf, ret, loss = fw.forward_values(data, w)
                    out[0] += wt * f
                    out[1] += wt * pf
                    out[2] += wt * ret
                    out[3] += wt * loss
                    out[4] += wt
                    if yielded:
                        out[5] += wt
                else:
                    f, pf = fw.FP_table_forward(data, w)  # P* (Newton slope) from its table
                    out[0] += wt * f
                    out[1] += wt * pf
            p = q
        a = seg_end


@nb.njit(cache=True)
def _gw_solve(data, g, energy, s0, hertz, w_cap, clamp, buf):
    """s_d with N E[F] = energy; Newton on G^0.4 with bisection safeguard (see _explicit_solve).

    Returns (status, s_d, w_needed). Without ``hertz``, trial s_d below the coverage of w_cap
    return status 1 with the w* that would be needed (``clamp``: as in _explicit_solve).
    """
    n_tot = g.n_total
    r = g.rho_w
    target = energy**0.4
    s_cov = -np.inf
    if not hertz or w_cap > 0.0:  # the Hertz estimate too, when given a cap
        s_cov = _s_covered(g, w_cap)
        s_cov += 1e-12 * (1.0 + abs(s_cov))  # rounding margin
    lo = -np.inf   # G(lo) >= energy
    hi = np.inf    # G(hi) < energy
    if g.kind == 1:
        hi = g.s_hi  # no summit above: G = 0
    s = s0
    if s >= hi:
        s = hi - 0.5
    step = 0.5
    dx_prev = np.inf
    for _ in range(_MAX_ITER):
        if s < s_cov:
            if not (clamp and hi > s_cov):
                return _NEEDS_TABLE, s, (_s_top(g, s) - s) * r
            s = s_cov
        _gw_integrals(data, g, s, hertz, False, w_cap, buf)
        gs = n_tot * buf[0]
        if gs >= energy:
            lo = s
        else:
            hi = s
        if gs == energy:
            return _OK, s, buf[6]
        if lo == -np.inf or hi == np.inf:
            # no bracket yet: steps doubling away from the start, or Newton's step when it points
            # the same way and goes further (Newton alone creeps up a Gaussian tail, 2.5/s per step)
            if lo == -np.inf:
                sn = s - step
            else:
                sn = s + step
            if gs > 0.0 and buf[1] > 0.0:
                sn_newton = s + (gs**0.4 - target) * gs**0.6 / (n_tot * r * buf[1])
                if (lo == -np.inf and sn_newton < sn) or (hi == np.inf and sn_newton > sn):
                    sn = sn_newton
                    step *= 0.5
            step *= 2.0
            s = sn
            continue
        sn = np.nan
        scale = max(1.0, abs(s))
        if gs > 0.0 and buf[1] > 0.0:
            sn = s + (gs**0.4 - target) * gs**0.6 / (n_tot * r * buf[1])
            dx = abs(sn - s)
            if dx <= 4e-16 * scale or (dx < 1e-12 * scale and dx >= 0.5 * dx_prev):
                return _OK if sn >= s_cov else _NEEDS_TABLE, sn, (_s_top(g, sn) - sn) * r
            dx_prev = dx
        if not (sn > lo and sn < hi):
            sn = 0.5 * (lo + hi)
            if hi - lo <= 4e-16 * scale:
                return _OK if sn >= s_cov else _NEEDS_TABLE, sn, (_s_top(g, sn) - sn) * r
        s = sn
    return _FAILED, s, np.nan


@nb.njit(cache=True)
def _gw_one(data, g, energies, s0, hertz, w_cap, clamp, out, k):
    """Impact k: out[:, k] = status, s_d, w_needed, 7 expectations."""
    buf = np.empty(7)
    status, s, need = _gw_solve(data, g, energies[k], s0[k], hertz, w_cap, clamp, buf)
    out[0, k] = status
    out[1, k] = s
    out[2, k] = need
    if status == _OK and not hertz:
        _gw_integrals(data, g, s, False, True, w_cap, buf)
        for j in range(7):
            out[3 + j, k] = buf[j]


@nb.njit(parallel=True, cache=True)
def _gw_impacts(data, g, energies, s0, hertz, w_cap, clamp, out):
    """All impacts, in parallel (each is independent: results do not depend on threads)."""
    for k in nb.prange(energies.size):
        _gw_one(data, g, energies, s0, hertz, w_cap, clamp, out, k)


@nb.njit(cache=True)
def _gw_impacts_serial(data, g, energies, s0, hertz, w_cap, clamp, out):
    """All impacts in this thread (a single impact: no parallel start-up, no waiting for threads)."""
    for k in range(energies.size):
        _gw_one(data, g, energies, s0, hertz, w_cap, clamp, out, k)


# =================================================================================================
# Python API
# =================================================================================================

def gaussian_summits(n, sigma, seed=None):
    """``n`` summit heights (m) drawn from a normal distribution of mean 0 and standard deviation ``sigma``.

    Parameters
    ----------
    n : int
        Number of summits, >= 1.
    sigma : float
        Standard deviation of the heights (m), > 0.
    seed : int or numpy.random.Generator, optional
        Seed of ``numpy.random.default_rng``; the same seed gives the same heights.
    """
    if isinstance(n, bool) or not isinstance(n, numbers.Integral) or not 1 <= n <= 10**9:
        raise ValueError(f"n (number of summits) must be an integer in [1, 1e9]; got {n!r}")
    sigma = float(check_finite_positive(real_scalar(sigma, "sigma"), "sigma", "(m, standard deviation of summit heights)"))
    return np.random.default_rng(seed).normal(0.0, sigma, int(n))


@dataclass(frozen=True)
class GreenwoodWilliamson:
    """Statistical description of a rough surface (Greenwood & Williamson 1966).

    Parameters
    ----------
    eta : float
        Summit density (1/m^2), > 0.
    sigma : float, optional
        Standard deviation of summit heights (m), > 0. Required for Gaussian heights; with a user
        ``pdf`` it defaults to the pdf's standard deviation (computed).
    A_n : float
        Nominal (apparent) contact area (m^2), > 0. The surface has N = eta A_n summits.
    pdf : callable, optional
        Summit-height probability density p(z) (1/m) of heights z (m) above the mean summit plane,
        vectorised over a NumPy array. Default: Gaussian with standard deviation sigma. It is
        tabulated on ``support`` (64 degree-5 cells per sigma) and normalised to 1 there. For
        Dask sweeps it must be picklable (a module-level function).
    support : (float, float), optional
        Heights (m) outside which ``pdf`` is zero; required with ``pdf``.
    """

    eta: float
    sigma: float | None = None
    A_n: float = 1.0
    pdf: object = None
    support: tuple | None = None

    def __post_init__(self):
        # plain floats: an array or a string here would fail far from its cause
        for name in ("eta", "A_n") + (("sigma",) if self.sigma is not None else ()):
            object.__setattr__(self, name, real_scalar(getattr(self, name), name))
        check_finite_positive(self.eta, "eta", "(1/m^2, summit density)")
        check_finite_positive(self.A_n, "A_n", "(m^2, nominal area)")
        n = self.eta * self.A_n
        if not (MIN_SUMMITS <= n <= MAX_SUMMITS):
            raise ValueError(f"the surface has N = eta A_n = {n!r} summits (eta = {self.eta!r} 1/m^2, A_n = "
                             f"{self.A_n!r} m^2); N must be in [{MIN_SUMMITS:g}, {MAX_SUMMITS:g}]")
        if self.pdf is None:
            if self.sigma is None:
                raise ValueError("sigma (m, standard deviation of summit heights) is required")
            if self.support is not None:
                raise ValueError("support applies to a user pdf only (the Gaussian is integrated "
                                 "until its tail is negligible)")
        else:
            if not callable(self.pdf):
                raise ValueError("pdf must be a callable p(z) (1/m)")
            if self.support is None or np.ndim(self.support) != 1 or len(self.support) != 2:
                raise ValueError("a user pdf needs support=(z_lo, z_hi) (m)")
            lo, hi = (real_scalar(v, "support") for v in self.support)
            if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
                raise ValueError(f"support must be finite with z_lo < z_hi (m); got {self.support!r}")
        if self.sigma is not None:
            check_finite_positive(self.sigma, "sigma", "(m, standard deviation of summit heights)")

    @property
    def n_summits(self):
        """N = eta A_n, the expected number of summits on the nominal area (-)."""
        return self.eta * self.A_n


@dataclass
class RoughImpact:
    """Result of :meth:`RoughSurface.impact`: arrays over V1 (floats for a scalar V1).

    Attributes
    ----------
    V1 : impact speed (m/s).  M : mass of the flat (kg).  unloading : "jcg", "etsion" or "brake".
    V1_star : V1 / V_c, V_c = sqrt(2 U_c / M) of one asperity (-).
    e : coefficient of restitution of the surface e_s = V2 / V1 (-).
    loss : dissipated fraction 1 - e_s^2 (-), accurate near 0.
    d_min : deepest approach: distance of the flat above the mean summit plane (m); negative when
        the flat ends below that plane.
    force_max : total contact force at d_min (N), the largest force of the impact.
    n_contact : summits in contact at d_min (w* > 0); expected number (float) for a statistical
        surface, a count for explicit summits.
    n_yielded : summits loaded past the onset of yield (w* > 1), same convention.
    dissipated : energy dissipated (J) = loss * energy_in.
    energy_in : (1/2) M V1^2 (J).
    w_star_max : explicit summits: w* of the tallest summit at d_min; statistical: w* at the upper
        end of the height integration (where the height distribution is truncated) (-).
    kind : "explicit" or "statistical".
    """

    V1: np.ndarray
    M: float
    unloading: str
    V1_star: np.ndarray
    e: np.ndarray
    loss: np.ndarray
    d_min: np.ndarray
    force_max: np.ndarray
    n_contact: np.ndarray
    n_yielded: np.ndarray
    dissipated: np.ndarray
    energy_in: np.ndarray
    w_star_max: np.ndarray
    kind: str = field(default="explicit")

    def as_dict(self):
        """The fields as a plain dict."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def __getitem__(self, key):
        return getattr(self, key)


class RoughSurface:
    """A rough surface of spherical summits of radius ``R_a``, struck by a rigid flat.

    Parameters
    ----------
    material : fastrest.Material
        The surface's (summits') material; the flat is rigid.
    R_a : float
        Summit radius of curvature (m), > 0.
    heights : array_like, optional
        Explicit summit heights (m), any datum. The mean summit plane is their mean; d_min is
        reported from it.
    gw : GreenwoodWilliamson or dict, optional
        Statistical description (summit density, height standard deviation, nominal area, pdf).
        Exactly one of ``heights`` and ``gw``.

    Attributes
    ----------
    impact_params : fastrest.Impact
        One summit against the rigid flat (its E_eff, omega_c, P_c, U_c, eps_y, nu).
    sigma : float
        Standard deviation of the summit heights (m) (of the given heights, or of the model).
    plasticity_index : float
        psi = sqrt(sigma / omega_c) = (E'/H) sqrt(sigma / R_a) with H = (pi/2) C(nu) Sy.
    """

    def __init__(self, material, R_a, heights=None, gw=None):
        if not isinstance(material, Material):
            raise TypeError("material must be a fastrest.Material")
        self.material = material
        self.R_a = float(check_finite_positive(real_scalar(R_a, "R_a"), "R_a", "(m, summit radius)"))
        try:
            self.impact_params = Impact(material, self.R_a, mass=1.0)  # mass unused here
        except ValueError as exc:
            raise ValueError(f"R_a = {self.R_a!r} m: {exc}") from None
        if (heights is None) == (gw is None):
            raise ValueError("give exactly one of heights= (explicit summits) and gw= (statistical)")
        ip = self.impact_params
        self.eps_y, self.nu = float(ip.eps_y), float(ip.nu)
        warn_if_outside_validated(self.eps_y, self.nu)
        self.omega_c, self.P_c, self.U_c = ip.omega_c, ip.P_c, ip.U_c
        self._tables = {}
        if heights is not None:
            z = np.array(as_float_array(heights, "heights"), dtype=np.float64).ravel()
            if z.size == 0:
                raise ValueError("heights is empty: a surface needs at least one summit")
            if not np.all(np.isfinite(z)):
                raise ValueError("heights must be finite (m)")
            self.kind = "explicit"
            self.heights = z
            self.gw = None
            self.z_top = float(z.max())
            with np.errstate(over="ignore", invalid="ignore"):
                self.z_mean = float(z.mean())
                self.sigma = float(z.std())
            if not (math.isfinite(self.sigma) and math.isfinite(self.z_mean)):
                raise ValueError("heights span more than the range of a float64 (m): their standard "
                                 "deviation overflows")
            self.n_summits = z.size
            self._h = np.ascontiguousarray((z - self.z_top) / self.omega_c)
        else:
            if isinstance(gw, dict):
                gw = GreenwoodWilliamson(**gw)
            if not isinstance(gw, GreenwoodWilliamson):
                raise TypeError("gw must be a GreenwoodWilliamson or a dict of its parameters")
            self.kind = "statistical"
            self.heights = None
            self.gw = gw
            self.n_summits = gw.n_summits
            self._gwdata, self.sigma = _gw_data(gw, self.omega_c)
            r = self._gwdata.rho_w
            if not (RHO_W_RANGE[0] <= r <= RHO_W_RANGE[1]):
                raise ValueError(
                    f"sigma / omega_c = {r!r} (sigma = {self.sigma!r} m, omega_c = {self.omega_c!r} m of a "
                    f"summit of radius R_a = {self.R_a!r} m) is outside [{RHO_W_RANGE[0]:g}, "
                    f"{RHO_W_RANGE[1]:g}], where the statistical model is computed: below, all summits "
                    "have practically one height (use explicit heights=); above, the height "
                    "distribution is wider than the model's w* range by many orders of magnitude")

    def __repr__(self):
        desc = (f"{self.n_summits} summits" if self.kind == "explicit"
                else f"GW eta={self.gw.eta!r}, A_n={self.gw.A_n!r}")
        return (f"RoughSurface({self.material!r}, R_a={self.R_a!r}, {desc}, sigma={self.sigma!r}, "
                f"psi={self.plasticity_index:.4g})")

    @property
    def plasticity_index(self):
        """psi = sqrt(sigma / omega_c) (-): JG's form of the Greenwood-Williamson index.

        Equal to (E'/H) sqrt(sigma / R_a) with the hardness-like H = (pi/2) C(nu) Sy, since
        omega_c = (pi C Sy / (2 E'))^2 R_a (JGM eq 4); sigma is the summit-height standard deviation.
        """
        return math.sqrt(self.sigma / self.omega_c)

    def plasticity_index_gw(self, H):
        """Greenwood-Williamson's psi = (E'/H) sqrt(sigma / R_a) with a given hardness H (Pa)."""
        H = float(check_finite_positive(H, "H", "(Pa, hardness)"))
        return self.impact_params.E_eff / H * math.sqrt(self.sigma / self.R_a)

    def params(self):
        """Keyword arguments that rebuild this surface (``RoughSurface(**params)``)."""
        p = {"material": self.material, "R_a": self.R_a}
        if self.kind == "explicit":
            p["heights"] = self.heights
        else:
            p["gw"] = self.gw
        return p

    # --- forward data: built for this material only, up to the interference the impacts reach ---
    def forward(self, unloading="jcg", w_max=0.0, extrapolate=False):
        """The cached :class:`fastrest.forward.ForwardData`, grown to cover ``w_max`` if needed.

        Tables built for different ``w_max`` hold bit-identical cells where both are defined, so
        results never depend on which table a surface happens to hold.
        """
        code = unloading_code(unloading)
        data = self._tables.get(code)
        if data is None or data.w_max < w_max:
            lim = fw.forward_limit(self.eps_y, self.nu, extrapolate=extrapolate)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)  # issued once, by __init__
                data = fw.forward_data(self.eps_y, self.nu, min(max(w_max, 2.0), lim), unloading,
                                       extrapolate=extrapolate)
            self._tables[code] = data
        return data

    def _hertz_dummy(self, unloading):
        """Placeholder ForwardData for the Hertz estimate (the kernels do not read it then)."""
        data = self._tables.get(unloading_code(unloading))
        if data is not None:
            return data
        return fw.ForwardData(unloading_code(unloading), self.eps_y, self.nu, 1.0, 1.0, 0.0, 47, 0,
                              np.zeros((1, 8)), np.zeros((1, 8)))

    # --- the impact ---------------------------------------------------------------------------
    def impact(self, V1, M, unloading="jcg", extrapolate=False):
        """Impact of a rigid flat of mass ``M`` (kg) at speed ``V1`` (m/s, scalar or array).

        Parameters
        ----------
        V1 : float or array_like
            Normal approach speed (m/s), finite and > 0 (at V1 = 0 nothing touches: ValueError).
        M : float
            Mass of the flat (kg), > 0 (against a fixed surface; use the reduced mass for two free
            bodies).
        unloading : {"jcg", "etsion", "brake"}
            Residual interference model of every summit, JGM eq (35), (33) or Brake's (:mod:`fastrest.unloading`).
        extrapolate : bool
            Allow summits past w* = 425 (JGM's range), up to a/R = 1, with an ExtrapolationWarning.

        Returns
        -------
        RoughImpact

        Raises
        ------
        ValueError
            Invalid input, or an impact that drives summits past the model's range.
        """
        code = unloading_code(unloading)
        M = float(check_finite_positive(real_scalar(M, "M"), "M", "(kg, mass of the flat)"))
        extrapolate = check_bool(extrapolate, "extrapolate")
        v = as_float_array(V1, "V1")
        shape = v.shape
        flat = np.ascontiguousarray(v.ravel())
        bad = ~(np.isfinite(flat) & (flat > 0))
        if np.any(bad):
            raise ValueError(f"V1 must be finite and > 0 (m/s); got {flat[bad][0]!r} (at V1 = 0 no "
                             "summit is ever touched and e_s is undefined)")
        with np.errstate(over="ignore", under="ignore"):
            energy = M * flat**2 / (2.0 * self.U_c)  # (V1/V_c)^2: impact energy over U_c
        bad = ~(np.isfinite(energy) & (energy >= sys.float_info.min))
        if np.any(bad):
            k = int(np.flatnonzero(bad)[0])
            raise ValueError(
                f"the impact energy (1/2) M V1^2 at V1 = {float(flat[k])!r} m/s, M = {M!r} kg is "
                f"{_bad_energy_word(energy[k])} against one summit's critical energy U_c = {self.U_c!r} J: "
                f"(V1/V_c)^2 = {float(energy[k])!r} must be a finite, normal double")
        if flat.size == 0:
            raw = np.zeros((10, 0))
        elif self.kind == "explicit":
            raw = self._solve_explicit(energy, unloading, extrapolate, M)
        else:
            raw = self._solve_gw(energy, unloading, extrapolate, M)
        out = self._assemble(flat, M, energy, raw, code)
        if extrapolate and np.any(out["w_star_max"] > OMEGA_M_STAR_MAX):
            warn(f"summits loaded past w* = {OMEGA_M_STAR_MAX:g}, the largest interference "
                 "JGM computed; the JG law is not validated there", ExtrapolationWarning)

        def shaped(a):
            a = a.reshape(shape)
            return a.item() if a.ndim == 0 else a

        return RoughImpact(V1=shaped(flat), M=M, unloading=unloading, kind=self.kind,
                           **{k: shaped(a) for k, a in out.items()})

    def _grow_or_raise(self, unloading, need, extrapolate, v1_bad, M):
        """Grow the forward table to cover w* = need, or raise if the model's range ends first."""
        lim = fw.forward_limit(self.eps_y, self.nu, extrapolate=extrapolate)
        data = self._tables.get(unloading_code(unloading))
        if data is not None and data.w_max >= lim:
            what = interference_limit_message(max(need, lim * (1 + 1e-15)), self.eps_y, self.nu, extrapolate)
            if self.kind == "statistical":
                what += (f". The surface has N = eta A_n = {self.n_summits:.6g} summits; its height distribution "
                         f"(sigma = {self.sigma!r} m) is integrated until its tail is negligible "
                         f"(here up to w* = {need:.4g}); a pdf with bounded support "
                         "(GreenwoodWilliamson(pdf=..., support=...)) truncates it")
            raise ValueError(f"the impact at V1 = {v1_bad!r} m/s (M = {M!r} kg) drives summits to a w* "
                             f"that {what}")
        return self.forward(unloading, min(lim, max(1.25 * need, 2.0 * (data.w_max if data else 0.0))),
                            extrapolate)

    def _solve_explicit(self, energy, unloading, extrapolate, M):
        h = self._h
        n = energy.size
        # Hertz estimate of the approach: the starting point of every JG solve (independent of the
        # table, so results do not depend on what the surface computed before)
        hz = np.zeros((9, n))
        dummy = self._hertz_dummy(unloading)
        run_parallel(_explicit_impacts, None, dummy, h, energy, energy**0.4, True, 0.0, False, hz)
        if np.any(hz[0] != _OK):
            raise RuntimeError("rough-surface solver (Hertz estimate) did not converge (please report)")
        x0 = hz[1].copy()
        # JG summits sink deeper than Hertz ones: start with twice the estimate
        return self._solve_growing_table(
            lambda data, w_cap, at_limit, out: run_parallel(_explicit_impacts, None, data, h, energy, x0, False,
                                                            w_cap, at_limit, out),
            9, 2.0 * float(x0.max()), energy, unloading, extrapolate, M)

    def _solve_growing_table(self, run, rows, w_guess, energy, unloading, extrapolate, M):
        """Run a JG solve, growing the forward table until no impact needs more of it."""
        lim = fw.forward_limit(self.eps_y, self.nu, extrapolate=extrapolate)
        data = self._tables.get(unloading_code(unloading))
        if data is None:
            data = self.forward(unloading, min(w_guess, lim), extrapolate)
        while True:
            out = np.zeros((rows, energy.size))
            run(data, min(data.w_max, lim), data.w_max >= lim, out)
            need = out[0] == _NEEDS_TABLE
            if not np.any(need):
                break
            k = int(np.flatnonzero(need)[0])
            data = self._grow_or_raise(unloading, float(out[2, need].max()), extrapolate,
                                       float(np.sqrt(2.0 * self.U_c * energy[k] / M)), M)
        if np.any(out[0] != _OK):
            raise RuntimeError("rough-surface solver did not converge (please report)")
        return out

    def _solve_gw(self, energy, unloading, extrapolate, M):
        g = self._gwdata
        n = energy.size
        dummy = self._hertz_dummy(unloading)
        s_start = 0.0 if g.kind == 0 else 0.5 * (g.s_lo + g.s_hi)
        hz = np.zeros((10, n))
        if n >= 4:
            def run(*args):
                return run_parallel(_gw_impacts, _gw_impacts_serial, *args)
        else:
            run = _gw_impacts_serial
        self._check_gw_energy(energy, M)
        # JG summits sink deeper than Hertz ones: a Hertz estimate past HERTZ_CAP x the law's end
        # (a/R = 1) means the impact itself is past it
        w_end = fw.forward_limit(self.eps_y, self.nu, extrapolate=True)
        run(dummy, g, energy, np.full(n, s_start), True, HERTZ_CAP * w_end, True, hz)
        if np.any(hz[0] == _NEEDS_TABLE):
            k = int(np.flatnonzero(hz[0] == _NEEDS_TABLE)[0])
            raise ValueError(f"the impact at V1 = {float(np.sqrt(2.0 * self.U_c * energy[k] / M))!r} m/s (M = {M!r} "
                             f"kg) drives summits to a w* that {interference_limit_message(w_end * 1.5, self.eps_y, self.nu, True)}"
                             f". The height distribution (sigma = {self.sigma!r} m) is integrated until its tail "
                             "is negligible; a pdf with bounded support (GreenwoodWilliamson(pdf=..., "
                             "support=...)) truncates it")
        if np.any(hz[0] != _OK):
            raise RuntimeError("rough-surface solver (Hertz estimate) did not converge (please report)")
        s0 = hz[1].copy()
        return self._solve_growing_table(
            lambda data, w_cap, at_limit, out: run(data, g, energy, s0, False, w_cap, at_limit, out),
            10, 1.5 * float(hz[2].max()), energy, unloading, extrapolate, M)

    def _check_gw_energy(self, energy, M):
        """Gaussian heights: an impact so light that the flat stops where the height density
        underflows (s = z/sigma > S_UNDERFLOW) is outside what the statistical model resolves."""
        g = self._gwdata
        if g.kind != 0:
            return
        buf = np.empty(7)
        _gw_integrals(self._hertz_dummy("jcg"), g, S_UNDERFLOW, True, False, 0.0, buf)
        low = g.n_total * buf[0]  # Hertz G at s_d = S_UNDERFLOW (JG's G is the same there or larger)
        if np.any(energy < low):
            k = int(np.flatnonzero(energy < low)[0])
            raise ValueError(
                f"the impact at V1 = {float(np.sqrt(2.0 * self.U_c * energy[k] / M))!r} m/s is too light for "
                f"the statistical model: the flat would stop more than {S_UNDERFLOW:g} sigma above the "
                f"mean summit plane, where the Gaussian height density exp(-s^2/2) is below 1e-281 (N = "
                f"{g.n_total:.4g} summits); (V1/V_c)^2 = {float(energy[k])!r} must be >= {low:.4g}")

    def _assemble(self, v, M, energy, raw, code):
        if self.kind == "explicit":
            x = raw[1]
            sums = raw[3:9]  # F, P, R, L, n_contact, n_yielded
            d_min = (self.z_top - self.z_mean) - x * self.omega_c
            w_top = x
            n_c, n_y = sums[4].astype(np.int64), sums[5].astype(np.int64)
            p_sum, l_sum = sums[1], sums[3]
        else:
            n_tot = self.gw.n_summits
            s_d = raw[1]
            ex = raw[3:10]  # E F, E P, E R, E L, P(contact), P(yield), w_top
            d_min = s_d * self.sigma
            w_top = ex[6]
            n_c, n_y = n_tot * ex[4], n_tot * ex[5]
            p_sum, l_sum = n_tot * ex[1], n_tot * ex[3]
        loss = l_sum / energy
        e = np.sqrt(1.0 - loss)
        result = {
            "V1_star": np.sqrt(energy), "e": e, "loss": loss, "d_min": d_min,
            "force_max": self.P_c * p_sum, "n_contact": n_c, "n_yielded": n_y,
            "dissipated": self.U_c * l_sum, "energy_in": 0.5 * M * v**2, "w_star_max": w_top,
        }
        for k, a in result.items():
            if np.any(np.isnan(a)):
                raise RuntimeError(f"rough-surface impact produced NaN in {k} (please report)")
        return result


def _gw_data(gw, omega_c):
    """GWData for the kernels, and sigma (computed from a user pdf if not given)."""
    if gw.pdf is None:
        sigma = float(gw.sigma)
        return GWData(0, float(gw.n_summits), sigma / omega_c, -np.inf, np.inf, 0.0,
                      np.zeros((1, 8))), sigma
    z_lo, z_hi = (float(v) for v in gw.support)
    # tabulate in z first to find the scale, then in s = z / sigma
    span = z_hi - z_lo
    scale = float(gw.sigma) if gw.sigma is not None else span / 8.0
    s_lo, s_hi = z_lo / scale, z_hi / scale
    ncell = max(4, int(math.ceil((s_hi - s_lo) * PDF_CELLS_PER_SIGMA)))
    edges_s = np.linspace(s_lo, s_hi, ncell + 1)
    edges = np.stack([edges_s[:-1], edges_s[1:]], axis=1)
    nodes = chebyshev_nodes(edges, GAUSS_U)  # a pdf need not be defined at its support's ends
    try:
        vals = np.asarray(gw.pdf(nodes * scale), dtype=np.float64) * scale
    except Exception:  # not vectorised
        vals = np.array([float(gw.pdf(float(z))) for z in (nodes * scale).ravel()]).reshape(nodes.shape) * scale
    if vals.shape != nodes.shape or not np.all(np.isfinite(vals)) or np.any(vals < 0):
        raise ValueError("pdf must return finite, non-negative densities on its support")
    rows = fit_cells(edges, vals, GAUSS_U)
    # exact integrals of the cell polynomials: half * sum over even k of c_k 2/(k+1)
    half = 0.5 * (edges[:, 1] - edges[:, 0])
    k = np.arange(6)
    even = np.where(k % 2 == 0, 2.0 / (k + 1), 0.0)
    mass = float(np.sum(half * (rows[:, 2:] @ even)))
    if not (mass > 0 and math.isfinite(mass)):
        raise ValueError("pdf integrates to zero over its support")
    rows[:, 2:] /= mass
    # moments by Gauss-Legendre on each cell (the cell polynomials are exact to degree 5)
    gx, gwt = np.polynomial.legendre.leggauss(8)
    center = 0.5 * (edges[:, 0] + edges[:, 1])
    pts = center[:, None] + half[:, None] * gx[None, :]
    u = gx[None, :]
    pv = sum(rows[:, 2 + j][:, None] * u**j for j in range(6))
    wts = half[:, None] * gwt[None, :] * pv
    m1 = float(np.sum(wts * pts))
    m2 = float(np.sum(wts * pts**2))
    sd_s = math.sqrt(max(m2 - m1 * m1, 0.0))
    sigma = float(gw.sigma) if gw.sigma is not None else sd_s * scale
    if gw.sigma is None:
        # re-tabulate on s = z / sigma with the computed sigma
        return _gw_data(GreenwoodWilliamson(gw.eta, sigma, gw.A_n, gw.pdf, gw.support), omega_c)
    data = GWData(1, float(gw.n_summits), sigma / omega_c, s_lo, s_hi, ncell / (s_hi - s_lo),
                  np.ascontiguousarray(rows))
    return data, sigma


# =================================================================================================
# Sweeps (local, or one Dask task per parameter set)
# =================================================================================================

def surface_from_params(material=None, R_a=None, heights=None, gw=None, gaussian=None,
                        E=None, nu=None, Sy=None):
    """Default factory of :func:`sweep`: build a :class:`RoughSurface` from plain parameters.

    ``material`` (a Material) or ``E, nu, Sy`` (Pa, -, Pa); ``R_a`` (m); and one of ``heights``
    (array, m), ``gw`` (GreenwoodWilliamson or dict) or ``gaussian=(n, sigma, seed)`` (summits
    drawn by :func:`gaussian_summits` where the task runs: nothing large is shipped).
    """
    if material is None:
        if E is None or nu is None or Sy is None:
            raise ValueError("give material= or all of E, nu, Sy")
        material = Material(E=E, nu=nu, Sy=Sy)
    if gaussian is not None:
        if heights is not None:
            raise ValueError("give only one of heights= and gaussian=")
        heights = gaussian_summits(*gaussian)
    return RoughSurface(material, R_a, heights=heights, gw=gw)


def _sweep_task(factory, params, array_keys, *args):
    """One parameter set (module-level, so Dask can ship it by reference)."""
    k = len(array_keys)
    params = dict(params)
    params.update(zip(array_keys, args[:k]))
    V1, M, unloading, extrapolate = args[k:]
    surface = factory(**params)
    return surface.impact(V1, M, unloading=unloading, extrapolate=extrapolate)


def sweep(surfaces, V1, M, unloading="jcg", extrapolate=False, factory=surface_from_params,
          client=None, scatter_min=100_000):
    """Impacts of many surfaces (or parameter sets) at the speeds ``V1``.

    Parameters
    ----------
    surfaces : sequence of RoughSurface or of dict
        Each dict holds keyword arguments of ``factory`` (default :func:`surface_from_params`:
        material or E/nu/Sy, R_a, and heights, gw or gaussian=(n, sigma, seed)).
    V1 : float or array_like
        Impact speeds (m/s), > 0; the same for every surface.
    M : float or sequence of float
        Mass of the flat (kg): one value, or one per surface.
    unloading, extrapolate
        As in :meth:`RoughSurface.impact`.
    factory : callable
        Module-level function building a RoughSurface from a dict (must pickle for Dask).
    client : dask.distributed.Client, optional
        Run one task per surface on this cluster. Arrays with at least ``scatter_min`` elements
        (explicit heights) and V1 are scattered once each (the same array object is shipped once
        even if several parameter sets use it). Without a client everything runs here.

    Returns
    -------
    list of RoughImpact
        In the order of ``surfaces``; the same numbers with or without a client (the kernels sum
        in fixed blocks, so thread counts do not change the result).
    """
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
    v = as_float_array(V1, "V1")
    unloading_code(unloading)
    check_bool(extrapolate, "extrapolate")
    if not callable(factory):
        raise TypeError("factory must be a callable building a RoughSurface from a dict")
    specs = []
    for s in surfaces:
        if isinstance(s, RoughSurface):
            specs.append(s.params())
        elif isinstance(s, dict):
            specs.append(dict(s))
        else:
            raise TypeError("surfaces must be RoughSurface objects or dicts of parameters")
    if client is None:
        out = []
        for s, spec, m in zip(surfaces, specs, masses):
            surface = s if isinstance(s, RoughSurface) else factory(**spec)
            out.append(surface.impact(v, m, unloading=unloading, extrapolate=extrapolate))
        return out
    v_future = client.scatter(v)
    shipped = {}  # id(array) -> future: each big array is scattered once
    futures = []
    for s, spec, m in zip(surfaces, specs, masses):
        small, keys, arrays = {}, [], []
        for key, val in spec.items():
            if isinstance(val, np.ndarray) and val.size >= scatter_min:
                if id(val) not in shipped:
                    shipped[id(val)] = (client.scatter(val), val)  # keep val alive for the id
                keys.append(key)
                arrays.append(shipped[id(val)][0])
            else:
                small[key] = val
        fac = factory if not isinstance(s, RoughSurface) else _rebuild_surface
        futures.append(client.submit(_sweep_task, fac, small, keys, *arrays, v_future, m, unloading,
                                     extrapolate, pure=False))
    return client.gather(futures)


def _rebuild_surface(material, R_a, heights=None, gw=None):
    """Factory for RoughSurface objects sent to Dask (their :meth:`RoughSurface.params`)."""
    return RoughSurface(material, R_a, heights=heights, gw=gw)


# =================================================================================================
# Slow reference (validation and benchmarks)
# =================================================================================================

def reference_impact(material, R_a, heights, V1, M, unloading="jcg"):
    """Brute-force impact on explicit summits, for validation: no tables, no fastrest.forward.

    Every summit's loading energy is :func:`fastrest.energy.f_star_kernel` (quadrature), its
    force :func:`fastrest.contact.p_star_kernel` and its unloading
    :func:`fastrest.unloading.restitution_kernel` (the single-sphere solver's own expressions,
    at V1* = sqrt(F)); the approach solving sum F = (V1/V_c)^2 comes from
    :func:`scipy.optimize.brentq`. Milliseconds per summit: use for N up to a few hundred.

    Returns a dict with the scalar fields of :class:`RoughImpact` (e, loss, d_min, force_max,
    n_contact, n_yielded, dissipated, w_star_max).
    """
    from scipy.optimize import brentq

    from .contact import p_star_kernel
    from .energy import f_star_kernel
    from .unloading import restitution_kernel

    model = unloading_code(unloading)
    if not isinstance(material, Material):
        raise TypeError(f"material must be a fastrest.Material, got {type(material).__name__}")
    R_a = float(check_finite_positive(real_scalar(R_a, "R_a"), "R_a", "(m, summit radius)"))
    M = float(check_finite_positive(real_scalar(M, "M"), "M", "(kg, mass of the flat)"))
    V1 = float(check_finite_positive(real_scalar(V1, "V1"), "V1", "(m/s)"))
    if not as_float_array(heights, "heights").size:
        raise ValueError("heights is empty: a surface needs at least one summit")
    try:
        ip = Impact(material, R_a, mass=M)
    except ValueError as exc:
        raise ValueError(f"R_a = {R_a!r} m, M = {M!r} kg: {exc}") from None
    eps, nu, wc = float(ip.eps_y), float(ip.nu), ip.omega_c
    z = np.asarray(heights, dtype=np.float64).ravel()
    z_top = float(z.max())
    h = (z - z_top) / wc
    v1_star = float(V1) / ip.V_c
    energy = v1_star**2 if v1_star < 1e150 else math.inf
    if not (math.isfinite(energy) and energy >= sys.float_info.min):
        raise ValueError(f"V1 = {V1!r} m/s with M = {M!r} kg: (V1/V_c)^2 = {energy!r} must be a finite, normal double")

    def excess(x):
        return sum(f_star_kernel(hi + x, eps, nu) for hi in h if hi + x > 0.0) - energy

    # bracket the approach by doubling from the Hertz single-summit value (an upper bound while
    # the tallest summit stays elastic)
    x_hi = energy**0.4
    while excess(x_hi) < 0.0:
        if x_hi >= OMEGA_M_STAR_MAX:
            raise ValueError(f"V1 = {V1!r} m/s (M = {M!r} kg, R_a = {R_a!r} m) drives summits past "
                             f"w* = {OMEGA_M_STAR_MAX:g}")
        x_hi = min(2.0 * x_hi, OMEGA_M_STAR_MAX)
    x = brentq(excess, 0.0, x_hi, xtol=1e-300, rtol=1e-15, maxiter=1000)
    f_sum = p_sum = l_sum = 0.0
    n_c = n_y = 0
    for hi in h:
        w = hi + x
        if w <= 0.0:
            continue
        f = f_star_kernel(w, eps, nu)
        _, loss, _, _ = restitution_kernel(math.sqrt(f), w, w - 1.0, eps, nu, model)
        f_sum += f
        p_sum += p_star_kernel(w, eps, nu)
        l_sum += loss * f
        n_c += 1
        n_y += w > 1.0
    loss = l_sum / energy
    return {"e": math.sqrt(1.0 - loss), "loss": loss, "d_min": (z_top - float(z.mean())) - x * wc,
            "force_max": ip.P_c * p_sum, "n_contact": n_c, "n_yielded": n_y,
            "dissipated": ip.U_c * l_sum, "w_star_max": x}
