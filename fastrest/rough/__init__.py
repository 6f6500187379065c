"""Impact of a rigid flat on a rough surface of JGM asperities (Greenwood-Williamson summits).

A rigid flat of mass M moves at V1 towards a rough surface covered with spherical asperities
(summits) of radius R_a, made of the surface's material. Every summit follows the JGM single-
sphere law on loading (Jackson-Green; with strain hardening, ``et_ratio`` = Et/E > 0, Ghaednia et
al. 2019) and unloads elastically; summits do not interact and the bulk under them
does not deform. With U_c, P_c, omega_c of one summit (:class:`fastrest.Impact` with radius R_a,
rigid flat; JGM eqs 4, 6, 24):

* summit heights z_i are measured upwards from the mean summit plane; the flat's surface is at
  distance d above it; summit i touches when z_i > d, at w_i* = (z_i - d)/omega_c;
* deepest approach d_min: (1/2) M V1^2 = U_c sum_i F(w_i) (F: :func:`fastrest.forward.F_forward`,
  JGM eqs 19, 25); the sum grows monotonically as d falls, with slope minus the total force;
* energy returned: U_c sum_i R(w_i), R = P*(w)(w - w_res*(w)) (JGM eq 38 with eq 35, 33 or
  Brake's), evaluated as e_s^2 = 1 - sum_i L(w_i)/(V1/V_c)^2 with L = F - R without cancellation
  (an all-elastic impact gives e_s = 1 exactly).

Two descriptions of a surface: explicit summit heights (an array; :func:`gaussian_summits` draws a
Gaussian set) or statistical (:class:`GreenwoodWilliamson`: summit density, height standard
deviation, nominal area, height pdf). Derivation, numerics and validation: docs/rough.md.

Where things are:

* :mod:`.surface`: :class:`RoughSurface` (input checks, the impact); :mod:`.result`: :class:`RoughImpact`;
* :mod:`.forward_cache`: a surface's forward tables (:mod:`fastrest.forward`), grown as impacts need;
* :mod:`.heights`: :func:`gaussian_summits`, :class:`GreenwoodWilliamson` and its tabulation;
* :mod:`.explicit`: the solver over explicit heights (parallel sums over summits);
* :mod:`.statistical`: the solver over a height distribution, on the expectations over the
  heights of :mod:`.expectations` (quadrature);
* :mod:`.common`: what both share (one summit's terms, the impact energy);
* :mod:`.sweeps`: :func:`sweep`, many surfaces here or on a Dask cluster;
* :mod:`.topography`: :class:`Topography`, :func:`load_topography` (a measured height map in SI
  units, read with the optional SurfaceTopography: ``pip install "fastrest[topography]"``);
* :mod:`.summits`: :func:`find_summits`, :func:`topography_summits`, :func:`from_topography` (a map's
  8-neighbour summits, their radii of curvature, the explicit surface they make); :mod:`.cli`:
  ``fastrest rough FILE`` (docs/topography.md);
* :mod:`.spectral`: :func:`spectral_moments`, :func:`gw_from_moments`, :func:`spectral_surface` (the
  Greenwood-Williamson surface of a map's spectral moments, Nayak 1971, McCool 1986;
  docs/rough-spectral.md).
"""
from .heights import GreenwoodWilliamson, gaussian_summits
from .result import RoughImpact
from .spectral import SpectralGW, SpectralMoments, gw_from_moments, spectral_moments, spectral_surface
from .summits import TopographySummits, find_summits, from_topography, topography_summits
from .surface import RoughSurface
from .sweeps import surface_from_params, sweep
from .topography import Topography, load_topography

__all__ = ["RoughSurface", "GreenwoodWilliamson", "RoughImpact", "gaussian_summits", "sweep",
           "surface_from_params", "Topography", "load_topography", "find_summits", "topography_summits",
           "from_topography", "TopographySummits", "spectral_moments", "gw_from_moments", "spectral_surface",
           "SpectralMoments", "SpectralGW"]
