"""A statistical surface whose summits are driven past the law's end: the message says what the
surface can take (in J, m/s, kg), and what to change in the inputs, in their units; the numbers it
gives work (an impact just below the stated V1 solves, just above it is refused)."""
import math
import re

import pytest

import fastrest
from fastrest import rough

ALU = fastrest.Material(70e9, 0.33, 2.8e8)
R_A = 20e-6
E_EFF = ALU.E / (1 - ALU.nu**2)                      # rigid flat (MODEL.md section 1)
C = 1.295 * math.exp(0.736 * ALU.nu)                  # JGM eq (5)
OMEGA_C = (math.pi * C * ALU.Sy / (2 * E_EFF))**2 * R_A   # JGM eq (4)
RHO_MAX = 425.0 / math.sqrt(2 * 45.0)  # w* = 425 over the Gaussian's reach above the mean (exp(-45) tail cut)


def number_after(text, prefix):
    m = re.search(re.escape(prefix) + r"\s*([-+0-9.e]+)", text)
    assert m, (prefix, text)
    return float(m.group(1).rstrip("."))


def refused(surface, v, M):
    with pytest.raises(ValueError) as err:
        surface.impact(v, M)
    return str(err.value)


def test_too_wide_a_distribution_says_which_sigma_or_R_a_works():
    s = rough.RoughSurface(ALU, R_A, gw=dict(eta=1e10, sigma=500e-9, A_n=1e-4))
    assert s.omega_c == pytest.approx(OMEGA_C, rel=1e-12)
    msg = refused(s, 0.1, 0.01)
    assert not re.search(r"e\+[1-9]\d", msg), msg   # no w* = 4.259e+82 of a solver's trial point
    assert "sigma = 5e-07 m" in msg and "beyond w* = 425" in msg
    assert number_after(msg, "sigma/omega_c <=") == pytest.approx(RHO_MAX, rel=1e-3)
    assert number_after(msg, "sigma <=") == pytest.approx(RHO_MAX * OMEGA_C, rel=1e-3)
    assert number_after(msg, "or R_a >=") == pytest.approx(R_A * 500e-9 / OMEGA_C / RHO_MAX, rel=1e-3)
    # the advice works: at the stated sigma the flat reaches the mean height, and the surface takes impacts
    ok = rough.RoughSurface(ALU, R_A, gw=dict(eta=1e10, sigma=0.99 * number_after(msg, "sigma <="), A_n=1e-4))
    assert math.isfinite(ok.impact(1e-3, 0.01).e)


def test_stated_speed_limit_is_the_surfaces():
    s = rough.RoughSurface(ALU, R_A, gw=dict(eta=1e10, sigma=1e-7, A_n=1e-4))
    M = 0.01
    msg = refused(s, 0.1, M)
    v_max = number_after(msg, "V1 must be below")
    m_max = number_after(msg, "(M below")
    cap = number_after(msg, "absorbs at most")
    assert v_max == pytest.approx(math.sqrt(2 * cap / M), rel=1e-3)
    assert m_max == pytest.approx(2 * cap / 0.1**2, rel=1e-3)
    assert math.isfinite(s.impact(0.99 * v_max, M).e)
    assert number_after(refused(s, 1.01 * v_max, M), "V1 must be below") == v_max
