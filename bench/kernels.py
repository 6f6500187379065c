"""Numba loops the benchmarks time: what a user's own @njit code calling fastrest.jit looks like."""
import numba as nb

from fastrest import jit as frj
from fastrest.models import jgm_fit_etsion_kernel, jgm_fit_jcg_kernel

__all__ = ["curve_loop", "curve_prange", "curve_chain", "fit_loop", "fit_chain", "fit_loop_mm", "fit_chain_mm",
           "fit45_loop", "table_loop", "table_chain", "scene_loop"]


# --- Curve (one material) -----------------------------------------------------------------------

@nb.njit(cache=True)
def curve_loop(data, v, out):
    """Throughput: independent calls of e_curve in a user's loop."""
    for i in range(v.size):
        out[i] = frj.e_curve(data, v[i])


@nb.njit(cache=True, parallel=True)
def curve_prange(data, v, out):
    """The same loop with prange (threads set by numba.set_num_threads)."""
    for i in nb.prange(v.size):
        out[i] = frj.e_curve(data, v[i])


@nb.njit(cache=True)
def curve_chain(data, v):
    """Latency: each call's speed depends on the previous result (v[i] - 1e-9 e; v[i] >= 1)."""
    x = 0.0
    for i in range(v.size):
        x = frj.e_curve(data, v[i] - 1e-9 * x)
    return x


# --- the closed-form fit (42)-(44), the speed reference -----------------------------------------

@nb.njit(cache=True)
def fit_loop(v, eps_y, out):
    for i in range(v.size):
        out[i] = jgm_fit_jcg_kernel(v[i], eps_y)


@nb.njit(cache=True)
def fit_chain(v, eps_y):
    x = 0.0
    for i in range(v.size):
        x = jgm_fit_jcg_kernel(v[i] - 1e-9 * x, eps_y)
    return x


@nb.njit(cache=True)
def fit_loop_mm(v, eps_y, out):
    for i in range(v.size):
        out[i] = jgm_fit_jcg_kernel(v[i], eps_y[i])


@nb.njit(cache=True)
def fit_chain_mm(v, eps_y):
    x = 0.0
    for i in range(v.size):
        x = jgm_fit_jcg_kernel(v[i] - 1e-9 * x, eps_y[i])
    return x


@nb.njit(cache=True)
def fit45_loop(v, eps_y, out):
    """JGM eq (45) (Etsion unloading fit) over arrays, per-point eps_y."""
    for i in range(v.size):
        out[i] = jgm_fit_etsion_kernel(v[i], eps_y[i])


# --- multi-material table -------------------------------------------------------------------------

@nb.njit(cache=True)
def table_loop(tab, v, eps_y, nu, out):
    for i in range(v.size):
        out[i] = frj.e_table(tab, v[i], eps_y[i], nu[i], frj.JCG)


@nb.njit(cache=True)
def table_chain(tab, v, eps_y, nu):
    x = 0.0
    for i in range(v.size):
        x = frj.e_table(tab, v[i] - 1e-9 * x, eps_y[i], nu[i], frj.JCG)
    return x


@nb.njit(cache=True)
def scene_loop(scene, k, v, out):
    for i in range(v.size):
        out[i] = frj.e_material(scene, v[i], k[i])
