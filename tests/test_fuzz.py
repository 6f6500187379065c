"""The fuzz suite (tests/fuzz.py): 0 unclear, 0 silent, 0 crash.

An error is clear when it is a TypeError (not a number) or ValueError (a number out of range) that
names the Python parameter, no CLI ``--option``, and passes on no internal exception. The default
run classifies one value of each kind for every parameter in this process
(:func:`test_fuzz_fast_subset`); the quick and full levels (with the CLI, in child processes: a
crash or hang is counted, not fatal) are ``slow``. Hypothesis draws further values for the fast
pure-Python entry points in this process.
"""
import math
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from tests import fuzz


def _check(level):
    counts, problems = fuzz.run(level)
    print()
    print(fuzz.summary(counts))
    for case, outcome, detail in problems[:20]:
        print(f"  {outcome}: {case}: {detail}")
    assert counts["tried"] == len(fuzz.build_cases(level))
    assert counts["clear"] > 0 and counts["accepted"] > 0  # the classifier sees both kinds
    assert (counts["unclear"], counts["silent"], counts["crash"]) == (0, 0, 0), problems[:20]


@pytest.mark.slow
def test_fuzz_fast_subset():
    """One value of each kind for every parameter of every Python target, in this process (~1 s
    after the targets are built): errors are TypeError/ValueError of the right type, name the
    parameter, name no CLI option and pass on no internal exception."""
    targets = {n: (p, f) for n, p, f in fuzz._targets()}
    problems = []
    counts = dict(clear=0, accepted=0, unclear=0, silent=0)
    for case in fuzz.fast_cases():
        outcome, detail = fuzz.classify(case, targets)
        counts[outcome] += 1
        if outcome in ("unclear", "silent"):
            problems.append((case[:3], outcome, detail))
    assert counts["clear"] > 0 and counts["accepted"] > 0
    assert not problems, problems[:20]


@pytest.mark.slow
def test_fuzz_explicit_cases():
    _check("quick")


@pytest.mark.slow
def test_fuzz_full():
    _check("full")


def test_classifier_flags_bad_behaviour():
    """The classifier itself: a silent acceptance, an unnamed error and a raw exception are caught."""
    targets = {"f": ({"x": 1.0}, lambda x: 1.0), "g": ({"x": 1.0}, lambda x: float("nan")),
               "h": ({"x": 1.0}, lambda x: (_ for _ in ()).throw(ValueError("bad"))),
               "k": ({"x": 1.0}, lambda x: 1 / 0), "m": ({"x": 1.0}, lambda x: (_ for _ in ()).throw(TypeError("x bad")))}
    assert fuzz.classify(("f", "x", "str", "error"), targets)[0] == "silent"
    assert fuzz.classify(("g", "x", "2.5", "either"), targets)[0] == "silent"
    assert fuzz.classify(("h", "x", "str", "error"), targets)[0] == "unclear"
    assert fuzz.classify(("k", "x", "str", "error"), targets)[0] == "unclear"
    assert fuzz.classify(("m", "x", "str", "error"), targets)[0] == "clear"
    # the right type: TypeError for a non-number, ValueError for a number out of range
    wrong = {"t": ({"x": 1.0}, lambda x: (_ for _ in ()).throw(ValueError("x must be a number"))),
             "v": ({"x": 1.0}, lambda x: (_ for _ in ()).throw(TypeError("x must be >= 0"))),
             "cli": ({"V_max": 1.0}, lambda V_max: (_ for _ in ()).throw(ValueError("--V-max must be > 0"))),
             "leak": ({"E": 1.0}, lambda E: (_ for _ in ()).throw(ValueError(
                 "E: this impact's error = ZeroDivisionError('division by zero')")))}
    assert fuzz.classify(("t", "x", "str", "error"), wrong)[0] == "unclear"
    assert fuzz.classify(("t", "x", "None", "error"), wrong)[0] == "unclear"
    assert fuzz.classify(("v", "x", "-1", "either"), wrong)[0] == "unclear"
    assert fuzz.classify(("v", "x", "nan", "error"), wrong)[0] == "unclear"
    assert fuzz.classify(("cli", "V_max", "-1", "either"), wrong)[0] == "unclear"
    assert fuzz.classify(("leak", "E", "tiny", "either"), wrong)[0] == "unclear"


@pytest.mark.slow
def test_crash_and_hang_are_counted(monkeypatch, tmp_path):
    """A child that dies or hangs is a crash, and the runner resumes after it."""
    cases = [("t", "x", "a", "either"), ("t", "x", "b", "either"), ("t", "x", "c", "either")]
    monkeypatch.setattr(fuzz, "build_cases", lambda level="quick": cases)
    script = tmp_path / "child.py"
    script.write_text(
        "import json, os, sys, time\n"
        "start = int(sys.argv[-1])\n"
        "for i in range(start, 3):\n"
        "    print(json.dumps({'i': i, 'start': True}), flush=True)\n"
        "    if i == 0: os._exit(139)\n"
        "    if i == 1: time.sleep(60)\n"
        "    print(json.dumps({'i': i, 'outcome': 'accepted', 'detail': ''}), flush=True)\n")
    real_popen = fuzz.subprocess.Popen

    def popen(argv, **kw):
        return real_popen([sys.executable, str(script), argv[-1]], **kw)

    monkeypatch.setattr(fuzz.subprocess, "Popen", popen)
    counts, problems = fuzz.run("quick", case_timeout=3.0)
    assert counts == dict(tried=3, clear=0, accepted=1, unclear=0, silent=0, crash=2)


_ANY = st.one_of(st.floats(), st.integers(min_value=-10**400, max_value=10**400), st.text(max_size=5),
                 st.booleans(), st.none(), st.complex_numbers(), st.binary(max_size=3),
                 st.lists(st.one_of(st.floats(), st.booleans()), max_size=3))


def _fast_targets():
    import fastrest
    from fastrest import models

    steel = fastrest.Material(2e11, 0.3, 1e9, rho=7800.0)
    c = fastrest.curve(0.005, 0.33, v_max=50.0)
    return {
        "Material": (dict(E=2e11, nu=0.3, Sy=1e9, rho=7800.0), lambda **k: fastrest.Material(**k)),
        "Impact": (dict(sphere=steel, R=0.01, mass=0.03), lambda **k: fastrest.Impact(**k).V_c),
        "direct.e_exact": (dict(v1_star=5.0, eps_y=0.005, nu=0.33), lambda **k: fastrest.direct.e_exact(**k)),
        "fastrest.e_star": (dict(v1_star=5.0, eps_y=0.005, nu=0.33), lambda **k: fastrest.e_star(**k)),
        "Curve.e": (dict(v1_star=5.0), lambda **k: c.e(**k)),
        "chang_ling": (dict(v1_star=5.0, eps_y=0.005, nu=0.33), lambda **k: models.chang_ling(**k)),
        "weir_tallon": (dict(V1=1.0, Sy=1e9, E_eff=2e11, rho=7800.0), lambda **k: models.weir_tallon(**k)),
    }


_TARGETS = None


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(target=st.sampled_from(sorted(["Material", "Impact", "direct.e_exact", "fastrest.e_star", "Curve.e",
                                      "chang_ling", "weir_tallon"])), data=st.data(), value=_ANY)
def test_hypothesis_values(target, data, value):
    global _TARGETS
    if _TARGETS is None:
        _TARGETS = _fast_targets()
    params, fn = _TARGETS[target]
    p = data.draw(st.sampled_from(sorted(params)))
    if isinstance(value, list):  # an array: never valid with a bool or a non-finite element
        never_valid = any(isinstance(x, bool) or not math.isfinite(x) for x in value)
    else:
        never_valid = (value is None or isinstance(value, (str, bytes, bool, complex))
                       or (isinstance(value, float) and not math.isfinite(value)
                           and not (target == "Material" and p == "Sy" and value == math.inf)))
    if p == "sphere":
        never_valid = True
    if value is None and ((target, p) in fuzz.OPTIONAL or p in ("rho", "mass")):
        never_valid = False
    kind = "error" if never_valid else "either"
    fuzz.NOT_NUMBERS["_hyp"] = value  # the classifier looks values up by label
    try:
        outcome, detail = fuzz.classify((target, p, "_hyp", kind), _TARGETS)
    finally:
        del fuzz.NOT_NUMBERS["_hyp"]
    assert outcome in ("clear", "accepted"), (target, p, value, outcome, detail)


def test_a_value_quoted_back_is_not_a_cli_option():
    """A str value that looks like an option ('--A', found by hypothesis) is quoted back by the
    message: the message itself names no CLI option, and is clear."""
    global _TARGETS
    if _TARGETS is None:
        _TARGETS = _fast_targets()
    fuzz.NOT_NUMBERS["_hyp"] = "--A"
    try:
        outcome, detail = fuzz.classify(("Curve.e", "v1_star", "_hyp", "error"), _TARGETS)
    finally:
        del fuzz.NOT_NUMBERS["_hyp"]
    assert outcome == "clear", detail
