"""Table files under hostile conditions: a full disk, unwritable targets, a closed output pipe,
damaged cache entries, and a corpus of damaged, hostile and special files (tests/damaged_corpus.py).

Crash-prone parts run in subprocesses with a time limit: a segfault or hang is a test failure,
not a crashed test run. The full-disk tests mount a small tmpfs and are skipped (with the reason)
where mounting is not permitted.
"""
import contextlib
import os
import shutil
import stat
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

import damaged_corpus
from fastrest import TableFileError, tables
from fastrest.tables import store

REPO = Path(__file__).resolve().parents[1]
TINY_GRID = dict(eps_y_min=0.004, eps_y_max=0.006, n_eps_y=6, nu_min=0.3, nu_max=0.35, n_nu=6,
                 bits_per_octave=1, eps_y_blocks=[], n_eps_y_energy=6)
GRID_ARGS = ["--eps-y-min", "0.004", "--eps-y-max", "0.006", "--n-eps-y", "7", "--nu-min", "0.3",
             "--nu-max", "0.35", "--n-nu", "6", "--bits-per-octave", "1", "--eps-y-blocks", "none",
             "--n-eps-y-energy", "6", "--no-progress"]
OTHER_GRID = dict(TINY_GRID, n_eps_y=7)


def env():
    e = dict(os.environ)
    e["PYTHONPATH"] = str(REPO) + os.pathsep + e.get("PYTHONPATH", "")
    return e


def run(args, timeout=600, **kwargs):
    return subprocess.run([sys.executable, *args], env=kwargs.pop("env", env()), capture_output=True,
                          text=True, timeout=timeout, **kwargs)


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    path = tmp_path_factory.mktemp("tiny") / "tiny.h5"
    tables.build(path, TINY_GRID, progress=False, measure=False)
    return path


@contextlib.contextmanager
def tmpfs(size, options=""):
    """A fresh tmpfs of ``size`` mounted on a temporary directory; skips if mounting is refused."""
    if not sys.platform.startswith("linux") or shutil.which("mount") is None:
        pytest.skip("mounting a tmpfs needs Linux and the mount command")
    d = tempfile.mkdtemp(prefix="fastrest-tmpfs-")
    opts = f"size={size}" + (f",{options}" if options else "")
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", opts, "tmpfs", d], capture_output=True, text=True)
    if r.returncode != 0:
        os.rmdir(d)
        pytest.skip(f"cannot mount a tmpfs here (root or CAP_SYS_ADMIN needed): {r.stderr.strip()}")
    try:
        yield Path(d)
    finally:
        subprocess.run(["umount", d], capture_output=True)
        os.rmdir(d)


def fill(directory, leave):
    """Fill the file system of ``directory`` with a file, then free ``leave`` bytes of it."""
    filler = directory / "filler"
    with open(filler, "wb") as fh:
        try:
            while True:
                fh.write(bytes(1 << 16))
                fh.flush()
        except OSError:
            pass
    with open(filler, "r+b") as fh:
        fh.truncate(max(filler.stat().st_size - leave, 0))
    return filler


def leftovers(directory):
    return sorted(p.name for p in directory.iterdir() if p.suffix in (".tmp", ".probe"))


def test_full_disk_build_gives_oserror_keeps_old_table(tiny):
    """`fastrest build --out` on a nearly full file system: exit status 1, one line naming the file
    and the cause, the old table intact and loadable, no temporary file (it segfaulted before:
    h5py closing a file after a failed write)."""
    with tmpfs("2m") as d:
        target = d / "table.h5"
        shutil.copyfile(tiny, target)
        before = target.read_bytes()
        fill(d, 300 * 1024)   # a new ~650 kB table cannot fit
        r = run(["-m", "fastrest", "build", "--out", str(target), *GRID_ARGS])
        assert r.returncode == 1, (r.returncode, r.stderr[-2000:])
        lines = r.stderr.strip().splitlines()
        assert len(lines) == 1 and "Traceback" not in r.stderr, r.stderr
        assert str(target) in lines[0] and "No space left on device" in lines[0]
        assert target.read_bytes() == before
        assert tables.read(target).grid == tables.normalise_grid(TINY_GRID)
        assert leftovers(d) == []


CACHED_CHILD = """
import sys, warnings
from fastrest import tables
grid = dict(eps_y_min=0.004, eps_y_max=0.006, n_eps_y=7, nu_min=0.3, nu_max=0.35, n_nu=6,
            bits_per_octave=1, eps_y_blocks=[], n_eps_y_energy=6)
for attempt in range(2):   # the caller catches the error and carries on: no crash later either
    try:
        tables.cached_table(grid, progress=False)
        print("built")
    except OSError as exc:
        print("OSError", exc.errno, exc)
print("alive")
"""


def test_full_disk_cached_table_gives_oserror_no_crash():
    """cached_table with the cache on a full file system: OSError naming the file, twice, and the
    process carries on (it raised RuntimeError and then segfaulted before)."""
    with tmpfs("1m") as d:
        cache = d / "cache"
        fill(d, 100 * 1024)
        r = run(["-c", CACHED_CHILD], env=dict(env(), FASTREST_CACHE_DIR=str(cache)))
        assert r.returncode == 0, (r.returncode, r.stderr[-2000:])
        out = r.stdout.splitlines()
        assert out[-1] == "alive" and len(out) == 3, r.stdout
        for line in out[:2]:
            assert line.startswith("OSError 28 ") and str(cache) in line, line
        assert not cache.exists() or leftovers(cache) == []


def test_read_only_file_system_build_is_one_line_error(tiny):
    with tmpfs("2m") as d:
        shutil.copyfile(tiny, d / "table.h5")
        r = subprocess.run(["mount", "-o", "remount,ro", str(d)], capture_output=True, text=True)
        if r.returncode != 0:
            pytest.skip(f"cannot remount read-only: {r.stderr.strip()}")
        target = d / "table.h5"
        r = run(["-m", "fastrest", "build", "--out", str(target), *GRID_ARGS], timeout=120)
        assert r.returncode == 1 and "Traceback" not in r.stderr, r.stderr
        line, = r.stderr.strip().splitlines()
        assert str(target) in line and "Read-only file system" in line
        assert tables.read(target).grid == tables.normalise_grid(TINY_GRID)


@pytest.mark.parametrize("kind, reason", [("DIR", "is a directory"), ("CHR", "character device"),
                                          ("FIFO", "FIFO"), ("MISSING", "")])
def test_unwritable_out_is_one_line_error_before_building(tmp_path, kind, reason):
    """Special files are made in tmp_path: no test touches the system's /dev or /proc."""
    target = tmp_path / "t.h5"
    if kind == "DIR":
        target = tmp_path
    elif kind == "CHR":
        try:
            os.mknod(target, stat.S_IFCHR | 0o600, os.makedev(1, 3))
        except OSError as exc:
            pytest.skip(f"cannot make a character device here (root or CAP_MKNOD needed): {exc}")
    elif kind == "FIFO":
        os.mkfifo(target)
    else:
        target = tmp_path / "file" / "t.h5"
        (tmp_path / "file").write_text("a file, not a directory")
        reason = "Not a directory"
    target = str(target)
    # the default grid takes seconds to build: the check comes first
    r = run(["-m", "fastrest", "build", "--out", target, "--no-progress"], timeout=60)
    assert r.returncode == 1 and "Traceback" not in r.stderr, r.stderr
    line, = r.stderr.strip().splitlines()
    assert line.startswith("fastrest build: error:") and target in line and reason in line, line
    assert r.stdout == ""
    if kind in ("CHR", "FIFO"):
        assert not os.path.isfile(target)  # still the special file


def test_info_into_closed_pipe_is_quiet():
    """`fastrest info --json FILE | head`: the reader goes away; no BrokenPipeError traceback."""
    read_end, write_end = os.pipe()
    os.close(read_end)
    try:
        r = subprocess.run([sys.executable, "-m", "fastrest", "info", "--json", str(tables.default_table_path())],
                           env=env(), stdout=write_end, stderr=subprocess.PIPE, text=True, timeout=120)
    finally:
        os.close(write_end)
    assert r.returncode == 141, r.stderr
    assert r.stderr == ""


def test_damaged_cached_table_is_rebuilt_with_a_warning(tmp_path, monkeypatch, tiny):
    cache = tmp_path / "cache"
    cache.mkdir()
    monkeypatch.setenv("FASTREST_CACHE_DIR", str(cache))
    monkeypatch.setattr(store, "LOADED", {})
    path = cache / f"{tables.grid_key(TINY_GRID)}.h5"
    data = tiny.read_bytes()
    for damage in (data[:len(data) // 2], data[:1000] + bytes(4096) + data[5096:], b""):
        path.write_bytes(damage)
        with pytest.warns(RuntimeWarning, match="rebuilding the cached table") as rec:
            t = tables.cached_table(TINY_GRID, progress=False)
        assert str(path) in str(rec[0].message)
        assert tables.read(path).grid == t.grid == tables.normalise_grid(TINY_GRID)
        store.LOADED.clear()
    # a FIFO in the cache's place is refused without blocking, and never replaced
    path.unlink()
    os.mkfifo(path)
    with pytest.raises(OSError, match="FIFO") as excinfo:
        tables.cached_table(TINY_GRID, progress=False)
    assert str(path) in str(excinfo.value)
    assert stat.S_ISFIFO(os.stat(path).st_mode)


def _check_corpus(results):
    counts, total = damaged_corpus.summary(results)
    report = "\n".join(f"{c}: {v}" for c, v in counts.items()) + f"\ntotal: {total}"
    print(report)
    bad = [r for r in results if r[2] != "refused"]
    assert not bad, f"{len(bad)} of {len(results)} not refused with TableFileError:\n" + "\n".join(
        f"{c}/{n}: {o}" for c, n, o in bad)


@pytest.mark.slow
def test_damaged_corpus_is_refused(tiny, tmp_path):
    """Every damaged, hostile or special file of the corpus: TableFileError, 0 crash, 0 hang
    (each loaded in a subprocess with a 20 s limit)."""
    cases = damaged_corpus.make_corpus(tiny, tmp_path / "corpus", n_random=40)
    assert len(cases) > 140
    _check_corpus(damaged_corpus.run_corpus(cases, timeout=20.0))


@pytest.mark.slow
def test_damaged_default_table_corpus_is_refused(tmp_path):
    """A fuzzing campaign's setting: 400 metadata byte flips, 100 data flips and 40 zeroed pages of the
    shipped table, plus the hostile and special cases built from it."""
    cases = damaged_corpus.make_corpus(tables.default_table_path(), tmp_path / "corpus", n_random=400,
                                       n_pages=40, lazy=True)
    _check_corpus(damaged_corpus.run_corpus(cases, timeout=60.0))


def test_table_file_error_is_the_only_error(tiny, tmp_path):
    """In process, the quick cases: the exception is TableFileError (a ValueError) naming the file."""
    assert issubclass(TableFileError, ValueError)
    for name in ("missing.h5", "empty.h5"):
        p = tmp_path / name
        if name == "empty.h5":
            p.write_bytes(b"")
        with pytest.raises(TableFileError) as exc:
            tables.load_table(p)
        assert str(p) in str(exc.value)


# --- files resealed after damage reach HDF5 only in a check process --------------------------------

def _resealed(n, pick=None):
    cases = [c for c in damaged_corpus.byte_cases(tables.default_table_path(), 0, 0, 2024, n_resealed=n)
             if c[0] == "resealed" and (pick is None or c[1] in pick)]
    return [(c, name, damaged_corpus.LazyFile(Path(tempfile.gettempdir()) / f"fastrest-{os.getpid()}-{name}.h5", make))
            for c, name, make in cases]


def _check_resealed(cases):
    from corpus_runner import fingerprint

    results = damaged_corpus.run_corpus(cases, timeout=120.0)
    base = fingerprint(tables.read(tables.default_table_path()))
    wrong = damaged_corpus.resealed_ok(results, base)
    counts, _ = damaged_corpus.summary(results)
    print(counts)
    assert not wrong, wrong
    return results


@pytest.mark.slow
def test_resealed_damage_is_refused_or_harmless():
    """20 metadata flips of the shipped table with a recomputed digest, each loaded in a child
    process: TableFileError, or (a byte HDF5 never reads) the shipped table's numbers exactly; the
    HDF5 parser's crashes and hangs stay in fastrest's check process."""
    _check_resealed(_resealed(20))


def test_resealed_file_that_crashes_hdf5_is_refused():
    """resealed-14776 (seed 2024) aborted the process inside HDF5 (SIGABRT, in-memory file image)
    before the check process; now the check process dies and the caller gets TableFileError."""
    results = _check_resealed(_resealed(300, pick={"resealed-14776"}))
    assert [r[2] for r in results] == ["refused"]


@pytest.mark.slow
def test_resealed_corpus_300_is_refused_or_harmless():
    """A fuzzing campaign's setting: 300 resealed metadata flips (before the check process: 171 accepted with
    the same numbers, 128 refused, 1 crash of the whole process)."""
    results = _check_resealed(_resealed(300))
    assert sum(r[2] == "refused" for r in results) >= 100


def test_check_process_crash_hang_and_refusal_are_table_file_errors(monkeypatch):
    from fastrest.tables import probe

    digest = "f" * 64
    monkeypatch.setattr(probe, "CHECKED", set())
    monkeypatch.setattr(probe, "_CHILD", "import os, signal; os.kill(os.getpid(), signal.SIGSEGV)")
    with pytest.raises(TableFileError, match=r"x\.h5: the HDF5 library crashed \(SIGSEGV\)"):
        probe.check_image(b"data", digest, "x.h5")
    monkeypatch.setattr(probe, "_CHILD", "import time; time.sleep(60)")
    monkeypatch.setattr(probe, "CHECK_TIMEOUT", 1.0)
    with pytest.raises(TableFileError, match=r"x\.h5: the HDF5 library did not finish parsing the file within 1 s"):
        probe.check_image(b"data", digest, "x.h5")
    monkeypatch.setattr(probe, "_CHILD", "import sys; sys.stdout.write('refused x.h5: bad'); sys.exit(0)")
    with pytest.raises(TableFileError, match=r"^x\.h5: bad$"):
        probe.check_image(b"data", digest, "x.h5")
    monkeypatch.setattr(probe, "_CHILD", "raise MemoryError('too big')")
    with pytest.raises(TableFileError, match=r"x\.h5: the process checking the file failed \(exit 1\): MemoryError"):
        probe.check_image(b"data", digest, "x.h5")
    assert probe.CHECKED == set()   # nothing failed is remembered as checked
    monkeypatch.setattr(probe, "_CHILD", "import sys; sys.stdout.write('ok')")
    probe.check_image(b"data", digest, "x.h5")
    assert probe.CHECKED == {digest}
    monkeypatch.setattr(probe, "_CHILD", "import os, signal; os.kill(os.getpid(), signal.SIGSEGV)")
    probe.check_image(b"data", digest, "x.h5")   # checked once per process


def test_untrusted_file_is_checked_once_trusted_ones_never(tmp_path, monkeypatch, tiny):
    """The shipped table (digest recorded in the package) and files this process wrote are parsed
    in-process at once; another file is checked in a child process the first time only."""
    from fastrest.tables import probe
    from fastrest.tables._default_digest import SHA256
    from fastrest.tables.file import read_verified

    assert read_verified(tables.default_table_path())[1] == SHA256 and SHA256 in probe.TRUSTED
    calls = []
    real = probe.subprocess.run

    def spy(*args, **kwargs):
        calls.append(args)
        return real(*args, **kwargs)

    monkeypatch.setattr(probe.subprocess, "run", spy)
    monkeypatch.setattr(probe, "CHECKED", set())
    tables.read(tables.default_table_path())
    written = tmp_path / "w.h5"
    tables.build(written, TINY_GRID, progress=False, measure=False)
    tables.read(written)
    assert calls == []
    # tiny.h5 was written by this process too: a copy with another digest stands for a foreign file
    other = tmp_path / "other.h5"
    other.write_bytes(tiny.read_bytes())
    import h5py
    with h5py.File(other, "r+") as f:
        f.attrs["history"] = "copied"
    damaged_corpus.reseal(other)
    for _ in range(2):
        assert tables.read(other).grid == tables.normalise_grid(TINY_GRID)
    assert len(calls) == 1


def test_build_default_records_the_digest(tmp_path, monkeypatch):
    """Building the shipped table's file writes its digest into the package (_default_digest.py)."""
    from fastrest.tables import store
    from fastrest.tables.file import read_verified

    monkeypatch.setattr(store, "_HERE", tmp_path)
    monkeypatch.setattr(store, "LOADED", {})
    (tmp_path / "default.h5").write_bytes(b"")
    tables.build(tmp_path / "default.h5", TINY_GRID, progress=False, measure=False)
    text = (tmp_path / "_default_digest.py").read_text()
    assert f"SHA256 = '{read_verified(tmp_path / 'default.h5')[1]}'" in text
