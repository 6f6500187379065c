"""Old code against new, interleaved: the runner of ``bench.loading_ab`` and ``bench.bounds_ab``.

Each round runs the worker (a ``python -c`` script printing numbers on its last line) once with the
old checkout first on PYTHONPATH and once with this one, each in its own Numba cache. The worker
runs in a neutral directory: ``-c`` puts the working directory first on sys.path, which would
shadow the old checkout with this one; the old worker's ``fastrest.__file__`` is checked.
"""
import os
import subprocess
import sys
import tempfile
from pathlib import Path

PRINT_PATH = "import fastrest; print(fastrest.__file__)\n"


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
                out = subprocess.run([sys.executable, "-c", PRINT_PATH + worker], env=env, capture_output=True,
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
