"""Load table files in a child process, one path per line, with a time limit per file: a crash or
hang of the loader is recorded as an outcome instead of ending the caller (tests/damaged_corpus.py)."""
import os
import select
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]

# The child reads one path per line and answers one line per path ("accepted" with a fingerprint
# of the numbers the table gives, so that an accepted damaged file can be compared with its base).
CHILD = r"""
import sys
from fastrest import TableFileError, tables
from corpus_runner import fingerprint
print("READY", flush=True)
for line in sys.stdin:
    path = line.rstrip("\n")
    try:
        status = "accepted " + fingerprint(tables.read(path))
    except TableFileError:
        status = "refused"
    except BaseException as exc:
        status = "other " + type(exc).__name__ + ": " + str(exc).replace("\n", " ")[:300]
    print(status, flush=True)
"""


def fingerprint(table):
    """SHA-256 over everything a Table evaluates (its TableData, the stored W* it reads, its grid)."""
    import hashlib
    import json

    import numpy as np

    h = hashlib.sha256(json.dumps(table.grid, sort_keys=True).encode())
    for part in (table.data, table.energy):
        for name, value in zip(part._fields, part):
            h.update(name.encode() + np.ascontiguousarray(value).tobytes())
    return h.hexdigest()[:16]


class LazyFile:
    """A corpus file written only when the runner needs it (and removed after): the byte-level
    cases of a 6 MB table would take gigabytes at once."""

    def __init__(self, path, make):
        self.path, self.make = Path(path), make

    def materialise(self):
        self.path.write_bytes(self.make())
        return self.path

    def __str__(self):
        return str(self.path)


# --- the runner --------------------------------------------------------------------------------

def _env():
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(REPO), str(REPO / "tests"), env.get("PYTHONPATH", "")])
    return env


class _Child:
    """A Python process answering one line per path; dies or hangs without harm to the caller."""

    def __init__(self):
        self.proc = subprocess.Popen([sys.executable, "-c", CHILD], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, env=_env())
        self.buf = b""

    def line(self, timeout):
        fd = self.proc.stdout.fileno()
        deadline = time.monotonic() + timeout
        while b"\n" not in self.buf:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([fd], [], [], left)[0]:
                return None  # hang
            chunk = os.read(fd, 65536)
            if not chunk:
                return ""  # the process ended
            self.buf += chunk
        line, self.buf = self.buf.split(b"\n", 1)
        return line.decode()

    def ask(self, path, timeout):
        try:
            self.proc.stdin.write(f"{path}\n".encode())
            self.proc.stdin.flush()
        except BrokenPipeError:
            return ""
        return self.line(timeout)

    def close(self):
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait()
        self.proc.stdin.close()
        self.proc.stdout.close()


def run_corpus(cases, timeout=20.0, start_timeout=120.0):
    """Load every case's path in a child process; returns a list of (category, name, outcome).

    outcome: "refused" (TableFileError), "accepted <fingerprint>", "other <Exception>: ...", "crash (exit N)"
    or "hang (> timeout s)". A crashed or hung child is replaced for the next case.
    """
    results, child = [], None
    try:
        for category, name, path in cases:
            if child is None:
                child = _Child()
                if child.line(start_timeout) != "READY":
                    raise RuntimeError("the loader process did not start")
            lazy = isinstance(path, LazyFile)
            answer = child.ask(path.materialise() if lazy else path, timeout)
            if lazy:
                path.path.unlink()
            if answer is None or answer == "":
                if answer is None:
                    outcome = f"hang (> {timeout:g} s)"
                    child.close()
                else:
                    child.close()
                    outcome = f"crash (exit {child.proc.returncode})"
                child = None
            else:
                outcome = answer
            results.append((category, name, outcome))
    finally:
        if child is not None:
            child.close()
    return results


def summary(results):
    """Counts by category and outcome class (refused / accepted / other / crash / hang)."""
    counts = {}
    for category, _, outcome in results:
        kind = outcome.split(" ")[0]
        counts.setdefault(category, {}).setdefault(kind, 0)
        counts[category][kind] += 1
    total = {}
    for c in counts.values():
        for k, v in c.items():
            total[k] = total.get(k, 0) + v
    return counts, total


