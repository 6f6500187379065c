"""Every accuracy figure the README and the docs state (outside the shipped table's own) is at least
the error at the worst points known: those the searches of bench/stated_figures.py and
bench/force_law.py found (bench/STATED_FIGURES.md, bench/FORCE_LAW.md) and those independent
searches reported.

References are independent of fastrest: tests/reference.py and tests/reference_hardening.py
(40-digit mpmath). The direct solver's figures are rounding (a few ulp): they are stated with a
margin of a few ulp over the worst found, for another CPU's libm (tests hold on any machine).
"""
import warnings

import pytest

import fastrest
from fastrest import direct

import reference as ref
from reference_hardening import hard_e

# --- the stated figures, where they are stated ------------------------------------------------------
#: Curve.e and Curve.omega_m, relative, every unloading model: README bench table ("Curve.e(v)" row),
#: bench/RESULTS.md, docs/performance.md, docs/index.md.
CURVE_E = 1.1e-13
#: Curve.loss (JCG), relative: the same places ("1 - e^2").
CURVE_LOSS = 3.5e-12
#: fastrest.direct.e_exact (JCG) against 40-digit mpmath, relative: README bench table, bench/RESULTS.md,
#: docs/performance.md.
DIRECT_E = 2.0e-15
#: The direct solver with strain hardening against tests/reference_hardening.py: docs/model.md
#: section 12 (w_m*, e; 1 - e^2 relative for JCG and where |1 - e^2| >= 0.1, absolute where Etsion's or
#: Brake's is smaller).
HARD_OMEGA_M = 2.5e-15
HARD_E = 2.9e-15
HARD_LOSS = 4.7e-14
HARD_LOSS_ABS = 3.9e-15
#: Time-step table of docs/model.md section 10 (and bench/FORCE_LAW.md): worst |e_Verlet / e - 1|
#: by steps per Hertz contact duration N, the crossing of w* = 1.9 located or not.
TIME_STEP = {  # N: (located, not located)
    20: (1.2e-2, 1.2e-2), 50: (1.7e-3, 1.7e-3), 100: (4.5e-4, 4.4e-4), 200: (1.2e-4, 1.2e-4),
    500: (1.8e-5, 4.3e-5), 1000: (4.5e-6, 2.2e-5), 4000: (2.7e-7, 5.3e-6), 16000: (1.7e-8, 1.4e-6),
    64000: (1.1e-9, 3.3e-7),
}

# --- the worst points known ----------------------------------------------------------------------------
#: (V1*, eps_y, nu, model): Curve.e
CURVE_E_POINTS = [(808.0595551676569, 0.01, 0.45, "etsion"), (808.0595551676569, 0.01, 0.45, "brake"),
                  (807.9934928688672, 0.009999999999999998, 0.45, "jcg")]
CURVE_OMEGA_M_POINTS = [(744.0800259344338, 0.01, 0.45, "jcg")]
CURVE_LOSS_POINTS = [(2.2812630427249756, 0.0005, 0.2, "jcg")]
DIRECT_POINTS = [(693.9623955652306, 0.008699936008934026, 0.26629357801684467)]
#: (V1*, eps_y, nu, Et/E, model)
HARD_POINTS = [(85.615, 0.006054, 0.21673, 1.72e-4, "jcg"), (85.615, 0.006054, 0.21673, 1.72e-4, "etsion"),
               (85.615, 0.006054, 0.21673, 1.72e-4, "brake"), (1786.2395972028432, 0.01, 0.33, 0.5, "etsion"),
               (1903.7389011327007, 0.0005, 0.45, 0.99, "jcg"), (1229.3408121463524, 0.0005, 0.45, 0.05, "jcg"),
               (300.0, 0.01, 0.2, 0.5, "etsion"), (1903.7389011327007, 0.0005, 0.45, 0.99, "etsion")]
#: (N, located, model, eps_y, nu, V1*)
TIME_STEP_POINTS = [
    (1000, False, "brake", 0.0005, 0.2, 3.207520047637879),
    (1000, False, "brake", 0.0005, 0.2, 2.973130840577368),
    (20, True, "jcg", 0.0005, 0.2, 901.008984860209),
    (20, False, "jcg", 0.0005, 0.2, 901.0369003918457),
    (50, True, "jcg", 0.0005, 0.2, 855.9989319652492),
    (50, False, "jcg", 0.0005, 0.2, 855.9949327188729),
    (100, True, "jcg", 0.0005, 0.2, 987.4220475941847),
    (100, False, "jcg", 0.0005, 0.2, 987.4197509972558),
    (200, True, "jcg", 0.0005, 0.2, 1058.8234836949298),
    (200, False, "jcg", 0.0005, 0.2, 1058.8226917649542),
    (500, True, "jcg", 0.0005, 0.2, 1103.5575417576815),
    (500, False, "brake", 0.0005, 0.2, 2.9731225336138767),
    (1000, True, "jcg", 0.0005, 0.2, 1108.6416602431875),
    (4000, True, "jcg", 0.0005, 0.2, 1072.3207818289945),
    (4000, True, "jcg", 0.0005, 0.2, 1050.2461913715465),
    (4000, False, "brake", 0.0005, 0.2, 2.97540962823957),
    (16000, True, "jcg", 0.0005, 0.2, 1122.3431575214368),
    (16000, False, "brake", 0.0005, 0.2, 2.970292538729056),
    (64000, True, "jcg", 0.0005, 0.2, 1131.9004456413556),
    (64000, False, "brake", 0.0005, 0.2, 3.0743844185703115),
]


def first_fast(points):
    """The first point in the default run, the others under ``-m slow`` (each costs an mpmath solve)."""
    return [points[0]] + [pytest.param(*p, marks=pytest.mark.slow) for p in points[1:]]


def rel(got, exact):
    return abs(float(got) - float(exact)) / abs(float(exact))


@pytest.mark.parametrize("v, eps, nu, m", first_fast(CURVE_E_POINTS))
def test_curve_e_within_the_stated_figure(v, eps, nu, m):
    err = rel(fastrest.curve(eps, nu, m).e(v), ref.ref_e_star(v, eps, nu, m))
    assert err <= CURVE_E, err
    assert err > CURVE_E / 4  # still a worst point: the figure is not far above it


@pytest.mark.parametrize("v, eps, nu, m", CURVE_OMEGA_M_POINTS)
def test_curve_omega_m_within_the_stated_figure(v, eps, nu, m):
    assert rel(fastrest.curve(eps, nu, m).omega_m(v), ref.ref_omega_m_star(v, eps, nu)) <= CURVE_E


@pytest.mark.parametrize("v, eps, nu, m", CURVE_LOSS_POINTS)
def test_curve_loss_within_the_stated_figure(v, eps, nu, m):
    err = rel(fastrest.curve(eps, nu, m).loss(v), ref.ref_loss_star(v, eps, nu, m))
    assert CURVE_LOSS / 4 < err <= CURVE_LOSS, err


@pytest.mark.parametrize("v, eps, nu", DIRECT_POINTS)
def test_direct_e_within_the_stated_figure(v, eps, nu):
    assert rel(direct.e_exact(v, eps, nu), ref.ref_e_star(v, eps, nu, "jcg")) <= DIRECT_E


@pytest.mark.parametrize("v, eps, nu, h, m", first_fast(HARD_POINTS))
def test_hardening_direct_within_the_stated_figures(v, eps, nu, h, m):
    wm, e, loss = hard_e(v, eps, nu, h, m)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", fastrest.ValidityWarning)  # JCG/Etsion with hardening
        s = direct.solve(v, eps, nu, m, et_ratio=h)
    assert rel(s["omega_m_star"], wm) <= HARD_OMEGA_M
    assert rel(s["e"], e) <= HARD_E
    if m == "jcg" or abs(loss) >= 0.1:
        assert rel(s["loss"], loss) <= HARD_LOSS
    else:
        assert abs(float(s["loss"]) - loss) <= HARD_LOSS_ABS


@pytest.mark.parametrize("n, locate, m, eps, nu, v", first_fast(TIME_STEP_POINTS))
def test_time_step_within_the_stated_figures(n, locate, m, eps, nu, v):
    law = fastrest.contact_law(eps, nu, m)
    err = rel(law.impact(v, steps_per_contact=n, locate_switch=locate)["e"], ref.ref_e_star(v, eps, nu, m))
    stated = TIME_STEP[n][0 if locate else 1]
    assert err <= stated, err
    assert err > stated / 4, err  # a worst point, not a random one


def test_reports_round_errors_up():
    from bench.timing import fmt_err

    assert fmt_err(1.0671809432696552e-13) == "1.1e-13"
    assert fmt_err(9.96e-16) == "1.0e-15"
    assert fmt_err(9.96e-7) == "1.0e-06"
    assert fmt_err(3.4e-12) == "3.4e-12"
    for x in (1.0001e-10, 2.84137e-10, 8.5218e-10, 9.99e-3):
        assert float(fmt_err(x)) >= x


def test_bench_report_states_the_worst_of_sample_and_search(tmp_path):
    import json

    from bench.report import apply_search

    search = {"curve": {"models": {m: {q: {"error": 1e-13 if m == "etsion" else 1e-15, "at": [800.0, 0.01, 0.45]}
                                       for q in ("e", "omega_m", "loss")} for m in ("jcg", "etsion", "brake")}},
              "direct": {"e": {"relative": 9e-16, "ulp": 5.0, "points": 10, "stated_bound": 1.1e-15, "stated": 2e-15}}}
    path = tmp_path / "s.json"
    path.write_text(json.dumps(search))
    sample = {"max_rel_error": 5e-14, "at_v1_star": 1.0, "at_eps_y": 0.005, "at_nu": 0.33}
    R = {"speed_error": {"curve_errors": {5: {q: dict(sample) for q in ("e_jcg", "omega_m", "loss_jcg")}},
                         "methods": [{"key": "curve_5", "error": 5e-14, "error_of": ""},
                                     {"key": "direct", "error": 7e-16, "error_of": ""}],
                         "direct_vs_mpmath": {"max_rel_error": 7e-16, "points": 24}}}
    apply_search(R, path)
    ce = R["speed_error"]["curve_errors"][5]
    assert ce["e_jcg"]["max_rel_error"] == 1e-13 and ce["omega_m"]["max_rel_error"] == 1e-13
    assert ce["loss_jcg"]["max_rel_error"] == 5e-14  # 1 - e^2: JCG's (relative) only, the sample's larger here
    by = {m["key"]: m for m in R["speed_error"]["methods"]}
    assert by["curve_5"]["error"] == 1e-13 and by["direct"]["error"] == 2e-15


@pytest.mark.slow
def test_time_step_search_covers_the_switch_region_and_reports_the_band():
    from bench import force_law

    cfg = dict(steps=[20], n_log=3, n_switch=4, refine=3, starts=1)
    vs = force_law.speeds(1000.0, cfg["n_log"], cfg["n_switch"])
    assert vs[-1] == 1000.0 and 3.207520047637879 in vs
    assert sum(2.23 < v <= 3.5 for v in vs) >= cfg["n_switch"]
    conv = force_law.convergence(cfg, lambda *a: None)
    for locate in (True, False):
        assert TIME_STEP[20][0 if locate else 1] >= conv[locate][0] > 0
        assert conv["band"][locate]["width"][0] > 0  # a speed below the switch whose stepped peak passed 1.9
