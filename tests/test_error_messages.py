"""Errors of the right type that name the Python parameter (and its range).

Each case below failed on the code before the fix: the wrong exception type, a message that did
not name the parameter, an internal exception passed on as text, or no error at all.
"""
import math

import numpy as np
import pytest

import fastrest
from fastrest import rough

STEEL = fastrest.Material(200e9, 0.3, 1e9, rho=7800.0)


@pytest.mark.parametrize("n", [None, "5", True, 1 + 0j, np.True_, b"5"], ids=repr)
def test_gaussian_summits_count_not_a_number_is_type_error(n):
    """Was ValueError; a bool is not a count."""
    with pytest.raises(TypeError, match=r"\bn\b"):
        rough.gaussian_summits(n, 1e-6)


@pytest.mark.parametrize("n", [0, 2.5, -3, 10**10])
def test_gaussian_summits_count_out_of_range_is_value_error(n):
    with pytest.raises(ValueError, match=r"\bn\b.*\[1, 1000000000\]"):
        rough.gaussian_summits(n, 1e-6)


def test_gaussian_summits_negative_seed_names_seed():
    """Was NumPy's 'expected non-negative integer'."""
    with pytest.raises(ValueError, match="seed"):
        rough.gaussian_summits(10, 1e-6, seed=-1)
    with pytest.raises(TypeError, match="seed"):
        rough.gaussian_summits(10, 1e-6, seed=True)
    with pytest.raises(ValueError, match="seed"):
        rough.gaussian_summits(10, 1e-6, seed=2.5)
    with pytest.raises(TypeError, match="seed"):
        rough.gaussian_summits(10, 1e-6, seed="a")
    a, b = rough.gaussian_summits(10, 1e-6, seed=3), rough.gaussian_summits(10, 1e-6, seed=np.int64(3))
    np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(a, rough.gaussian_summits(10, 1e-6, seed=np.random.default_rng(3)))


def test_gaussian_summits_huge_sigma_is_refused():
    """sigma = 1.7e308 returned infinite heights (1.8e308 is already inf as a Python float)."""
    for sigma in (1.7e308, 1e307, 1.8e308):
        with pytest.raises(ValueError, match="sigma"):
            rough.gaussian_summits(5, sigma)
    assert np.all(np.isfinite(rough.gaussian_summits(1000, rough.heights.SIGMA_SAMPLE_MAX, seed=0)))


@pytest.mark.parametrize("materials", [5, 2.5, None, "ab", object()], ids=["5", "2.5", "None", "ab", "object"])
def test_scene_materials_not_a_sequence(materials):
    """scene(5) said "'int' object is not iterable"."""
    with pytest.raises(TypeError, match="materials"):
        fastrest.scene(materials)


def test_scene_material_errors_name_materials():
    with pytest.raises(TypeError, match=r"materials\[1\]"):
        fastrest.scene([(0.005, 0.33), 5])
    with pytest.raises(ValueError, match=r"materials\[0\]"):
        fastrest.scene([(0.005, 0.33, 1.0)])
    with pytest.raises(TypeError, match=r"materials\[0\].*nu"):
        fastrest.scene([(0.005, True)])
    with pytest.raises(ValueError, match="materials"):
        fastrest.scene([])
    with pytest.raises(TypeError, match="curves"):
        fastrest.Scene(5)
    with pytest.raises(TypeError, match=r"curves\[0\]"):
        fastrest.Scene([(0.005, 0.33)])


def test_impact_outside_double_precision_names_the_parameter():
    """Leaked "ZeroDivisionError('division by zero')" as the scale's value."""
    with pytest.raises(ValueError) as info:
        fastrest.Impact(fastrest.Material(1e-300, 0.3, 5e-303, rho=7800), 0.01)
    msg = str(info.value)
    assert "Error(" not in msg
    assert "sphere.E = 1e-300 Pa" in msg and "sphere.Sy = 5e-303 Pa" in msg and "units" in msg
    with pytest.raises(ValueError, match=r"^R = 1e\+200 m.*units"):
        fastrest.Impact(fastrest.Material(2e11, 0.3, 1e9), 1e200, mass=1.0)
    with pytest.raises(ValueError, match=r"^sphere.E = 1e\+300 Pa"):
        fastrest.Impact(fastrest.Material(1e300, 0.3, 1e9), 0.01, mass=1.0)
    with pytest.raises(ValueError, match=r"sphere2.E = 1e-300 Pa"):
        fastrest.Impact.two_spheres(STEEL, 0.01, fastrest.Material(1e-300, 0.3, 1e9), 0.01, 1.0, 1.0)


@pytest.mark.parametrize("surface", ["explicit", "statistical"])
def test_rough_impact_past_the_range_names_V1_and_M(surface):
    """RoughSurface(...).impact(0.01, 1e300) said "did not converge (please report)" (RuntimeError)."""
    if surface == "explicit":
        s = rough.RoughSurface(STEEL, 1e-4, heights=rough.gaussian_summits(200, 1e-6, seed=1))
    else:
        s = rough.RoughSurface(STEEL, 1e-4, gw=dict(eta=1e10, sigma=1e-6, A_n=1e-4))
    with pytest.raises(ValueError, match=r"V1 = 0.01 m/s \(M = 1e\+300 kg\).*V1 must be below .* m/s at this M "
                                         r"\(M below .* kg at this V1\)"):
        s.impact(0.01, 1e300)


def test_rough_surface_without_summits_is_type_error():
    with pytest.raises(TypeError, match="heights"):
        rough.RoughSurface(STEEL, 1e-4)
    with pytest.raises(TypeError, match="sigma"):
        rough.GreenwoodWilliamson(eta=1e10, A_n=1e-4)


def test_jit_errors_never_leak_into_python_messages():
    """critical_scales of an impact far outside double precision: NaN inside, a named error outside."""
    from fastrest import jit as frj

    s = frj.critical_scales(1e-300, 0.3, 5e-303, 0.01, 0.03, math.inf, 0.3, math.inf, math.inf, math.inf)
    assert all(math.isnan(x) for x in s)
