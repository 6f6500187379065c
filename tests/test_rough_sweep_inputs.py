"""rough.sweep and its helpers with a hardening material and with inputs that are not surfaces."""
import numpy as np
import pytest

import fastrest
from fastrest import rough

HARD_STEEL = fastrest.Material(200e9, 0.3, 1e9, Et=2e9)   # Et/E = 0.01
GW = dict(eta=1e10, sigma=20e-9, A_n=1e-4)
V = np.array([0.01, 0.1])


def test_sweep_of_a_hardening_material_equals_the_direct_surface():
    """A dict naming a material with its own Et: the swept surface uses that Et/E (it failed before)."""
    out = rough.sweep([dict(material=HARD_STEEL, R_a=1e-4, gw=GW)], V, 0.01, unloading="brake")
    assert out.errors == [] and out.ok.tolist() == [True]
    direct = rough.RoughSurface(HARD_STEEL, 1e-4, gw=GW).impact(V, 0.01, "brake")
    assert direct.kind == "statistical"
    for key, val in direct.as_dict().items():
        np.testing.assert_array_equal(np.asarray(out[0][key]), np.asarray(val), err_msg=key)


def test_surface_from_params_takes_the_materials_et_ratio():
    s = rough.surface_from_params(material=HARD_STEEL, R_a=1e-4, gw=GW)
    assert s.et_ratio == HARD_STEEL.et_ratio and s.law.name == "ghaednia"
    assert rough.surface_from_params(E=200e9, nu=0.3, Sy=1e9, R_a=1e-4, gw=GW).et_ratio == 0.0
    with pytest.raises(ValueError, match="contradicts"):
        rough.surface_from_params(material=HARD_STEEL, R_a=1e-4, gw=GW, et_ratio=0.0)


@pytest.mark.parametrize("bad", [None, 3.0, "abc", {"R_a": 1e-4}])
def test_sweep_names_surfaces_when_not_a_sequence(bad):
    with pytest.raises(TypeError, match="surfaces must be a sequence"):
        rough.sweep(bad, V, 0.01)


def test_gaussian_summits_names_n_for_a_duration():
    with pytest.raises(TypeError, match=r"^n \(number of summits\) must be a whole number"):
        rough.gaussian_summits(n=np.timedelta64(5, "s"), sigma=1e-7)
    with pytest.raises(TypeError, match=r"^n \(number of summits\)"):
        rough.gaussian_summits(n=np.datetime64("2020-01-01"), sigma=1e-7)
