"""Old code against new, interleaved: the runner of ``bench.loading_ab`` and ``bench.bounds_ab``.

Each round runs the worker (a ``python -c`` script printing numbers on its last line) once with the
old checkout first on PYTHONPATH and once with this one, each in its own Numba cache. The worker
runs in a neutral directory: ``-c`` puts the working directory first on sys.path, which would
shadow the old checkout with this one; the old worker's ``fastrest.__file__`` is checked.
"""
import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

PRINT_PATH = "import fastrest; print(fastrest.__file__)\n"
#: Prepended to every worker too: ``best(f, n)``, the fastest of n calls of f (seconds).
BEST = ("import time\n"
        "def best(f, n):\n"
        "    t = []\n"
        "    for _ in range(n):\n"
        "        a = time.perf_counter(); f(); t.append(time.perf_counter() - a)\n"
        "    return min(t)\n")


def run_interleaved(old, rounds, worker):
    """{"old": [numbers per round], "new": [...]} of ``worker`` run against ``old`` and this checkout."""
    old = Path(old).resolve()
    res = {"old": [], "new": []}
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(rounds):
            for which in ("old", "new"):
                env = dict(os.environ, NUMBA_CACHE_DIR=os.path.join(tmp, which))
                if which == "old":
                    env["PYTHONPATH"] = str(old)
                out = subprocess.run([sys.executable, "-c", PRINT_PATH + BEST + worker], env=env, capture_output=True,
                                     text=True, cwd=tmp)
                if out.returncode:
                    raise RuntimeError(f"{which} worker failed:\n{out.stderr}")
                lines = out.stdout.strip().splitlines()
                if (which == "old") != lines[0].startswith(str(old)):
                    raise RuntimeError(f"{which} worker imported {lines[0]}")
                res[which].append(tuple(float(x) for x in lines[-1].split()))
    return res


def medians(res, n):
    """Per path and quantity, the median over rounds."""
    return {k: [sorted(x[j] for x in v)[len(v) // 2] for j in range(n)] for k, v in res.items()}


def revisions(old):
    """Short commit names of the old checkout and of this one."""
    def rev(*args):
        return subprocess.run(["git", *args, "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True).stdout.strip()
    return rev("-C", str(old)), rev()


def report_main(argv, prog, doc, title, worker, names, out, rounds=5):
    """The command line of an old/new comparison: run ``worker`` interleaved against ``--old``,
    write the Markdown table of ``names`` (one per number the worker prints) to ``out``."""
    from .report import machine
    p = argparse.ArgumentParser(prog=prog, description=doc)
    p.add_argument("--old", required=True, help="checkout of the old fastrest (put first on PYTHONPATH)")
    p.add_argument("--rounds", type=int, default=rounds)
    a = p.parse_args(argv)
    res = run_interleaved(a.old, a.rounds, worker)
    med = medians(res, len(names))
    m = machine()
    rev, new = revisions(a.old)
    lines = [f"# {title} (`{prog}`)", "",
             f"Machine: {m.get('nproc')}-core {m.get('cpu')}; old = {rev or a.old}, new = {new or 'this checkout'}; "
             f"{a.rounds} interleaved rounds (subprocesses, own Numba caches), median of the per-round bests.", "",
             "| path | old | new | new/old |", "| --- | --- | --- | --- |"]
    lines += [f"| {name} | {med['old'][j]:.3f} | {med['new'][j]:.3f} | {med['new'][j] / med['old'][j]:.3f} |"
              for j, name in enumerate(names)]
    lines += ["", "Rounds (old/new): " + "; ".join(
        ", ".join(f"{o[j]:.2f}/{n[j]:.2f}" for j in range(len(names))) for o, n in zip(res["old"], res["new"]))]
    Path(out).write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return lines
