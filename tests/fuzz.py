"""Fuzz suite over fastrest's public API and CLI: every public function, class and CLI
command called with hostile and extreme values for each parameter in turn (the others valid).

Each call is classified:

* ``clear``: TypeError or ValueError whose message names the parameter (the Python parameter: never a
  CLI ``--option`` for a Python call) and whose type fits the value: TypeError for a value that is
  not a number (a string, a bool, None, a complex, an object) or not of the parameter's kind (a
  number for a Material), ValueError for a number out of range (NaN, inf, -1, 1e300, 2.5 for a
  count);
* ``accepted``: returned, and every number in the result is finite (valid or extreme-but-valid input);
* ``unclear``: any other exception, an error of the wrong type, or a message that does not name
  the parameter;
* ``silent``: returned for input that is never valid (a string, a bool, NaN, ...), or returned a
  non-finite number;
* ``crash``: the process died or exceeded the time limit (the runner restarts after the case).

Run ``python -m tests.fuzz [--level full]``; it prints the counts. The cases run in child
processes: a crash or hang ends the child, is counted, and the next child resumes after it.
"""
import contextlib
import io
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time
import warnings

import numpy as np

# --- values -------------------------------------------------------------------------------------
# never valid for a number: an error is required
NOT_NUMBERS = {
    "str": "5", "bytes": b"5", "bytearray": bytearray(b"1"), "bool": True, "np.bool_": np.True_,
    "None": None, "complex": 1 + 0j, "list with bool": [1.0, True], "nested bool": [[1.0, True]],
    "masked": np.ma.masked_array([1.0, 2.0], [0, 1]), "object": object(), "dict": {"a": 1},
    "nan": math.nan, "-inf": -math.inf, "inf": math.inf, "int beyond float": 10**400,
}
# numbers: a clear error or a finite result
EXTREME = {
    "0": 0.0, "-1": -1.0, "tiny": 1e-300, "subnormal": 5e-324, "huge": 1e300, "1e-9": 1e-9, "2.5": 2.5,
    "np.float32": np.float32(0.3), "int": 3, "np.int64": np.int64(2), "-0": -0.0,
}
ARRAYS = {"2x2 array": np.array([[0.3, 0.3], [0.3, 0.3]]), "empty": np.array([])}
#: Labels of values that are not real numbers at all: a TypeError is required.
NOT_REAL = {"str", "bytes", "bytearray", "bool", "np.bool_", "None", "complex", "list with bool",
            "nested bool", "masked", "object", "dict"}
#: Labels of real numbers (or number-valued arrays): an error for them is a ValueError (out of
#: range), except for parameters that take no number at all (a Material, a flag).
NUMBERS = {"nan", "-inf", "inf", "int beyond float"} | set(EXTREME) | {f"random {i}" for i in range(10)}

LEVELS = {"quick": dict(random=0), "full": dict(random=6)}


def _is_finite(x):
    if x is None or isinstance(x, (str, bool, bytes)):
        return True
    if isinstance(x, dict):
        return all(_is_finite(v) for v in x.values())
    if isinstance(x, (list, tuple)):
        return all(_is_finite(v) for v in x)
    if hasattr(x, "as_dict"):
        return _is_finite(x.as_dict())
    try:
        a = np.asarray(x)
    except Exception:  # an object: not a number
        return True
    if a.dtype.kind in "fc":
        return bool(np.all(np.isfinite(a)))
    return True


# --- targets --------------------------------------------------------------------------------------

def _targets():
    """(name, params, call): call(**kwargs) with every parameter valid by default."""
    import fastrest
    from fastrest import direct, forward, models, rough, tables

    steel = fastrest.Material(2e11, 0.3, 1e9, rho=7800.0)
    imp = fastrest.Impact(steel, 0.01)
    c = fastrest.curve(0.005, 0.33, v_max=50.0)
    s = fastrest.scene([(0.005, 0.33), (0.003, 0.3)], v_max=50.0)
    tab = fastrest.load_table()
    law = fastrest.contact_law(0.005, 0.33)
    ip = fastrest.Impact(steel, 1e-4, mass=1.0)
    surf = rough.RoughSurface(steel, 1e-4, heights=[0.0, 1e-8, 2e-8])
    T = []

    def add(name, params, fn):
        T.append((name, params, fn))

    v3 = dict(v1_star=5.0, eps_y=0.005, nu=0.33)
    add("Material", dict(E=2e11, nu=0.3, Sy=1e9, rho=7800.0), lambda **k: fastrest.Material(**k))
    add("Impact", dict(sphere=steel, R=0.01, mass=0.03), lambda **k: fastrest.Impact(**k))
    add("Impact.two_spheres", dict(sphere1=steel, R1=0.01, sphere2=steel, R2=0.02),
        lambda **k: fastrest.Impact.two_spheres(**k))
    add("Impact.e", dict(V1=1.0, extrapolate=False), lambda **k: imp.e(**k))
    add("Impact.V_max", dict(extrapolate=False), lambda **k: imp.V_max(**k))
    add("Impact.residual", dict(V1=1.0), lambda **k: imp.residual(**k))
    add("Impact.rebound_velocity", dict(V1=1.0), lambda **k: imp.rebound_velocity(**k))
    add("Impact.max_interference", dict(V1=1.0, extrapolate=False), lambda **k: imp.max_interference(**k))
    add("Impact.v1_star", dict(V1=1.0, extrapolate=False), lambda **k: imp.v1_star(**k))
    add("limit", dict(eps_y=0.005, nu=0.33, extrapolate=False), lambda **k: fastrest.limit(**k))
    add("poisson_factor", dict(nu=0.3), lambda **k: fastrest.poisson_factor(**k))
    add("critical_velocity_ratios", dict(nu=0.3), lambda **k: fastrest.critical_velocity_ratios(**k))
    add("P_star", dict(w=2.0, eps_y=0.005, nu=0.3), lambda **k: fastrest.P_star(**k))
    add("A_star", dict(w=2.0, eps_y=0.005, nu=0.3), lambda **k: fastrest.A_star(**k))
    add("W_star", dict(w=2.0, eps_y=0.005, nu=0.3), lambda **k: fastrest.W_star(**k))
    add("omega_star_limit", dict(eps_y=0.005, nu=0.3), lambda **k: fastrest.omega_star_limit(**k))
    for f in ("omega_m_star", "e_star", "loss_star", "residual_star", "solve"):
        p = dict(v3, extrapolate=False)
        add(f"direct.{f}", p, lambda f=f, **k: getattr(direct, f)(**k))
    for f in ("omega_m_star", "e_star", "loss_star"):
        add(f"fastrest.{f}", dict(v3), lambda f=f, **k: getattr(fastrest, f)(**k))
        t = f[: -len("_star")]  # Table's methods are named like Curve's: omega_m, e, loss
        add(f"Table.{t}", dict(v3), lambda t=t, **k: getattr(tab, t)(**k))
    for f in ("W_star", "loading_energy"):
        add(f"Table.{f}", dict(w=2.0, eps_y=0.005, nu=0.33), lambda f=f, **k: getattr(tab, f)(**k))
    add("curve", dict(eps_y=0.005, nu=0.33, v_max=20.0, extrapolate=False), lambda **k: fastrest.curve(**k))
    for f in ("e", "loss", "omega_m"):
        add(f"Curve.{f}", dict(v1_star=5.0), lambda f=f, **k: getattr(c, f)(**k))
        add(f"Scene.{f}", dict(v1_star=5.0, material=1), lambda f=f, **k: getattr(s, f)(**k))
    add("scene", dict(materials=[(0.005, 0.33)], v_max=20.0, extrapolate=False),
        lambda **k: fastrest.scene(**k))
    add("Scene", dict(curves=[c]), lambda **k: fastrest.Scene(**k))
    add("contact_law", dict(eps_y=0.005, nu=0.33, w_max=50.0, extrapolate=False, omega_c=1.0, P_c=1.0),
        lambda **k: fastrest.contact_law(**k))
    add("ContactLaw.force", dict(interference=2.0), lambda **k: law.force(**k))
    add("ContactLaw.impact", dict(v1_star=3.0, steps_per_contact=200, locate_switch=True), lambda **k: law.impact(**k))
    add("ContactLaw.new_state", dict(n=3), lambda **k: law.new_state(**k))
    add("forward.forward_data", dict(eps_y=0.005, nu=0.33, w_max=5.0, extrapolate=False),
        lambda **k: forward.forward_data(**k))
    add("tables.normalise_grid", dict(n_eps_y=72, n_nu=6, eps_y_max=0.01, c_eps_y_map_rate=30.0, n_eps_y_energy=32),
        lambda **k: tables.normalise_grid(k))
    for name in models.MODELS:
        add(f"models.MODELS[{name}]", dict(v3), lambda name=name, **k: models.MODELS[name](**k))
    add("models.evaluate", dict(impact=imp, V1=1.0), lambda **k: [models.evaluate(m, **k) for m in models.MODELS])
    add("models.weir_tallon", dict(V1=1.0, Sy=1e9, E_eff=2e11, rho=7800.0, cap=False), lambda **k: models.weir_tallon(**k))
    add("models.johnson", dict(V1=1.0, Sy=1e9, E_eff=2e11, rho=7800.0), lambda **k: models.johnson(**k))
    add("models.weir_tallon_unit_velocity", dict(Sy=1e9, E_eff=2e11, rho=7800.0),
        lambda **k: models.weir_tallon_unit_velocity(**k))
    add("models.chang_ling_dimensional", dict(impact=imp, V1=1.0), lambda **k: models.chang_ling_dimensional(**k))
    add("models.wu_finite_plastic_velocity", dict(eps_y=0.005), lambda **k: models.wu_finite_plastic_velocity(**k))
    add("models.thornton", dict(v1_star=5.0, nu=0.3), lambda **k: models.thornton(**k))
    add("models.ceb_hardness_factor", dict(nu=0.3), lambda **k: models.ceb_hardness_factor(**k))
    add("rough.gaussian_summits", dict(n=10, sigma=1e-6, seed=1), lambda **k: rough.gaussian_summits(**k))
    add("rough.GreenwoodWilliamson", dict(eta=1e10, sigma=1e-6, A_n=1e-4), lambda **k: rough.GreenwoodWilliamson(**k))
    add("rough.RoughSurface", dict(material=steel, R_a=1e-4, heights=[0.0, 1e-8, 2e-8]),
        lambda **k: rough.RoughSurface(**k))
    add("rough.RoughSurface(gw)", dict(eta=1e10, sigma=0.5 * ip.omega_c, A_n=1e-6),
        lambda **k: rough.RoughSurface(steel, 1e-4, gw=k).impact(1e-3, 1e-3))
    add("RoughSurface.impact", dict(V1=1e-3, M=1e-3, extrapolate=False), lambda **k: surf.impact(**k))
    add("rough.sweep", dict(V1=1e-3, M=1e-3, extrapolate=False), lambda **k: rough.sweep([surf], on_error="raise", **k))  # errors, not per-surface records
    # strain hardening: Et of a Material, et_ratio of the normalised APIs (Brake: no warning)
    add("Material(Et)", dict(E=2e11, nu=0.3, Sy=1e9, rho=7800.0, Et=1e9), lambda **k: fastrest.Material(**k))
    add("P_star(et_ratio)", dict(w=2.0, eps_y=0.005, nu=0.3, et_ratio=0.01), lambda **k: fastrest.P_star(**k))
    add("direct.e_exact(et_ratio)", dict(v3, et_ratio=0.01), lambda **k: direct.e_exact(unloading="brake", **k))
    add("limit(et_ratio)", dict(eps_y=0.005, nu=0.33, et_ratio=0.01), lambda **k: fastrest.limit(**k))
    add("curve(et_ratio)", dict(eps_y=0.005, nu=0.33, v_max=20.0, et_ratio=0.01),
        lambda **k: fastrest.curve(unloading="brake", **k))
    add("contact_law(et_ratio)", dict(eps_y=0.005, nu=0.33, w_max=50.0, et_ratio=0.01),
        lambda **k: fastrest.contact_law(unloading="brake", **k))
    add("rough.RoughSurface(et_ratio)", dict(material=steel, R_a=1e-4, heights=[0.0, 1e-8, 2e-8], et_ratio=0.01),
        lambda **k: rough.RoughSurface(**k))
    return T


_BASE_E = ["--E", "2e11", "--nu", "0.3", "--Sy", "1e9", "--R", "0.01", "--rho", "7800", "--V", "1"]


#: An output path whose directory does not exist (in the temporary directory, never a system path):
#: the CLI cases give bad options, refused before the path is used.
_NO_DIR_OUT = os.path.join(tempfile.gettempdir(), "fastrest-fuzz-no-such-dir", "x.h5")


def _cli_cases():
    """(name, param, argv, expect): every numeric option of ``e`` and the grid options of ``build``
    with hostile text; ``info`` with bad paths (expect: a clear message, exit 1 or 2)."""
    out = []
    texts = {"word": "abc", "nan": "nan", "inf": "inf", "-inf": "-inf", "negative exponent": "-2e11",
             "zero": "0", "huge": "1e300", "tiny": "1e-300", "empty": ""}
    opts = ["--E", "--nu", "--Sy", "--R", "--rho", "--V"]
    for o in opts:
        for label, t in texts.items():
            argv = list(_BASE_E)
            argv[argv.index(o) + 1] = t
            out.append((f"cli e {o}", o.strip("-"), ["e"] + argv, "either" if label in ("huge", "tiny", "zero") else "error"))
    for o in ("--mass", "--flat-E", "--flat-nu", "--flat-Sy"):
        for label, t in texts.items():
            extra = [o, t] + (["--flat-nu", "0.3"] if o == "--flat-E" else []) + (
                ["--flat-E", "2e11"] if o in ("--flat-nu", "--flat-Sy") else [])
            out.append((f"cli e {o}", o.strip("-").replace("-", "_"), ["e"] + _BASE_E + extra,
                        "either" if label in ("huge", "tiny", "zero") else "error"))
    for label, t in (("model", "nope"),):
        out.append(("cli e --model", "model", ["e"] + _BASE_E + ["--model", t], "error"))
    out.append(("cli e --json all", "json", ["e"] + _BASE_E[:-1] + ["0", "1"] + ["--model", "all", "--json"], "json"))
    grid_bad = {"--n-eps-y": ["1000000000", "1e300", "2.5", "abc", "-5"], "--eps-y-max": ["inf", "nan", "-1", "1e300"],
                "--eps-y-min": ["0", "-0.001", "inf"], "--n-nu": ["1", "100000"], "--nu-max": ["0.5", "2"],
                "--bits-per-octave": ["0", "99"], "--c-eps-y-map-rate": ["-1", "inf", "1e300"],
                "--eps-y-blocks": ["128:1000000000", "x", "3:24"], "--fine-v1-star-max": ["3", "inf"]}
    for o, vals in grid_bad.items():
        for t in vals:
            out.append((f"cli build {o}", o.strip("-").replace("-", "_"), ["build", "--out", _NO_DIR_OUT, o, t], "error"))
    for t in (_NO_DIR_OUT, tempfile.gettempdir(), __file__):
        out.append(("cli info", "file", ["info", t], "error"))
    out.append(("cli info (default)", "file", ["info"], "ok"))
    return out


#: Parameters for which None is a valid value (an optional argument), or inf (a body that never yields).
OPTIONAL = {("Material", "rho"), ("rough.RoughSurface(et_ratio)", "et_ratio"), ("Material(Et)", "rho"), ("curve(et_ratio)", "v_max"), ("contact_law(et_ratio)", "w_max"), ("Impact", "mass"), ("curve", "v_max"), ("scene", "v_max"),
            ("contact_law", "w_max"), ("ContactLaw.new_state", "n"), ("rough.gaussian_summits", "seed")}
INF_OK = {("Material", "Sy"), ("Material(Et)", "Sy")}
#: (target, parameter, label) valid although the label is never valid for a number.
VALID = {("rough.gaussian_summits", "seed", "int beyond float")}  # any integer >= 0 seeds NumPy
#: Flags: only True/False (and NumPy booleans) are valid, numbers are not.
FLAGS = {"extrapolate", "cap", "locate_switch"}
#: Words a message may use for a parameter: derived quantities the parameter sets.
ALIASES = {"R_a": {"R_eff"}, "M": {"V1"}, "V1": {"M"}, "sigma": {"w*"}, "eta": {"N"}, "A_n": {"N"},
           "R": {"R_eff"}, "mass": {"mass"}, "E": {"E_eff"}}


def _expect(name, p, label):
    if p in FLAGS:
        return "either" if label in ("bool", "np.bool_") else "error"
    if label == "None" and (name, p) in OPTIONAL:
        return "either"
    if label == "inf" and (name, p) in INF_OK or (name, p, label) in VALID:
        return "either"
    return "error" if label in NOT_NUMBERS else "either"


def build_cases(level="quick"):
    """The cases, in a fixed order: (target, param, label, kind, payload)."""
    cases = []
    for name, params, _ in _targets():
        for p in params:
            for label in list(NOT_NUMBERS) + list(EXTREME) + list(ARRAYS):
                cases.append((name, p, label, _expect(name, p, label)))
            for i in range(LEVELS[level]["random"]):
                cases.append((name, p, f"random {i}", _expect(name, p, "random")))
    for name, p, argv, expect in _cli_cases():
        cases.append((name, p, json.dumps(argv), "cli-" + expect))
    return cases


def _value(label, name, p):
    if label in NOT_NUMBERS:
        return NOT_NUMBERS[label]
    if label in EXTREME:
        return EXTREME[label]
    if label in ARRAYS:
        return ARRAYS[label]
    # random: a float of random magnitude and sign, seeded by the case
    rng = np.random.default_rng(abs(hash((name, p, label))) % 2**32)
    return float(rng.choice([-1, 1]) * 10.0 ** rng.uniform(-320, 308))


def _expected_type(label, default):
    """The exception type an error for ``label`` must have, given the parameter's valid
    ``default`` value; None where either is right (an array for a scalar, an empty array)."""
    if isinstance(default, (bool, np.bool_)) or label in NOT_REAL:
        return TypeError  # a flag takes True/False only
    if label in ARRAYS:
        return None
    numeric = isinstance(default, (int, float, np.ndarray)) or (
        isinstance(default, (list, tuple)) and all(isinstance(x, (int, float)) for x in default))
    if not numeric:  # an object (Material, Impact, a list of pairs or of curves): a number is a type error
        return TypeError
    return ValueError if label in NUMBERS else None


_CLI_OPTION = re.compile(r"(?<![\w-])--[A-Za-z][\w-]*")
#: An exception's repr inside a message ("ZeroDivisionError('division by zero')"): an internal
#: failure passed on as text, not a message about the parameter.
_LEAKED = re.compile(r"\b[A-Z]\w*(Error|Exception)\(")


def _names_param(msg, p):
    words = {p, p.replace("_", "-")} | ALIASES.get(p, set())
    if p in ("interference", "w", "v1_star", "V1"):
        words |= {"interference", "w", "w_max", "v1_star", "V1", "V1*"}
    return any(re.search(r"(?<![A-Za-z0-9_])" + re.escape(w) + r"(?![A-Za-z0-9_])", msg) for w in words)


def _run_cli(argv):
    from fastrest.cli import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as exc:  # argparse
            code = exc.code
    return code, out.getvalue(), err.getvalue()


def classify(case, targets):
    name, p, label, kind = case
    if kind.startswith("cli-"):
        argv = json.loads(label)
        try:
            code, out, err = _run_cli(argv)
        except Exception as exc:
            return "unclear", f"{type(exc).__name__}: {exc}"[:300]
        if "Traceback" in err:
            return "unclear", err[-300:]
        expect = kind[4:]
        if expect == "json":
            try:
                json.loads(out, parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))
            except ValueError as exc:
                return "silent", f"invalid JSON: {exc}"
            return ("accepted", "") if code == 0 else ("unclear", err[-300:])
        if code in (0, None):
            if expect == "error":
                return "silent", f"exit 0 for {argv}"
            return "accepted", ""
        msg = err.strip().splitlines()[-1] if err.strip() else ""
        if "error" in msg or "invalid" in msg or "fastrest" in msg:
            return "clear", msg[:300]
        return "unclear", msg[:300]
    params, fn = targets[name]
    kwargs = dict(params)
    kwargs[p] = _value(label, name, p)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with np.errstate(all="ignore"):
                r = fn(**kwargs)
    except (TypeError, ValueError) as exc:
        msg = str(exc)
        want = _expected_type(label, params[p])
        if want is not None and not isinstance(exc, want):
            return "unclear", f"{type(exc).__name__} (want {want.__name__}): {msg[:300]}"
        own = msg.replace(repr(kwargs[p]), "") if isinstance(kwargs[p], (str, bytes)) else msg  # the value quoted back
        if _CLI_OPTION.search(own):
            return "unclear", f"names a CLI option in a Python call: {msg[:300]}"
        if _LEAKED.search(own):
            return "unclear", f"passes on an internal exception: {msg[:300]}"
        return ("clear", msg[:300]) if _names_param(msg, p) else ("unclear", f"{type(exc).__name__}: {msg[:300]}")
    except Exception as exc:
        return "unclear", f"{type(exc).__name__}: {str(exc)[:300]}"
    if kind == "error":
        return "silent", f"returned {r!r}"[:300]
    if not _is_finite(r):
        return "silent", f"non-finite result {r!r}"[:300]
    return "accepted", ""


#: Labels of the default (fast) run: one of each kind of value.
FAST_LABELS = ("str", "None", "bool", "complex", "nan", "inf", "-1", "0", "huge", "subnormal", "2.5",
               "2x2 array")


def fast_cases():
    """A subset of the quick cases for the default test run, classified in this process: every
    Python target and parameter with :data:`FAST_LABELS` (the CLI and the child processes are in
    the slow runs)."""
    return [c for c in build_cases("quick") if not c[3].startswith("cli-") and c[2] in FAST_LABELS]


def _child(level, start):
    """Run cases from ``start``; one JSON line per case (flushed, so a crash loses nothing)."""
    os.environ.setdefault("MPLBACKEND", "Agg")
    # the records go to a private copy of stdout; what the cases themselves print (the CLI's
    # tables, a line without its newline) goes to a temporary file and cannot merge into a record
    out = os.fdopen(os.dup(1), "w")
    sink = tempfile.TemporaryFile("w")   # not the system's /dev/null: tests touch no system path
    os.dup2(sink.fileno(), 1)
    sys.stdout = sink
    cases = build_cases(level)
    targets = {n: (p, f) for n, p, f in _targets()}
    for i in range(start, len(cases)):
        print(json.dumps({"i": i, "start": True}), file=out, flush=True)
        outcome, detail = classify(cases[i], targets)
        print(json.dumps({"i": i, "outcome": outcome, "detail": detail}), file=out, flush=True)


def _complete_lines(text):
    """The JSON records of the lines the child finished writing (the last may be partial)."""
    out = []
    for x in text.split("\n")[:-1]:
        try:
            out.append(json.loads(x))
        except ValueError:
            pass
    return out


def run(level="quick", case_timeout=300.0, log=None):
    """All cases in child processes; returns (counts, problems)."""
    cases = build_cases(level)
    counts = dict(tried=0, clear=0, accepted=0, unclear=0, silent=0, crash=0)
    problems = []
    start = 0
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    while start < len(cases):
        with tempfile.TemporaryFile("w+") as f:
            proc = subprocess.Popen([sys.executable, "-m", "tests.fuzz", "--child", level, str(start)],
                                    cwd=root, stdout=f, stderr=subprocess.DEVNULL, text=True)
            last_seen, current, t_case = start, None, time.monotonic()
            while True:
                try:
                    proc.wait(timeout=1.0)
                    done = True
                except subprocess.TimeoutExpired:
                    done = False
                # pread: the child writes through the same open file, so moving its shared offset
                # (seek + read) made the child overwrite its first records
                fd = f.fileno()
                raw = os.pread(fd, os.fstat(fd).st_size, 0)
                lines = _complete_lines(raw.decode("utf-8", "replace"))
                finished = {d["i"]: d for d in lines if "outcome" in d}
                started = [d["i"] for d in lines if d.get("start")]
                cur = max(started) if started else None
                if cur != current:
                    current, t_case = cur, time.monotonic()
                if done or (current is not None and current not in finished
                            and time.monotonic() - t_case > case_timeout):
                    if not done:
                        proc.kill()
                        proc.wait()
                    break
        for i in sorted(finished):
            d = finished[i]
            counts["tried"] += 1
            counts[d["outcome"]] += 1
            if d["outcome"] in ("unclear", "silent"):
                problems.append((cases[i][:3], d["outcome"], d["detail"]))
        nxt = max(finished) + 1 if finished else start
        if nxt < len(cases) and (current is not None and current not in finished):
            counts["tried"] += 1
            counts["crash"] += 1
            problems.append((cases[current][:3], "crash", f"exit {proc.returncode}"))
            nxt = current + 1
        if nxt <= start and not finished:
            nxt = start + 1  # the child died before its first case: count it and move on
            counts["tried"] += 1
            counts["crash"] += 1
            problems.append((cases[start][:3], "crash", f"exit {proc.returncode}"))
        start = nxt
    return counts, problems


def summary(counts):
    return ("fuzz: {tried} tried / {clear} clear error / {accepted} accepted / {unclear} unclear / "
            "{silent} silent / {crash} crash").format(**counts)


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "--child":
        _child(sys.argv[2], int(sys.argv[3]))
        sys.exit(0)
    level = "full" if "--level" in sys.argv and sys.argv[sys.argv.index("--level") + 1] == "full" else "quick"
    t0 = time.time()
    counts, problems = run(level)
    for case, outcome, detail in problems:
        print(f"{outcome:8s} {case}: {detail}")
    print(summary(counts), f"({time.time() - t0:.0f} s, level {level})")
    sys.exit(0 if counts["unclear"] == counts["silent"] == counts["crash"] == 0 else 1)
