"""Slow, high-precision reference implementation of the normalised JGM (2010) model.

Used only by the test-suite.  It is deliberately independent of the ``fastrest``
package (nothing is imported from it) and is written directly from the paper
(Jackson, Green & Marghitu, Nonlinear Dyn. 60 (2010) 217-229, eqs 8-15, 22-38)
and the project's model notes (the algebra of eqs 8-38 as docs/model.md states it).

Everything is evaluated in a private mpmath context at 40 significant digits
(the global ``mpmath.mp`` context is never touched), integrals with
tanh-sinh quadrature (``quad``) on short, log-spaced sub-intervals, and the
maximum interference with a safeguarded Newton iteration to ~1e-34 relative.
Inputs are plain Python floats (converted exactly); outputs are Python floats
(correctly rounded from the 40-digit result).

Normalised model (w = omega/omega_c; eps_y = S_y/E' > 0; Poisson nu in [0, 0.5)):

* C(nu) = 1.295 exp(0.736 nu)                                              (5)
* w <= 1.9 : P* = w^1.5, A* = w  (Hertz)                                   (14)
* w >  1.9 : A* = w (w/1.9)^B, B = 0.14 exp(23 eps_y)                      (8),(10)
             a/R = (pi C eps_y / 2) sqrt(A*)
             H_G/S_y = 2.84 - 0.92 (1 - cos(pi a/R))    (only 0 < a/R <= 1) (12)
             P* = exp(-w^(5/12)/4) w^1.5 + (4 H_G/(C S_y)) (1 - exp(-w^(5/9)/25)) w   (9)
* F(w) = V1*^2 at maximum interference w:
             F = w^2.5 (w <= 1.9),  F = 1.9^2.5 + (5/2) int_{1.9}^w P* dz  (w > 1.9)
  (equivalently F = 1 + (5/2) int_1^w P*; (W_ep)* of (25) is 1 - F.)
* JCG unloading (35):  r = w_res/w_m = 1.02 (1 - ((w_m + 5.9)/6.9)^(-0.54)), r = 0 for w_m <= 1
* Etsion unloading (33): w_m - w_res* = P*(w_m) / sqrt(A*(w_m))
* Brake unloading (Brake 2015 as implemented by tmdsimpy, _normal_asperity_unloading):
  w_m - w_res* = P*(w_m) / sqrt(w_m)
* (32)+(38):  e^2 = P*(w_m) (w_m - w_res*) / V1*^2;  R_res/R = P*(w_m)^2 / (w_m - w_res*)^3  (36)
* V1* <= 1: elastic, e = 1.

Domain policy (the reference refuses rather than extrapolates):
* eps_y must be > 0, nu in [0, 0.5), w >= 0, V1* >= 0 -> otherwise ValueError.
* The JG branch needs a/R <= 1 (eq. 12 is stated for 0 < a/R < 1; the end point
  a/R = 1 itself is accepted).  P*, F, w_m etc. raise ValueError past that point.
* JCG: the fit (35) exceeds 1 for w_m of order 1e4 (no rebound).  ref_e_star /
  ref_loss_star raise ValueError if r > 1, ref_residual_star if r >= 1.

Branch thresholds use the exact decimal 1.9 (mpf('1.9')).  The float 1.9 lies
below it and no float lies strictly between, so a float w compares the same way
as ``w <= 1.9`` in double precision.  The V1* threshold is V1*^2 <= 1.9^2.5
evaluated at 40 digits.
"""

from __future__ import annotations

import bisect
import functools

import mpmath

__all__ = [
    "ref_P_star",
    "ref_A_star",
    "ref_F",
    "ref_W_star",
    "ref_omega_m_star",
    "ref_e_star",
    "ref_loss_star",
    "ref_residual_star",
    "ref_v1_star_at",
]

DPS = 40

_ctx = mpmath.MPContext()
_ctx.dps = DPS
_mpf = _ctx.mpf

_W19 = _mpf("1.9")                  # Hertz / JG switch, in units of omega_c
_F19 = _W19 ** _mpf("2.5")          # F(1.9) = 1.9^2.5
_HALF5 = _mpf("2.5")
_LN19 = _ctx.ln(_W19)
_F3_2 = _mpf(3) / 2
_F5_12 = _mpf(5) / 12
_F5_9 = _mpf(5) / 9
_ANCHOR_RATIO = _mpf(2) ** _mpf("0.5")    # anchors at 1.9 * 2^(k/2)
_NEWTON_RTOL = _mpf(10) ** (-(DPS - 6))
_QUAD_RTOL = _mpf(10) ** (-(DPS - 5))


def _gauss_legendre_half(n):
    """Positive nodes x_i and weights of the n-point Gauss-Legendre rule on [-1, 1]
    (n even), computed by Newton on the Legendre recurrence at 20 extra digits."""
    ctx = mpmath.MPContext()
    ctx.dps = DPS + 20
    out = []
    for i in range(1, n // 2 + 1):
        x = ctx.cos(ctx.pi * (i - ctx.mpf(1) / 4) / (n + ctx.mpf(1) / 2))
        for _ in range(100):
            p0, p1 = ctx.mpf(1), x
            for k in range(2, n + 1):
                p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < ctx.mpf(10) ** (-(DPS + 15)):
                break
        p0, p1 = ctx.mpf(1), x
        for k in range(2, n + 1):
            p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
        dp = n * (x * p1 - p0) / (x * x - 1)
        out.append((_mpf(x), _mpf(2 / ((1 - x * x) * dp * dp))))
    return tuple(out)


_GL_HALF = _gauss_legendre_half(24)

_UNLOADINGS = ("jcg", "etsion", "brake")


# --------------------------------------------------------------------------- helpers
def _check_params(eps_y, nu):
    eps_y = float(eps_y)
    nu = float(nu)
    if not (eps_y > 0.0) or eps_y != eps_y or eps_y == float("inf"):
        raise ValueError(f"eps_y must be finite and > 0, got {eps_y!r}")
    if not (0.0 <= nu < 0.5):
        raise ValueError(f"nu must be in [0, 0.5), got {nu!r}")
    return eps_y, nu


def _check_unloading(unloading):
    u = str(unloading).lower()
    if u not in _UNLOADINGS:
        raise ValueError(f"unloading must be 'jcg', 'etsion' or 'brake', got {unloading!r}")
    return u


def _check_nonneg(x, name):
    x = float(x)
    if not (x >= 0.0) or x == float("inf"):
        raise ValueError(f"{name} must be finite and >= 0, got {x!r}")
    return x


class _Law:
    """JG loading law and the cumulative energy F for one (eps_y, nu)."""

    def __init__(self, eps_y: float, nu: float):
        ctx = _ctx
        self.eps = _mpf(eps_y)      # exact binary value of the float
        self.nu = _mpf(nu)
        self.C = _mpf("1.295") * ctx.exp(_mpf("0.736") * self.nu)
        self.B = _mpf("0.14") * ctx.exp(23 * self.eps)
        self.k_aR = ctx.pi * self.C * self.eps / 2      # a/R = k_aR * sqrt(A*)
        # w where a/R = 1 on the JG branch: w^(1+B) 1.9^(-B) = (1/k_aR)^2
        a_max = 1 / self.k_aR ** 2
        self.w_max = (a_max * _W19 ** self.B) ** (1 / (1 + self.B))
        # anchors for F on the JG branch (lazily extended)
        self._aw = [_W19]
        self._aF = [_F19]
        self._complete = False       # True once the last anchor is w_max

    # -- loading law -------------------------------------------------------
    def A_jg(self, w):
        return w * (w / _W19) ** self.B

    def aR_jg(self, w):
        return self.k_aR * _ctx.sqrt(self.A_jg(w))

    def P_jg(self, w):
        """JG branch (9) of P*, evaluated for any w > 0 (no branch switch)."""
        ctx = _ctx
        lw = ctx.ln(w)
        # a/R = k sqrt(A*),  sqrt(A*) = exp(((1+B) ln w - B ln 1.9)/2)
        aR = self.k_aR * ctx.exp(((1 + self.B) * lw - self.B * _LN19) / 2)
        if aR > 1 + _mpf("1e-30"):  # the end point w_max itself may round to 1 + tiny
            raise ValueError(
                f"a/R = {float(aR):.6g} > 1 at w = {float(w):.6g}: the JG law (12) is "
                f"undefined there (eps_y = {float(self.eps)!r}, w_max = {float(self.w_max):.6g})"
            )
        s = ctx.sin(ctx.pi * aR / 2)
        hg = _mpf("2.84") - _mpf("0.92") * 2 * s * s           # 1 - cos x = 2 sin^2(x/2)
        t1 = ctx.exp(_F3_2 * lw - ctx.exp(_F5_12 * lw) / 4)    # exp(-w^(5/12)/4) w^1.5
        t2 = (4 * hg / self.C) * (-ctx.expm1(-ctx.exp(_F5_9 * lw) / 25)) * w
        return t1 + t2

    def P(self, w):
        if w <= _W19:
            return w ** _mpf("1.5")
        return self.P_jg(w)

    def A(self, w):
        if w <= _W19:
            return w
        return self.A_jg(w)

    # -- energy ------------------------------------------------------------
    def _int_P(self, a, b):
        """(5/2) * int_a^b P_jg(z) dz for a short JG-branch interval (b/a <= sqrt 2).

        Fixed 24-point Gauss-Legendre.  The integrand is analytic except for the
        branch point at z = 0, so on [a, 1.42 a] the error is ~ 11.6^(-48) ~ 1e-51;
        every anchor segment is cross-checked against mpmath.quad (see _extend).
        """
        if a == b:
            return _mpf(0)
        c = (a + b) / 2
        h = (b - a) / 2
        P = self.P_jg
        acc = _ctx.fsum(wt * (P(c + h * x) + P(c - h * x)) for x, wt in _GL_HALF)
        return _HALF5 * h * acc

    def _extend(self):
        """Append one anchor; returns False if already at w_max."""
        if self._complete:
            return False
        w0 = self._aw[-1]
        w1 = w0 * _ANCHOR_RATIO
        if w1 >= self.w_max:
            w1 = self.w_max
            self._complete = True
        # anchor segment: tanh-sinh quadrature, checked against the Gauss-Legendre rule
        seg = _HALF5 * _ctx.quad(self.P_jg, [w0, w1])
        seg_gl = self._int_P(w0, w1)
        if abs(seg - seg_gl) > _QUAD_RTOL * abs(seg):
            raise RuntimeError(  # pragma: no cover - would indicate a quadrature failure
                f"quadrature disagreement on [{float(w0)}, {float(w1)}]: "
                f"{_ctx.nstr(seg, 30)} vs {_ctx.nstr(seg_gl, 30)}"
            )
        self._aF.append(self._aF[-1] + seg)
        self._aw.append(w1)
        return True

    def _anchor_below_w(self, w):
        while self._aw[-1] < w:
            if not self._extend():
                break
        i = bisect.bisect_right(self._aw, w) - 1
        return max(i, 0)

    def F(self, w):
        if w <= _W19:
            return w ** _mpf("2.5")
        if w > self.w_max:
            self.P_jg(w)             # raises the a/R > 1 error
        i = self._anchor_below_w(w)
        return self._aF[i] + self._int_P(self._aw[i], w)

    def omega_m(self, v1):
        """Solve F(w_m) = v1^2 (v1 an mpf >= 0)."""
        T = v1 * v1
        if T <= _F19:
            return v1 ** _mpf("0.8")
        # bracket between anchors
        while self._aF[-1] < T:
            if not self._extend():
                raise ValueError(
                    f"V1* = {float(v1)!r} needs w_m beyond w_max = {float(self.w_max):.6g} "
                    f"where a/R > 1 and the JG law is undefined"
                )
        i = bisect.bisect_left(self._aF, T)      # aF[i-1] < T <= aF[i]
        if self._aF[i] == T:
            return self._aw[i]
        lo, hi = self._aw[i - 1], self._aw[i]
        Flo, Fhi = self._aF[i - 1], self._aF[i]
        # start from linear interpolation; track F(w) incrementally
        w = lo + (hi - lo) * (T - Flo) / (Fhi - Flo)
        Fw = Flo + self._int_P(lo, w)
        for _ in range(200):
            g = Fw - T
            if g > 0:
                hi = w
            elif g < 0:
                lo = w
            else:
                return w
            step = g / (_HALF5 * self.P_jg(w))
            if abs(step) <= _NEWTON_RTOL * w:   # quadratic convergence: next step ~ 0
                return w - step
            w_new = w - step
            if not (lo < w_new < hi):           # safeguard: bisect
                w_new = (lo + hi) / 2
            Fw = Fw + self._int_P(w, w_new)
            w = w_new
        raise RuntimeError("omega_m Newton iteration did not converge")  # pragma: no cover


@functools.lru_cache(maxsize=None)
def _law(eps_y: float, nu: float) -> _Law:
    return _Law(eps_y, nu)


def _jcg_ratio(wm):
    """r = w_res/w_m from (35), without cancellation near w_m = 1; 0 for w_m <= 1."""
    if wm <= 1:
        return _mpf(0)
    ctx = _ctx
    # 1 - ((wm+5.9)/6.9)^-0.54 = -expm1(-0.54 * log1p((wm-1)/6.9))
    return _mpf("1.02") * -ctx.expm1(-_mpf("0.54") * ctx.log1p((wm - 1) / _mpf("6.9")))


@functools.lru_cache(maxsize=4096)
def _solve(v1_star: float, eps_y: float, nu: float):
    """Return (law, v1, w_m) at full precision."""
    law = _law(eps_y, nu)
    v1 = _mpf(v1_star)
    return law, v1, law.omega_m(v1)


@functools.lru_cache(maxsize=4096)
def _restitution(v1_star: float, eps_y: float, nu: float, unloading: str):
    """Return (e^2, 1 - e^2, w_res*, R_res/R) as mpf for validated inputs.

    For JCG with r > 1 e^2 is negative and R_res/R is None (callers raise).
    """
    law, v1, wm = _solve(v1_star, eps_y, nu)
    one = _mpf(1)
    if unloading in ("etsion", "brake"):
        if wm <= _W19:          # Hertz loading: (33) gives w_res = 0, e = 1 exactly (Brake too)
            return one, _mpf(0), _mpf(0), one
        P = law.P_jg(wm)
        # w_m - w_res*: Etsion (33) with the JG area; Brake (as tmdsimpy implements it,
        # deltabar = deltam (1 - Fm / F_Hertz(deltam))) with the Hertz area A* = w_m
        d = P / _ctx.sqrt(law.A_jg(wm) if unloading == "etsion" else wm)
        e2 = P * d / (v1 * v1)
        return e2, 1 - e2, wm - d, P * P / d ** 3
    # JCG
    r = _jcg_ratio(wm)
    if wm <= _W19:
        # P* w_m = w_m^2.5 = V1*^2 exactly, so e^2 = 1 - r and 1 - e^2 = r
        e2 = 1 - r
        loss = r
        P = wm ** _mpf("1.5") if wm > 0 else _mpf(0)
    else:
        P = law.P_jg(wm)
        e2 = P * wm * (1 - r) / (v1 * v1)
        loss = 1 - e2
    d = wm * (1 - r)
    if wm == 0:
        rr = one
    elif d > 0:
        rr = P * P / d ** 3
    else:
        rr = None
    return e2, loss, wm * r, rr


# --------------------------------------------------------------------------- public API
@functools.lru_cache(maxsize=4096)
def ref_P_star(w, eps_y, nu):
    """P* = P/P_c at w = omega/omega_c (Hertz for w <= 1.9, JG eq. 9 above)."""
    eps_y, nu = _check_params(eps_y, nu)
    w = _check_nonneg(w, "w")
    return float(_law(eps_y, nu).P(_mpf(w)))


@functools.lru_cache(maxsize=4096)
def ref_A_star(w, eps_y, nu):
    """A* = A/A_c (w for w <= 1.9, eq. 8 above)."""
    eps_y, nu = _check_params(eps_y, nu)
    w = _check_nonneg(w, "w")
    law = _law(eps_y, nu)
    wm = _mpf(w)
    if wm > _W19:
        law.P_jg(wm)        # domain check (a/R <= 1)
    return float(law.A(wm))


@functools.lru_cache(maxsize=4096)
def ref_F(w, eps_y, nu):
    """F(w) = 1.9^2.5 + (5/2) int_1.9^w P* (w > 1.9), w^2.5 below: V1*^2 reaching w."""
    eps_y, nu = _check_params(eps_y, nu)
    w = _check_nonneg(w, "w")
    return float(_law(eps_y, nu).F(_mpf(w)))


@functools.lru_cache(maxsize=4096)
def ref_W_star(w, eps_y, nu):
    """(W_ep)* of eq. (25) = -(5/2) int_1^w P* = 1 - F(w)."""
    eps_y, nu = _check_params(eps_y, nu)
    w = _check_nonneg(w, "w")
    return float(1 - _law(eps_y, nu).F(_mpf(w)))


@functools.lru_cache(maxsize=4096)
def ref_v1_star_at(w, eps_y, nu):
    """V1* whose maximum interference is w: sqrt(F(w))."""
    eps_y, nu = _check_params(eps_y, nu)
    w = _check_nonneg(w, "w")
    return float(_ctx.sqrt(_law(eps_y, nu).F(_mpf(w))))


def ref_omega_m_star(v1_star, eps_y, nu):
    """Maximum normalised interference w_m solving F(w_m) = V1*^2 (eq. 29)."""
    eps_y, nu = _check_params(eps_y, nu)
    v1_star = _check_nonneg(v1_star, "v1_star")
    return float(_solve(v1_star, eps_y, nu)[2])


def ref_e_star(v1_star, eps_y, nu, unloading="jcg"):
    """Coefficient of restitution e(V1*) (e = 1 for V1* <= 1)."""
    eps_y, nu = _check_params(eps_y, nu)
    v1_star = _check_nonneg(v1_star, "v1_star")
    u = _check_unloading(unloading)
    e2 = _restitution(v1_star, eps_y, nu, u)[0]
    if e2 < 0:
        raise ValueError("JCG fit (35) gives w_res > w_m here: no rebound")
    return float(_ctx.sqrt(e2))


def ref_loss_star(v1_star, eps_y, nu, unloading="jcg"):
    """1 - e^2 (fraction of the impact energy dissipated), to full relative accuracy."""
    eps_y, nu = _check_params(eps_y, nu)
    v1_star = _check_nonneg(v1_star, "v1_star")
    u = _check_unloading(unloading)
    e2, loss = _restitution(v1_star, eps_y, nu, u)[:2]
    if e2 < 0:
        raise ValueError("JCG fit (35) gives w_res > w_m here: no rebound")
    return float(loss)


def ref_residual_star(v1_star, eps_y, nu, unloading="jcg"):
    """(w_res*, R_res/R): residual interference / omega_c and residual radius / R."""
    eps_y, nu = _check_params(eps_y, nu)
    v1_star = _check_nonneg(v1_star, "v1_star")
    u = _check_unloading(unloading)
    _, _, wres, rr = _restitution(v1_star, eps_y, nu, u)
    if rr is None:
        raise ValueError("JCG fit (35) gives w_res >= w_m here: no rebound")
    return float(wres), float(rr)


# --------------------------------------------------------------------------- self-check
_CHECK_ROWS = [
    # V1*, eps_y, nu, w_m, e (JCG, 35), e (Etsion, 33)   -- MODEL.md section 6
    (10.0, 0.005, 0.33, 6.549856322605, 0.828732572622, 0.865201796636),
    (300.0, 0.001, 0.25, 126.263984325110, 0.405336002185, 0.535560693544),
    (2.2, 0.005, 0.33, 1.879049170052, 0.967494217053, 1.0),
    (2.25, 0.005, 0.33, 1.913161497590, 0.965283934588, 0.997554804946),
]


if __name__ == "__main__":
    import time

    print(f"{'V1*':>6} {'eps_y':>6} {'nu':>5} {'w_m':>22} {'e JCG':>18} {'e Etsion':>18}")
    maxd = [0.0, 0.0, 0.0]
    for v1, eps, nu, wm_t, ej_t, ee_t in _CHECK_ROWS:
        wm = ref_omega_m_star(v1, eps, nu)
        ej = ref_e_star(v1, eps, nu, "jcg")
        ee = ref_e_star(v1, eps, nu, "etsion")
        print(f"{v1:6g} {eps:6g} {nu:5g} {wm:22.15f} {ej:18.15f} {ee:18.15f}")
        for k, (a, b) in enumerate(((wm, wm_t), (ej, ej_t), (ee, ee_t))):
            maxd[k] = max(maxd[k], abs(a - b))
    print("max |diff| vs MODEL.md table: w_m %.2e  e_JCG %.2e  e_Etsion %.2e" % tuple(maxd))
    ok = maxd[0] < 1e-11 and maxd[1] < 1e-11 and maxd[2] < 1e-11
    print("P*(1.9) Hertz / JG branch:", ref_P_star(1.9, 0.005, 0.33),
          float(_law(0.005, 0.33).P_jg(_W19)))
    print("loss JCG at V1* = 1 + 1e-12:", ref_loss_star(1 + 1e-12, 0.005, 0.33))

    # timings on fresh (uncached) inputs
    _law.cache_clear()
    _solve.cache_clear()
    _restitution.cache_clear()
    vs = [1.5, 2.5, 3.7, 10.3, 31.0, 99.0, 301.0]
    t0 = time.perf_counter()
    for v in vs:
        ref_omega_m_star(v, 0.004, 0.3)
    t1 = time.perf_counter()
    print(f"ref_omega_m_star: {(t1 - t0) / len(vs) * 1e3:.1f} ms/call (incl. anchor build)")
    vs2 = [v * 1.0137 for v in vs]
    t0 = time.perf_counter()
    for v in vs2:
        ref_e_star(v, 0.004, 0.3, "jcg")
    t1 = time.perf_counter()
    print(f"ref_e_star (anchors cached): {(t1 - t0) / len(vs2) * 1e3:.1f} ms/call")
    print("OK" if ok else "MISMATCH")
