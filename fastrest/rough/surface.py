"""The user's side of rough surfaces: :class:`RoughSurface` (input checks, then the solvers of
:mod:`.explicit` and :mod:`.statistical` on forward tables from :mod:`.forward_cache`)."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, cast
from numpy.typing import ArrayLike, NDArray

if TYPE_CHECKING:
    from ..forward import ForwardData
import math
import sys

import numpy as np

from .._validation import (EDGE_TOL, OMEGA_M_STAR_MAX, ExtrapolationWarning, as_float_array, check_bool,
                           check_finite_positive, real_scalar, warn, warn_if_outside_validated)
from ..energy import f_star_kernel
from ..limits import interference_limit_message
from ..impact import Impact
from ..loading import LAWS, NAMES, LoadingLaw, resolve as resolve_loading
from ..materials import Material
from ..unloading import unloading_code, warn_if_unfitted
from . import explicit, statistical
from .common import NEEDS_TABLE, OK, check_speeds, energy_parts
from .forward_cache import ForwardCache
from .heights import GreenwoodWilliamson, gw_data
from .result import RoughImpact

__all__ = ["RoughSurface", "RHO_W_RANGE"]

#: Range of sigma/omega_c (the plasticity index squared) where the statistical model is computed:
#: heights enter the quadrature as w* = (zs - zs_d) sigma/omega_c, which loses the resolution of zs
#: (relative 1e-16 w*/(sigma/omega_c)) when sigma/omega_c is tiny.
RHO_W_RANGE = (1e-6, 1e12)


class RoughSurface:
    """A rough surface of spherical summits of radius ``R_a`` (or each its own, ``radii``), struck
    by a rigid flat.

    Every summit follows the JGM single-sphere law on loading (Jackson-Green, or with strain
    hardening Ghaednia et al. 2019: ``et_ratio``) and unloads elastically; summits do not interact
    and the bulk under them does not deform (Greenwood-Williamson assumptions).

    Parameters
    ----------
    material : fastrest.Material
        The surface's (summits') material; the flat is rigid.
    R_a : float, optional
        Summit radius of curvature (m), > 0, of every summit. Required unless ``radii`` is given.
    heights : array_like, optional
        Explicit summit heights (m), any datum, finite, at least one. The mean summit plane is
        their mean; d_min is reported from it.
    radii : array_like, optional
        Explicit surfaces only, keyword-only: each summit's radius of curvature (m), finite and
        > 0, as many as ``heights`` (:func:`fastrest.rough.from_topography` measures them). Each
        summit is normalised by its own critical values (omega_c, P_c, U_c scale as R, R^2, R^3,
        JGM eqs 4, 6, 24). Give ``R_a`` or ``radii``, not both.
    gw : GreenwoodWilliamson or dict, optional
        Statistical description (summit density, height standard deviation, nominal area, pdf).
        Exactly one of ``heights`` and ``gw``.
    et_ratio : float, optional
        Strain hardening of the summits: tangent modulus over Young's modulus Et/E (-),
        0 <= et_ratio < 1, keyword-only; default None: the material's own Et/E
        (``Material(..., Et=...)``; 0, elastic-perfectly plastic, without Et). Given for a material
        with Et > 0, it must equal that material's Et/E.
    loading : {None, "jackson-green", "ghaednia"}, optional
        Loading law of every summit (:mod:`fastrest.loading`), keyword-only; None (default) picks
        Jackson-Green for et_ratio = 0 and Ghaednia et al. (2019) above (equal to Jackson-Green bit
        for bit at et_ratio = 0).

    Attributes
    ----------
    impact_params : fastrest.Impact
        One summit against the rigid flat (its E_eff, omega_c, P_c, U_c, eps_y, nu).
    eps_y, nu : float
        Sy/E' (-) and Poisson's ratio (-) of the summits.
    et_ratio : float
        Et/E of the summits (-).
    loading : str or None
        The loading law as given (its name), None for the default.
    law : fastrest.loading.LoadingLaw
        The loading law in use (resolved from ``loading`` and ``et_ratio``).
    omega_c, P_c, U_c : float
        Critical interference (m), force (N) and energy (J) of one summit (JGM eqs 4, 6, 24); with
        ``radii``, of the reference summit, the tallest (``R_a`` is then its radius).
    heights, radii : ndarray or None
        Explicit surfaces: summit heights and radii (m) as given (``radii`` filled with ``R_a`` for
        one radius); None for a statistical surface.
    sigma : float
        Standard deviation of the summit heights (m) (of the given heights, or of the model).
    n_summits : int or float
        Number of summits (N = eta A_n for a statistical surface).
    kind : str
        "explicit" or "statistical".

    Raises
    ------
    TypeError
        If ``material`` is not a Material, ``gw`` not a GreenwoodWilliamson or dict, or a number
        (``et_ratio`` included) is not real.
    ValueError
        For R_a, heights or radii out of range, neither or both of ``heights`` and ``gw``, both
        or neither of ``R_a`` and ``radii``, ``radii`` with ``gw``, as many radii as heights not given,
        sigma/omega_c outside :data:`RHO_W_RANGE` (statistical), ``et_ratio`` outside [0, 1), an
        unknown ``loading``, or et_ratio > 0 with ``loading="jackson-green"``.

    Warns
    -----
    ValidityWarning
        Material outside the validated eps_y, nu range.

    Notes
    -----
    Summit i is at w_i* = (z_i - d)/omega_c with the flat at height d; the deepest approach solves
    (1/2) M V1^2 = U_c sum_i F(w_i) (JGM eq 29 summed over summits) and the energy returned is
    U_c sum_i R(w_i) (eq 38 per summit). Derivation and numerics: docs/rough.md.

    Examples
    --------
    >>> import fastrest
    >>> from fastrest import rough
    >>> steel = fastrest.Material(E=200e9, nu=0.3, Sy=1e9)
    >>> s = rough.RoughSurface(steel, 100e-6, gw=dict(eta=1e10, sigma=50e-9, A_n=1e-4))
    >>> 0.0 < s.impact(0.1, 0.01).e < 1.0
    True

    A strain-hardening material (Et = E/100) rebounds better (Brake unloading, the pairing the
    hardening law's peers use):

    >>> h = rough.RoughSurface(steel, 100e-6, gw=dict(eta=1e10, sigma=50e-9, A_n=1e-4), et_ratio=0.01)
    >>> h.law.name, bool(h.impact(0.1, 0.01, "brake").e > s.impact(0.1, 0.01, "brake").e)
    ('ghaednia', True)

    Summits of their own radii (m):

    >>> t = rough.RoughSurface(steel, heights=[0.0, -2e-8, -5e-8], radii=[50e-6, 200e-6, 100e-6])
    >>> t.R_a, t.radii.tolist()
    (5e-05, [5e-05, 0.0002, 0.0001])
    """

    def __init__(self, material: Material, R_a: float | None = None, heights: ArrayLike | None = None,
                 gw: GreenwoodWilliamson | dict[str, Any] | None = None, *, radii: ArrayLike | None = None,
                 et_ratio: float | None = None, loading: str | LoadingLaw | None = None) -> None:
        if not isinstance(material, Material):
            raise TypeError("material must be a fastrest.Material")
        self.material = material
        own = float(getattr(material, "et_ratio", 0.0))  # Et/E of a Material(..., Et=...)
        if et_ratio is None:
            et_ratio = own
        elif own > 0.0 and abs(float(real_scalar(et_ratio, "et_ratio")) - own) > EDGE_TOL * own:
            raise ValueError(f"et_ratio = {et_ratio!r} contradicts the material's Et/E = {own!r}: give the "
                             "tangent modulus once (Material(..., Et=...) or et_ratio=)")
        self.et_ratio = own if own > 0.0 else float(real_scalar(et_ratio, "et_ratio"))
        self.law = resolve_loading(loading, self.et_ratio)  # validates et_ratio and loading
        self.loading = None if loading is None else self.law.name
        if heights is None and gw is None:
            raise TypeError("give heights= (explicit summits) or gw= (statistical): neither was given")
        if heights is not None and gw is not None:
            raise ValueError("give exactly one of heights= (explicit summits) and gw= (statistical)")
        if radii is not None:
            if R_a is not None:
                raise ValueError("give R_a (one radius for every summit) or radii= (each summit's), not both")
            if heights is None:
                raise ValueError("radii= needs explicit summits (heights=); a statistical surface (gw=) has "
                                 "one radius, R_a")
            heights = self._heights(heights)
            R_a = self._check_radii(material, heights, radii)
        elif R_a is None:
            raise TypeError("give R_a (m, the summit radius) or radii= (m, each summit's): neither was given")
        self.R_a = float(check_finite_positive(real_scalar(R_a, "R_a"), "R_a", "(m, summit radius)"))
        try:
            self.impact_params = Impact(material, self.R_a, mass=1.0)  # mass unused here
        except ValueError as exc:
            raise ValueError(f"R_a = {self.R_a!r} m: {exc}") from None
        ip = self.impact_params
        self.eps_y, self.nu = float(ip.eps_y), float(ip.nu)
        warn_if_outside_validated(self.eps_y, self.nu)
        self.omega_c, self.P_c, self.U_c = ip.omega_c, ip.P_c, ip.U_c
        self._tables = ForwardCache(self.eps_y, self.nu, self.et_ratio, self.law.name)
        if heights is not None:
            self._init_explicit(heights if radii is not None else self._heights(heights))  # checked once
        else:
            self._init_statistical(gw)

    # defaults of a surface pickled before strain hardening (its __dict__ lacks them)
    et_ratio: float = 0.0
    loading: str | None = None
    law: LoadingLaw = LAWS[NAMES[0]]

    # radii over the reference radius of an explicit surface with radii=; None: one radius (and for
    # a surface pickled before radii)
    _r: NDArray[np.float64] | None = None

    # set by _init_explicit or _init_statistical: one of heights and gw is None
    kind: str
    heights: Any
    gw: Any
    n_summits: float

    @staticmethod
    def _heights(heights):
        z = np.array(as_float_array(heights, "heights"), dtype=np.float64).ravel()
        if z.size == 0:
            raise ValueError("heights is empty: a surface needs at least one summit")
        if not np.all(np.isfinite(z)):
            raise ValueError("heights must be finite (m)")
        return z

    def _check_radii(self, material, z, radii):
        """The reference radius R_a of a surface with heights ``z`` (checked) and ``radii``. Unless
        every radius is the same (then the surface is one of R_a, bit for bit), sets ``_radii`` and
        ``_r``, the radii over the reference radius (the tallest summit's, so that its r is exactly
        1), put in the kernels' order by :meth:`_init_explicit`."""
        R = np.array(as_float_array(radii, "radii"), dtype=np.float64).ravel()
        if R.size != z.size:
            raise ValueError(f"radii must give one radius (m) per summit: {z.size} heights, {R.size} radii")
        bad = ~(np.isfinite(R) & (R > 0.0))
        if np.any(bad):
            k = int(np.flatnonzero(bad)[0])
            raise ValueError(f"radii (m, summit radii of curvature) must be finite and > 0; radii[{k}] = {float(R[k])!r}")
        for k in (int(R.argmin()), int(R.argmax())):  # every summit's critical values exist
            try:
                Impact(material, float(R[k]), mass=1.0)
            except ValueError as exc:
                raise ValueError(f"radii[{k}] = {float(R[k])!r} m: {exc}") from None
        R_ref = float(R[int(z.argmax())])
        R.setflags(write=False)  # .radii: the surface computes with these (a copy of the input)
        if not np.all(R == R_ref):
            self._r, self._radii = R / R_ref, R
        return R_ref

    @property
    def radii(self) -> NDArray[np.float64] | None:
        """Summit radii of curvature (m) of an explicit surface (``R_a`` repeated for one radius);
        None for a statistical surface."""
        if self.kind != "explicit":
            return None
        if self._r is None:
            return np.full(self.heights.size, self.R_a)
        return cast(NDArray[np.float64], self._radii)

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        for a in (state.get("heights"), state.get("_radii")):  # read-only again after unpickling
            if isinstance(a, np.ndarray):
                a.setflags(write=False)

    @property
    def _descending(self):
        """The kernels' heights are sorted tallest first (a surface with radii)."""
        return self._r is not None

    def _init_explicit(self, z):
        z.setflags(write=False)  # .heights: the surface computes with these (a copy of the input)
        self.kind, self.heights, self.gw = "explicit", z, None
        self.z_top = float(z.max())
        with np.errstate(over="ignore", invalid="ignore"):
            self.z_mean = float(z.mean())
            self.sigma = float(z.std())
        if not (math.isfinite(self.sigma) and math.isfinite(self.z_mean)):
            raise ValueError("heights span more than the range of a float64 (m): their standard "
                             "deviation overflows")
        self.n_summits = z.size
        h = (z - self.z_top) / self.omega_c
        if self._r is None:
            self._h = np.ascontiguousarray(h)
        else:  # tallest first (z.argmax(), the first, leads): the sums stop at the first summit out of contact
            order = np.argsort(-z, kind="stable")
            self._h, self._r = np.ascontiguousarray(h[order]), np.ascontiguousarray(self._r[order])

    def _init_statistical(self, gw):
        if isinstance(gw, dict):
            gw = GreenwoodWilliamson(**gw)
        if not isinstance(gw, GreenwoodWilliamson):
            raise TypeError("gw must be a GreenwoodWilliamson or a dict of its parameters")
        self.kind, self.heights, self.gw = "statistical", None, gw
        self.n_summits = gw.n_summits
        self._gwdata, self.sigma = gw_data(gw, self.omega_c)
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
        law = "".join(f", {k}={v!r}" for k, v in self._law_params().items())
        radius = (f"R_a={self.R_a!r}" if self._r is None
                  else f"radii {float(self._radii.min())!r} to {float(self._radii.max())!r}")
        return (f"RoughSurface({self.material!r}, {radius}, {desc}, sigma={self.sigma!r}, "
                f"psi={self.plasticity_index:.4g}{law})")

    def _law_params(self):
        """et_ratio and loading where not the defaults (for repr and :meth:`params`)."""
        p: dict[str, Any] = {}
        if self.et_ratio != 0.0:
            p["et_ratio"] = self.et_ratio
        if self.loading is not None:
            p["loading"] = self.loading
        return p

    @property
    def plasticity_index(self) -> float:
        """psi = sqrt(sigma / omega_c) (-): Jackson & Green's form of the Greenwood-Williamson index.

        Equal to (E'/H) sqrt(sigma / R_a) with the hardness-like H = (pi/2) C(nu) Sy, since
        omega_c = (pi C Sy / (2 E'))^2 R_a (JGM eq 4); sigma is the summit-height standard deviation.

        Examples
        --------
        >>> import fastrest
        >>> from fastrest import rough
        >>> s = rough.RoughSurface(fastrest.Material(200e9, 0.3, 1e9), 1e-4, gw=dict(eta=1e10, sigma=5e-8))
        >>> round(s.plasticity_index, 3)
        1.937
        """
        return math.sqrt(self.sigma / self.omega_c)

    def plasticity_index_gw(self, H: float) -> float:
        """Greenwood & Williamson's plasticity index psi = (E'/H) sqrt(sigma / R_a) (-).

        Parameters
        ----------
        H : float
            Hardness (Pa), > 0.

        Returns
        -------
        float
            psi (-); equal to :attr:`plasticity_index` for H = (pi/2) C(nu) Sy.

        Raises
        ------
        ValueError
            If H is not finite and > 0.

        Examples
        --------
        >>> import fastrest
        >>> from fastrest import rough
        >>> s = rough.RoughSurface(fastrest.Material(200e9, 0.3, 1e9), 1e-4, heights=[0.0, 1e-7])
        >>> s.plasticity_index_gw(2.8e9) > 0
        True
        """
        H = float(check_finite_positive(H, "H", "(Pa, hardness)"))
        return self.impact_params.E_eff / H * math.sqrt(self.sigma / self.R_a)

    def params(self) -> dict[str, Any]:
        """The arguments that rebuild this surface.

        Returns
        -------
        dict
            material, R_a (m) or radii (m), and heights (m) or gw, and et_ratio (-) and loading
            where not the defaults: ``RoughSurface(**s.params())`` is an equal surface (used by
            :func:`fastrest.rough.sweep` to ship surfaces to Dask).

        Examples
        --------
        >>> import fastrest
        >>> from fastrest import rough
        >>> s = rough.RoughSurface(fastrest.Material(200e9, 0.3, 1e9), 1e-4, heights=[0.0, 1e-8])
        >>> sorted(rough.RoughSurface(**s.params()).params())
        ['R_a', 'heights', 'material']
        """
        p: dict[str, Any] = {"material": self.material}
        if self._r is None:
            p["R_a"] = self.R_a
        else:
            p["radii"] = self._radii
        if self.kind == "explicit":
            p["heights"] = self.heights
        else:
            p["gw"] = self.gw
        p.update(self._law_params())
        return p

    def forward(self, unloading: str = "jcg", *, w_max: float = 0.0, extrapolate: bool = False) -> ForwardData:
        """The surface's cached forward table: :meth:`fastrest.rough.forward_cache.ForwardCache.get`.

        Parameters
        ----------
        unloading : {"jcg", "etsion", "brake"}
            Unloading model (a table per model).
        w_max : float
            Largest w* (-) the table must serve; the cached table is rebuilt larger if needed.
        extrapolate : bool
            Allow w_max past 425 (up to a/R = 1).

        Returns
        -------
        ForwardData
            Loading energy, force and unloading of one summit, JGM eqs (9), (14), (19), (25),
            (33)/(35), (38) (:mod:`fastrest.forward`), under the surface's loading law; built
            without the contact law's cells (``contact_cells=False``: for
            ``fastrest.jit.contact_force`` build a law with :func:`fastrest.contact_law`).

        Raises
        ------
        ValueError
            Unknown unloading model, or w_max past the model's range.
        """
        return self._tables.get(unloading, w_max=w_max, extrapolate=extrapolate)

    def impact(self, V1: ArrayLike, M: float, unloading: str = "jcg", *, extrapolate: bool = False) -> RoughImpact:
        """Impact of a rigid flat of mass ``M`` at speed ``V1`` on the surface.

        Parameters
        ----------
        V1 : float or array_like
            Normal approach speed (m/s), finite and > 0 (at V1 = 0 nothing touches: ValueError).
        M : float
            Mass of the flat (kg), > 0 (against a fixed surface; use the reduced mass for two free
            bodies).
        unloading : {"jcg", "etsion", "brake"}
            Residual interference model of every summit, JGM eq (35), (33) or Brake's
            (:mod:`fastrest.unloading`).
        extrapolate : bool
            Allow summits past w* = 425 (JGM's range), up to a/R = 1.

        Returns
        -------
        RoughImpact
            e_s, 1 - e_s^2, deepest approach, force, contact counts, energies (shaped as V1).

        Raises
        ------
        ValueError
            Invalid input, an impact that drives summits past the model's range, or (statistical)
            an impact too light for the height distribution to resolve.
        TypeError
            Non-numeric V1 or M, or a non-boolean extrapolate.

        Warns
        -----
        ExtrapolationWarning
            With ``extrapolate=True``, when summits pass w* = 425.

        Notes
        -----
        With E = (V1/V_c)^2 = M V1^2/(2 U_c): sum_i F(w_i) = E at the deepest approach (JGM eq 29
        per summit) and 1 - e_s^2 = sum_i L(w_i)/E, L = F - R with R from eq (38). Explicit
        summits keep the relative accuracy of 1 - e_s^2 near the onset of yield (the solver
        carries w* - 1 of the tallest summit, :mod:`fastrest.rough.explicit`).

        Examples
        --------
        >>> import fastrest
        >>> from fastrest import rough
        >>> s = rough.RoughSurface(fastrest.Material(200e9, 0.3, 1e9), 1e-4, heights=[0.0, 1e-8, 3e-8])
        >>> r = s.impact([0.01, 0.1], 1e-3)
        >>> bool(r.e[0] > r.e[1])
        True
        """
        return self._impact(V1, M, unloading, extrapolate, self._solve_explicit)

    def _impact(self, V1, M, unloading, extrapolate, solve_explicit):
        """:meth:`impact` with the explicit solver ``solve_explicit(e_hi, e_lo, unloading,
        extrapolate, M)`` -> (8, n) (:meth:`_solve_explicit`; ``fastrest.cuda.rough_impact`` passes
        its GPU one)."""
        unloading_code(unloading)
        M = float(check_finite_positive(real_scalar(M, "M"), "M", "(kg, mass of the flat)"))
        extrapolate = check_bool(extrapolate, "extrapolate")
        flat, shape = check_speeds(V1)
        warn_if_unfitted(unloading, self.et_ratio)  # JCG/Etsion with hardening: an extrapolation
        e_hi, e_lo = energy_parts(flat, M, self.U_c)  # (V1/V_c)^2: impact energy over U_c
        bad = ~(np.isfinite(e_hi) & (e_hi >= sys.float_info.min))
        if np.any(bad):
            k = int(np.flatnonzero(bad)[0])
            raise ValueError(
                f"the impact energy (1/2) M V1^2 at V1 = {float(flat[k])!r} m/s, M = {M!r} kg is "
                f"{'too large' if not e_hi[k] < math.inf else 'too small'} against one summit's critical energy U_c = {self.U_c!r} J: "
                f"(V1/V_c)^2 = {float(e_hi[k])!r} must be a finite, normal double")
        self._check_energy_capacity(flat, M, e_hi, extrapolate)
        if flat.size == 0:
            raw = np.zeros((8, 0))
        elif self.kind == "explicit":
            raw = solve_explicit(e_hi, e_lo, unloading, extrapolate, M)
        else:
            raw = self._solve_statistical(e_hi, unloading, extrapolate, M)
        out = self._assemble(flat, M, e_hi, raw)
        if extrapolate and np.any(out["w_star_max"] > OMEGA_M_STAR_MAX):
            warn(f"summits loaded past w* = {OMEGA_M_STAR_MAX:g}, the largest interference "
                 f"JGM computed; the {self.law.short} law is not validated there", ExtrapolationWarning)

        def shaped(a):
            a = a.reshape(shape)
            return a.item() if a.ndim == 0 else a

        return RoughImpact(V1=shaped(flat), M=M, unloading=unloading, kind=self.kind,
                           **{k: shaped(a) for k, a in out.items()})

    def _check_energy_capacity(self, flat, M, e_hi, extrapolate):
        """ValueError naming V1 and M, with their range, for an impact energy above what all N
        summits absorb with each at the end of the model (N F(w*_end) U_c: a bound, as every summit
        lies at or below the tallest). Such an impact is certainly past the model's range; below
        the bound the solver finds out (and says so) itself."""
        w_end = self._tables.limit(extrapolate)
        # sum of the summits' U_c over the reference one: N for one radius
        weight = float(self.n_summits) if self._r is None else float(np.sum(self._r**3))
        cap = weight * f_star_kernel(w_end, self.eps_y, self.nu, self.law.code, self.et_ratio)
        over = e_hi > cap
        if not np.any(over):
            return
        k = int(np.flatnonzero(over)[0])
        v, e_j = float(flat[k]), float(e_hi[k]) * self.U_c
        cap_j = cap * self.U_c
        raise ValueError(
            f"the impact at V1 = {v!r} m/s (M = {M!r} kg) drives summits past the model's range: its energy "
            f"(1/2) M V1^2 = {e_j:.6g} J exceeds {cap_j:.6g} J, the most the surface's N = {self.n_summits:.6g} "
            f"summits can absorb before {'the tallest' if self._r is None else 'one'} reaches w* = {w_end:.6g} "
            f"({'a/R = 1' if extrapolate else 'JGM range'}). V1 must be below "
            f"{math.sqrt(2.0 * cap_j / M):.6g} m/s at this M (M below {2.0 * cap_j / v**2:.6g} kg at this V1)")

    # --- solving: a Hertz estimate, then the loading law on a forward table grown as needed -------

    def _speed(self, energy, M):
        """V1 (m/s) of the impact energy ``energy`` (over U_c): for messages."""
        return float(np.sqrt(2.0 * self.U_c * energy / M))

    def _solve(self, run, w_guess, energy, unloading, extrapolate, M):
        """:meth:`ForwardCache.solve` with this surface's messages."""
        note = None
        if self.kind == "statistical":
            def note(k):
                return self._capacity_note(energy[k], M, unloading, extrapolate)
        return self._tables.solve(run, w_guess, unloading, extrapolate,
                                  lambda k: f"V1 = {self._speed(energy[k], M)!r} m/s (M = {M!r} kg)", note)

    def _capacity_note(self, energy, M, unloading, extrapolate):
        """What the statistical surface absorbs before its tallest integrated summits pass the
        law's end, the largest V1 (and M) below it, and what to change (text for messages)."""
        w_end = self._tables.limit(extrapolate)
        data = self._tables.get(unloading, w_max=w_end, extrapolate=extrapolate)
        return statistical.capacity_note(data, self._gwdata, w_end, self.sigma, self.omega_c, self.R_a, self.U_c,
                                         self.n_summits, self._speed(energy, M), M)

    def _solve_explicit(self, e_hi, e_lo, unloading, extrapolate, M):
        h, r, desc = self._h, self._r, self._descending
        # the Hertz estimate starts every solve (independent of the table held, so results do not
        # depend on what the surface computed before); JG/Ghaednia summits sink deeper: table to 2x
        x0, d0 = explicit.hertz_estimate(h, e_hi, e_lo, r, desc)
        return self._solve(
            lambda data, w_model: explicit.solve_impacts(data, h, e_hi, e_lo, x0, d0, w_model, r, desc),
            2.0 * float(explicit.largest_w(h, r, float(x0.max()))), e_hi, unloading, extrapolate, M)

    def _solve_statistical(self, energy, unloading, extrapolate, M):
        g = self._gwdata
        statistical.check_resolved(g, energy, lambda k: f"V1 = {self._speed(energy[k], M)!r} m/s")
        # JG (and Ghaednia) summits sink deeper than Hertz ones, bar a few % near w* = 1.9: a Hertz
        # estimate past HERTZ_CAP x the law's end (a/R = 1) means the impact itself is past it
        w_end = self._tables.limit(True)
        hz = statistical.hertz_estimate(g, energy, statistical.HERTZ_CAP * w_end)
        if np.any(hz[0] == NEEDS_TABLE):
            k = int(np.flatnonzero(hz[0] == NEEDS_TABLE)[0])
            raise ValueError(f"the impact at V1 = {self._speed(energy[k], M)!r} m/s (M = {M!r} kg) drives "
                             f"summits to a w* that {interference_limit_message(w_end * 1.5, self.eps_y, self.nu, True)}"
                             + self._capacity_note(energy[k], M, unloading, extrapolate))
        if np.any(hz[0] != OK):
            raise RuntimeError("rough-surface solver (Hertz estimate) did not converge (please report)")
        zs0 = hz[1].copy()
        return self._solve(
            lambda data, w_model: statistical.solve_impacts(data, g, energy, zs0, w_model),
            1.5 * float(hz[2].max()), energy, unloading, extrapolate, M)

    def _assemble(self, v, M, energy, raw):
        """The result fields from a solver output (rows: status, w* needed, position, w* at the
        top, sum P*, sum L, in contact, yielded; per summit for a statistical surface)."""
        pos, w_top, p_sum, l_sum, n_c, n_y = raw[2:8]
        if self.kind == "explicit":
            d_min = (self.z_top - self.z_mean) - pos * self.omega_c
            n_c, n_y = n_c.astype(np.int64), n_y.astype(np.int64)
        else:
            n_tot = self.gw.n_summits
            d_min = pos * self.sigma
            n_c, n_y = n_tot * n_c, n_tot * n_y
            p_sum, l_sum = n_tot * p_sum, n_tot * l_sum
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
