"""Command line of the benchmark suite: ``python -m bench [--quick] [--out-dir DIR] [--update-readme]``."""
import argparse
import datetime
import shlex
import sys
import time
import warnings
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

FULL = dict(
    n_materials=16, n_time=1_000_000, per_err=1500, n_direct=4000, n_mp=24, rounds_plot=21,
    curve_bits=[2, 3, 4, 5, 6],
    # uniform grids (one eps_y axis for all cells) against the default's blocks of cells
    table_grids=[dict(n_eps_y=20, n_nu=6, bits_per_octave=2, fine_bits_per_octave=2, eps_y_blocks=[]),
                 dict(n_eps_y=40, n_nu=6, bits_per_octave=3, fine_bits_per_octave=3, eps_y_blocks=[]),
                 dict(n_eps_y=40, n_nu=6, eps_y_blocks=[]), dict(n_eps_y=72, n_nu=6, eps_y_blocks=[]),
                 dict(n_eps_y=48, n_nu=6, eps_y_blocks=[[128.0, 16], [256.0, 24], [512.0, 32]])],
    batch_sizes=[10**3, 10**4, 10**5, 10**6, 10**7], thread_sizes=[10**6, 10**7], rounds=21,
    scalar_block=0.02, njit_n=10**6, mm_n=10**6, build_repeats=3, curve_repeats=15, curve_err_n=3000,
    fresh_warm=5, fresh_cold=2, memory_batch_n=10**7,
)
QUICK = dict(
    n_materials=6, n_time=120_000, per_err=300, n_direct=600, n_mp=3, rounds_plot=5,
    curve_bits=[2, 3, 4, 5, 6],
    table_grids=[dict(n_eps_y=20, n_nu=6, bits_per_octave=2, fine_bits_per_octave=2, eps_y_blocks=[]),
                 dict(n_eps_y=40, n_nu=6, eps_y_blocks=[])],
    batch_sizes=[10**3, 10**4, 10**5, 10**6], thread_sizes=[10**6], rounds=5,
    scalar_block=0.005, njit_n=2 * 10**5, mm_n=2 * 10**5, build_repeats=1, curve_repeats=5, curve_err_n=500,
    fresh_warm=1, fresh_cold=1, memory_batch_n=10**6,
)

# Waiting for, and repeating after, other processes' activity (bench.timing.POLICY).
FULL_POLICY = dict(threshold=0.1, retries=2, max_wait=30.0, budget=300.0)
QUICK_POLICY = dict(threshold=0.1, retries=0, max_wait=0.0, budget=0.0)


def loadavg():
    """The 1, 5 and 15 minute load averages (other processes competing for the 2 cores)."""
    try:
        return [float(x) for x in open("/proc/loadavg").read().split()[:3]]
    except (OSError, ValueError):
        return None


def run(quick, out_dir, log=print, command=None):
    import numpy as np  # noqa: F401

    import fastrest
    from . import fresh, modes, report, speed_error, targets
    from . import timing
    from .timing import OtherLoad

    cfg = QUICK if quick else FULL
    timing.POLICY.update(QUICK_POLICY if quick else FULL_POLICY)
    timing._SPENT[0] = 0.0
    t0 = time.perf_counter()
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    warnings.simplefilter("ignore", fastrest.ValidityWarning)
    R = {"quick": quick, "config": cfg, "date": date,
         "command": command or " ".join(["python -m bench"] + [shlex.quote(a) for a in sys.argv[1:]]),
         "machine": report.machine(), "versions": report.versions()}
    R["load"] = {"start": loadavg()}
    load_all = OtherLoad()
    log("fastrest benchmarks" + (" (quick)" if quick else "") + f" -> {out_dir}; load average "
        f"{R['load']['start']}")
    sections, other = {}, {}
    # Peak memory first, while this process is small: a child's ru_maxrss starts at the resident size of
    # the process that forked it.
    for key, title, fn in (("memory", "2. peak memory (fresh processes)", lambda: fresh.peak_memory(cfg, log)),
                           ("speed_error", "1. speed against error", lambda: speed_error.run(cfg, log)),
                           ("modes", "2. modes", lambda: modes.run(cfg, log)),
                           ("fresh", "2. first use (fresh processes)",
                            lambda: {"first_use": fresh.first_use(cfg, log)})):
        log(title)
        t1 = time.perf_counter()
        ld = OtherLoad()
        R[key] = fn()
        sections[key] = time.perf_counter() - t1
        other[key] = ld.stop()
    R["section_s"] = sections
    R["section_other_cores"] = other
    R["load"]["end"] = loadavg()
    R["load"]["other_cores"] = load_all.stop()
    R["policy"] = dict(timing.POLICY, spent_s=timing._SPENT[0])
    if R["load"]["other_cores"] is not None:
        R["load"]["other_cpu_s"] = R["load"]["other_cores"] * (time.perf_counter() - load_all.t0)
    report.apply_search(R)
    R["targets"] = targets.evaluate(R)
    R["elapsed_s"] = time.perf_counter() - t0
    R["headline"] = report.headline(R)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    speed_error.plot(R["speed_error"], out_dir / "speed_vs_error.png")
    report.write_all(R, out_dir)
    log(f"wrote {out_dir / 'RESULTS.md'}, {out_dir / 'readme_table.md'}, {out_dir / 'speed_vs_error.png'} "
        f"in {R['elapsed_s']:.0f} s")
    for t in R["targets"]:
        log(f"  {'met    ' if t['met'] else 'NOT met'}  {t['name']}: {t['measured']}")
    return R


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m bench", description=__doc__)
    p.add_argument("--quick", action="store_true", help="small n, few repeats (under a minute)")
    p.add_argument("--out-dir", default=str(REPO / "bench"), help="where to write the results (default bench/)")
    p.add_argument("--update-readme", action="store_true",
                   help="do not run: replace README.md's benchmark section with <out-dir>/readme_table.md")
    p.add_argument("--force", action="store_true", help="with --update-readme: accept a --quick result")
    p.add_argument("--rerender", action="store_true",
                   help="do not run: render the reports again from <out-dir>/results.json with the stored "
                        "search of bench/stated_figures.json folded in (no timing)")
    args = p.parse_args(argv)
    if args.rerender:
        from .report import rerender
        rerender(args.out_dir)
        return 0
    if args.update_readme:
        from .report import update_readme
        try:
            update_readme(REPO / "README.md", args.out_dir, force=args.force)
        except (FileNotFoundError, ValueError) as exc:
            print(f"python -m bench: {exc}", file=sys.stderr)
            return 2
        print(f"updated {REPO / 'README.md'} from {Path(args.out_dir) / 'readme_table.md'}")
        return 0
    run(args.quick, args.out_dir)
    return 0
