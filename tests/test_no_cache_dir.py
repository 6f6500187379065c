"""A read-only install where Numba finds no writable cache directory: ``import fastrest`` works,
compiles without on-disk caching and warns once (it raised "no locator available" before).

Simulated in a child process on a copy of the package whose ``__pycache__`` directories are
files (so they cannot be created), with HOME, XDG_CACHE_HOME and NUMBA_CACHE_DIR below a file:
this holds as root too, which file permissions would not stop.
"""
import os
import pathlib
import shutil
import subprocess
import sys

import fastrest

PACKAGE = pathlib.Path(fastrest.__file__).resolve().parent

CHILD = r"""
import warnings
warnings.simplefilter("always")
with warnings.catch_warnings(record=True) as rec:
    import fastrest
    from fastrest._jit import jit

    @jit
    def twice(x):
        return 2.0 * x

    value = twice(1.5)
assert fastrest.__file__.startswith(EXPECTED), fastrest.__file__
assert value == 3.0
ours = [w for w in rec if "cannot cache compiled kernels" in str(w.message)]
assert len(ours) == 1, [str(w.message) for w in rec]
assert ours[0].category is RuntimeWarning and "NUMBA_CACHE_DIR" in str(ours[0].message)
print("OK")
"""


def test_import_without_any_writable_cache_directory(tmp_path):
    """A few seconds: kernels compile lazily, so the import itself compiles little."""
    copy = tmp_path / "site" / "fastrest"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__", "default.h5"))
    os.symlink(PACKAGE / "tables" / "default.h5", copy / "tables" / "default.h5")
    for d in [copy, *(p for p in copy.rglob("*") if p.is_dir())]:
        (d / "__pycache__").write_text("not a directory")
    blocker = tmp_path / "afile"
    blocker.write_text("a file: nothing can be created below it")
    env = {k: v for k, v in os.environ.items() if not k.startswith(("NUMBA_", "PYTHON"))}
    env.update(HOME=str(blocker / "home"), XDG_CACHE_HOME=str(blocker / "cache"),
               NUMBA_CACHE_DIR=str(blocker / "numba"), PYTHONPATH=str(copy.parent), PYTHONDONTWRITEBYTECODE="1")
    code = f"EXPECTED = {str(copy)!r}\n" + CHILD
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=600,
                       cwd=tmp_path)
    assert r.returncode == 0 and r.stdout.strip() == "OK", r.stderr[-3000:]
