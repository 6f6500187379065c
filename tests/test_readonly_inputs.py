"""Read-only, strided or byte-swapped inputs reach the jit array kernels with the warm-up's Numba type.

A read-only array (``a.flags.writeable = False``: memory-mapped files, xarray) is a different Numba
type from a writeable one: handed to a kernel as it is, it compiles the kernel again (16 s for
``fastrest.e_star`` after ``fastrest warmup``). Every public array entry point goes through
:func:`fastrest._validation.kernel_array`; each test calls the entry point with a writeable array,
then with a read-only one, and checks that the array kernel's dispatcher gained no signature (no
timing: independent of this process's compile state).
"""
import numpy as np
import pytest

import fastrest
from fastrest import contact, direct, energy
from fastrest.scene import scene_array
from fastrest.critical import c_of_nu
from fastrest.curve_data import curve_array
from fastrest.tables.kernel import table_array
from fastrest.tables.w_star import loading_energy_array


def _readonly(a):
    a = np.array(a, dtype=np.float64)
    a.flags.writeable = False
    return a


def _variants(a):
    """Read-only, strided (every other element) and big-endian versions of ``a``."""
    a = np.asarray(a, dtype=np.float64)
    strided = np.repeat(a, 2)[::2]
    return [_readonly(a), strided, a.astype(">f8")]


def _no_new_signature(kernel, call, a):
    """``call(a)`` with a writeable ``a`` then with its variants: same results, no new signature."""
    want = call(np.array(a, dtype=np.float64))
    n = len(kernel.signatures)
    for b in _variants(a):
        got = call(b)
        assert len(kernel.signatures) == n, f"{kernel.__name__} compiled again for {b.dtype}, {b.flags}"
        np.testing.assert_array_equal(got, want)


V = [2.0, 5.0, 20.0]


def test_kernel_array_copies_only_when_needed():
    from fastrest._validation import kernel_array

    a = np.arange(6.0).reshape(2, 3)
    assert np.shares_memory(kernel_array(a), a)
    r = _readonly(a)
    k = kernel_array(r)
    assert k.flags.writeable and k.flags.c_contiguous and k.ndim == 1 and not np.shares_memory(k, r)
    np.testing.assert_array_equal(k, r.ravel())


@pytest.mark.parametrize("fn", [fastrest.e_star, fastrest.omega_m_star, fastrest.loss_star])
def test_default_table(fn):
    _no_new_signature(table_array, lambda v: fn(v, 0.005, 0.3), V)
    _no_new_signature(table_array, lambda e: fn(5.0, e, 0.3), [0.005, 0.002, 0.001])


def test_table_w_star():
    t = fastrest.load_table()
    _no_new_signature(loading_energy_array, lambda w: t.W_star(w, 0.005, 0.3), [1.0, 5.0, 20.0])


def test_curve():
    c = fastrest.curve(0.005, 0.33, v_max=30.0)
    _no_new_signature(curve_array, c.e, V)
    _no_new_signature(curve_array, c.loss, V)


def test_scene():
    s = fastrest.scene([(0.005, 0.33), (0.001, 0.25)], v_max=30.0)
    _no_new_signature(scene_array, lambda v: s.e(v, 1), V)
    _no_new_signature(scene_array, lambda k: s.e(5.0, k), [0.0, 1.0, 1.0])
    k = np.array([0, 1, 1])
    n = len(scene_array.signatures)
    k.flags.writeable = False
    s.e(5.0, k)
    assert len(scene_array.signatures) == n


def test_direct_and_impact():
    _no_new_signature(direct.impact_array, lambda v: direct.e_exact(v, 0.005, 0.33), V)
    _no_new_signature(direct.impact_array, lambda n: direct.omega_m_exact(5.0, 0.005, n), [0.3, 0.33])
    impact = fastrest.Impact(fastrest.Material(200e9, 0.33, 1.12e9), 0.01, mass=0.0327)
    _no_new_signature(direct.impact_array, impact.e, [0.5, 1.0, 2.0])


def test_contact_and_energy():
    _no_new_signature(contact._p_star_array, lambda w: fastrest.P_star(w, 0.005, 0.33), [0.5, 5.0])
    _no_new_signature(contact._a_star_array, lambda w: fastrest.A_star(w, 0.005, 0.33), [0.5, 5.0])
    _no_new_signature(energy._f_star_array, lambda w: fastrest.loading_energy(w, 0.005, 0.33), [0.5, 5.0])
    _no_new_signature(c_of_nu, fastrest.poisson_factor, [0.2, 0.3, 0.4])


def test_rough_surface():
    from fastrest.rough import RoughSurface, gaussian_summits
    from fastrest.rough.common import _energy_low_array

    steel = fastrest.Material(200e9, 0.3, 1e9, rho=7800.0)
    s = RoughSurface(steel, 1e-4, heights=gaussian_summits(20, 1e-6, seed=1))
    _no_new_signature(_energy_low_array, lambda v: s.impact(v, 1e-3).e, [0.01, 0.02])
