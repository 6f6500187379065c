"""Tests of the HDF5 table storage layer (fastrest.tables.hdf5, hdf5_read, file)."""
import os
import signal
import stat
import subprocess
import sys
import textwrap
import time

import h5py
import numpy as np
import pytest

import fastrest
from fastrest.tables import file as tablefile, hdf5
from fastrest.tables.hdf5 import FORMAT_NAME, FORMAT_VERSION, TableFileError, write_table
from fastrest.tables.hdf5_read import read_table
from damaged_corpus import reseal


def example():
    """Axes, datasets and attributes covering every supported kind of value."""
    velocity = np.linspace(0.1, 10.0, 5)
    nu = np.array([0.2, 0.3, 0.45])
    # Values whose bits a lossy round trip would change: -0.0, NaN, inf, a subnormal.
    e = np.arange(15, dtype=np.float64).reshape(5, 3) / 7.0
    e[0, :] = [-0.0, np.nan, np.inf]
    e[1, 0] = 5e-324
    axes = {
        "velocity": (velocity, "m s-1", "impact velocity"),
        "nu": (nu, "1", "Poisson's ratio"),
    }
    datasets = {
        "restitution": (e, ("velocity", "nu"), "1", "coefficient of restitution"),
        "regime": (np.arange(5, dtype=np.int32), ("velocity",), "1", "regime code"),
        "omega_star_switch": (np.float64(1.9), (), "1", "switch interference"),
    }
    attrs = {
        "title": "test table",
        "references": "doi:10.1007/s11071-009-9591-z",
        "n_points": 15,
        "tolerance": 1e-12,
        "limits": np.array([0.0005, 0.01]),
        "grid": {"velocity": {"n": 5, "spacing": "linear"}, "nu": [0.2, 0.3, 0.45]},
    }
    return axes, datasets, attrs


def write_example(path):
    write_table(path, *example())
    return path


def test_round_trip(tmp_path):
    path = write_example(tmp_path / "table.h5")
    axes, datasets, attrs = example()
    table = read_table(path)

    assert table.path == str(path)
    assert set(table.axes) == set(axes)
    assert set(table.datasets) == set(datasets)
    for name, (values, units, long_name) in axes.items():
        assert table.axes[name].dtype == np.float64
        assert table.axes[name].tobytes() == values.tobytes()
        assert table.units[name] == units
        assert table.long_names[name] == long_name
    for name, (values, dims, units, long_name) in datasets.items():
        got = table.datasets[name]
        assert got.dtype == np.asarray(values).dtype
        assert got.shape == np.shape(values)
        assert got.tobytes() == np.asarray(values).tobytes()  # bitwise, NaN and -0.0 included
        assert table.dims[name] == dims
        assert table.units[name] == units
        assert table.long_names[name] == long_name

    for key, value in attrs.items():
        if isinstance(value, np.ndarray):
            np.testing.assert_array_equal(table.attrs[key], value)
        else:
            assert table.attrs[key] == value
    assert table.attrs["grid"]["velocity"]["n"] == 5  # JSON decoded back into a dict
    assert table.attrs["format"] == FORMAT_NAME
    assert table.attrs["format_version"] == FORMAT_VERSION
    assert table.attrs["fastrest_version"] == fastrest.__version__
    assert len(table.attrs["checksum"]) == 64
    assert table.attrs["checksum_algorithm"] == "sha256"

    # What h5dump, h5netcdf and xarray see: named scales attached to each dimension,
    # CF attributes, contiguous uncompressed storage.
    with h5py.File(path, "r") as f:
        for name in axes:
            assert h5py.h5ds.is_scale(f[name].id)
            assert f[name].attrs["NAME"] == name.encode()
        for name, (_, dims, units, long_name) in datasets.items():
            dset = f[name]
            assert not h5py.h5ds.is_scale(dset.id)
            assert [[s.name for s in dim.values()] for dim in dset.dims] == [
                ["/" + axis] for axis in dims]
            assert dset.attrs["units"] == units
            assert dset.attrs["long_name"] == long_name
            assert dset.chunks is None and dset.compression is None
        assert f.attrs["title"] == "test table"


def test_float32_and_integer_axis_stored_as_float64(tmp_path):
    path = tmp_path / "table.h5"
    write_table(path, {"x": (np.arange(3), "m", "x")},
                {"y": (np.ones(3, dtype=np.float32), ("x",), "1", "y")}, {})
    table = read_table(path)
    assert table.axes["x"].dtype == np.float64
    assert table.datasets["y"].dtype == np.float64


def test_writing_twice_gives_identical_bytes(tmp_path):
    first = write_example(tmp_path / "a.h5")
    # HDF5 timestamps, if any were written, have a resolution of one second.
    start = int(time.time())
    while int(time.time()) == start:
        time.sleep(0.01)
    second = write_example(tmp_path / "b.h5")
    assert first.read_bytes() == second.read_bytes()
    before = first.read_bytes()
    write_example(first)  # rewriting over an existing file
    assert first.read_bytes() == before


def test_new_file_is_not_private_to_the_owner(tmp_path):
    # mkstemp makes 0o600 files; the table must get the usual umask-based mode instead.
    path = write_example(tmp_path / "table.h5")
    umask = os.umask(0)
    os.umask(umask)
    assert (os.stat(path).st_mode & 0o777) == (0o666 & ~umask)


def test_truncated_file(tmp_path):
    path = write_example(tmp_path / "table.h5")
    with open(path, "r+b") as fh:
        fh.truncate(os.path.getsize(path) // 2)
    with pytest.raises(TableFileError, match="truncated") as excinfo:
        read_table(path)
    assert str(path) in str(excinfo.value)


def flip_data_byte(path):
    with h5py.File(path, "r") as f:
        offset = f["restitution"].id.get_offset()
        size = f["restitution"].id.get_storage_size()
    assert offset is not None and size > 0
    with open(path, "r+b") as fh:
        fh.seek(offset + size // 2)
        byte = fh.read(1)[0]
        fh.seek(offset + size // 2)
        fh.write(bytes([byte ^ 0xFF]))


def test_flipped_data_byte_fails_digest(tmp_path):
    path = write_example(tmp_path / "table.h5")
    flip_data_byte(path)
    with pytest.raises(TableFileError, match="digest mismatch") as excinfo:
        read_table(path)
    assert str(path) in str(excinfo.value)


def test_flipped_data_byte_with_recomputed_digest_fails_checksum(tmp_path):
    """The arrays' checksum attribute still catches a change whose file digest was recomputed."""
    path = write_example(tmp_path / "table.h5")
    flip_data_byte(path)
    reseal(path)
    with pytest.raises(TableFileError, match="checksum mismatch") as excinfo:
        read_table(path)
    assert str(path) in str(excinfo.value)


def test_header_holds_size_and_digest_of_the_bytes(tmp_path):
    """The first 512 bytes (HDF5's user block) hold the size and SHA-256 of the rest, which a
    reader can check with plain reads; h5py sees an ordinary HDF5 file with a user block."""
    import hashlib

    path = write_example(tmp_path / "table.h5")
    data = path.read_bytes()
    text = data[:512].rstrip(b"\0").decode("ascii").splitlines()
    assert text == ["fastrest-table-file 1", f"size {len(data)}",
                    f"sha256 {hashlib.sha256(data[512:]).hexdigest()}"]
    assert data[512:520] == b"\x89HDF\r\n\x1a\n"
    assert read_table(path).digest == hashlib.sha256(data[512:]).hexdigest()
    with h5py.File(path, "r") as f:
        assert f.userblock_size == 512 and f.attrs["format"] == FORMAT_NAME


def test_missing_checksum(tmp_path):
    path = write_example(tmp_path / "table.h5")
    with h5py.File(path, "a") as f:
        del f.attrs["checksum"]
    with pytest.raises(TableFileError, match="digest"):
        read_table(path)
    reseal(path)
    with pytest.raises(TableFileError, match="checksum"):
        read_table(path)


def test_missing_axis(tmp_path):
    path = write_example(tmp_path / "table.h5")
    with h5py.File(path, "a") as f:
        del f["nu"]
    reseal(path)
    with pytest.raises(TableFileError, match="missing axis") as excinfo:
        read_table(path)
    assert "restitution" in str(excinfo.value)


def test_foreign_hdf5_file(tmp_path):
    path = tmp_path / "foreign.h5"
    with h5py.File(path, "w") as f:
        f["data"] = np.arange(4.0)
    with pytest.raises(TableFileError, match="without a fastrest header") as excinfo:
        read_table(path)
    assert str(path) in str(excinfo.value) and "rebuild" in str(excinfo.value)
    with h5py.File(path, "w", userblock_size=512) as f:  # with a valid header
        f["data"] = np.arange(4.0)
    reseal(path)
    with pytest.raises(TableFileError, match="not a fastrest table") as excinfo:
        read_table(path)
    assert str(path) in str(excinfo.value)


def test_newer_format_version(tmp_path):
    path = write_example(tmp_path / "table.h5")
    with h5py.File(path, "a") as f:
        f.attrs["format_version"] = FORMAT_VERSION + 1
    reseal(path)
    with pytest.raises(TableFileError) as excinfo:
        read_table(path)
    message = str(excinfo.value)
    assert str(path) in message
    assert f"format version {FORMAT_VERSION + 1}" in message
    assert f"format version {FORMAT_VERSION} " in message
    assert "upgrade fastrest" in message and "rebuild" in message


def test_not_an_hdf5_file(tmp_path):
    path = tmp_path / "random.h5"
    path.write_bytes(np.random.default_rng(0).bytes(4096))
    with pytest.raises(TableFileError, match="not a fastrest table file") as excinfo:
        read_table(path)
    assert str(path) in str(excinfo.value)


def test_missing_file(tmp_path):
    path = tmp_path / "nowhere.h5"
    with pytest.raises(TableFileError, match="does not exist") as excinfo:
        read_table(path)
    assert str(path) in str(excinfo.value)


def test_bad_input_is_rejected_before_writing(tmp_path):
    path = write_example(tmp_path / "table.h5")
    before = path.read_bytes()
    axes, datasets, attrs = example()
    for bad in (np.array([True, False, True, False, True]),
                np.array(["a", "b", "c", "d", "e"], dtype=object)):
        datasets["bad"] = (bad, ("velocity",), "1", "bad")
        with pytest.raises(TypeError):
            write_table(path, axes, datasets, attrs)
    assert path.read_bytes() == before
    assert list(tmp_path.glob("*.tmp")) == []


def test_exception_while_writing_keeps_old_file(tmp_path, monkeypatch):
    path = write_example(tmp_path / "table.h5")
    before = path.read_bytes()
    calls = []
    original = hdf5.write_variable

    def failing_write(f, name, *args):
        calls.append(name)
        if len(calls) == 3:
            # The file is built in memory: nothing is on disk yet.
            assert list(tmp_path.glob("*.tmp")) == []
            raise RuntimeError("simulated failure while writing")
        return original(f, name, *args)

    monkeypatch.setattr(hdf5, "write_variable", failing_write)
    axes, datasets, attrs = example()
    datasets["restitution"] = (np.zeros((5, 3)), ("velocity", "nu"), "1", "new content")
    with pytest.raises(RuntimeError, match="simulated"):
        write_table(path, axes, datasets, attrs)

    assert len(calls) == 3
    assert path.read_bytes() == before
    assert read_table(path).long_names["restitution"] == "coefficient of restitution"
    assert list(tmp_path.glob("*.tmp")) == []


class FailingOs:
    """``os`` for fastrest.tables.file whose n-th write fails with ``code`` (after a short write)."""

    def __init__(self, code, fail_at=2):
        self.code, self.fail_at, self.writes = code, fail_at, 0

    def __getattr__(self, name):
        return getattr(os, name)

    def write(self, fd, data):
        self.writes += 1
        if self.writes >= self.fail_at:
            raise OSError(self.code, os.strerror(self.code))
        return os.write(fd, data[:len(data) // 2])  # a short write first, as on a filling disk


@pytest.mark.parametrize("code", [28, 5, 122])  # ENOSPC, EIO, EDQUOT
def test_write_error_gives_oserror_naming_path_and_keeps_old_file(tmp_path, monkeypatch, code):
    path = write_example(tmp_path / "table.h5")
    before = path.read_bytes()
    monkeypatch.setattr(tablefile, "CHUNK_BYTES", 1024)
    monkeypatch.setattr(tablefile, "os", FailingOs(code, fail_at=3))
    axes, datasets, attrs = example()
    datasets["restitution"] = (np.zeros((5, 3)), ("velocity", "nu"), "1", "new content")
    with pytest.raises(OSError) as excinfo:
        write_table(path, axes, datasets, attrs)
    assert excinfo.value.errno == code
    assert str(path) in str(excinfo.value) and os.strerror(code) in str(excinfo.value)
    monkeypatch.undo()
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["table.h5"]  # no temporary file left


def test_unwritable_targets_give_oserror_naming_path(tmp_path):
    """A directory, a missing directory, a FIFO and a character device (made in tmp_path: no test
    touches the system's /dev) are refused and left as they were, even by root."""
    axes, datasets, attrs = example()
    (tmp_path / "dir.h5").mkdir()
    os.mkfifo(tmp_path / "fifo.h5")
    targets = [tmp_path / "dir.h5", tmp_path / "missing-dir" / "t.h5", tmp_path / "fifo.h5"]
    kept = ["dir.h5", "fifo.h5"]
    try:
        os.mknod(tmp_path / "null.h5", stat.S_IFCHR | 0o600, os.makedev(1, 3))
        targets.append(tmp_path / "null.h5")
        kept.append("null.h5")
    except OSError:
        pass  # not root: the FIFO stands for the special files
    for target in targets:
        with pytest.raises(OSError) as excinfo:
            write_table(target, axes, datasets, attrs)
        assert str(target) in str(excinfo.value), excinfo.value
    assert stat.S_ISFIFO(os.stat(tmp_path / "fifo.h5").st_mode)
    if "null.h5" in kept:
        assert stat.S_ISCHR(os.stat(tmp_path / "null.h5").st_mode)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(kept)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this system")
def test_fifo_is_refused_without_blocking(tmp_path):
    fifo = tmp_path / "table.h5"
    os.mkfifo(fifo)
    t0 = time.monotonic()
    with pytest.raises(TableFileError, match="FIFO"):
        read_table(fifo)
    assert time.monotonic() - t0 < 5


CHILD = textwrap.dedent("""
    import os, sys, time
    import numpy as np
    from fastrest.tables import file as tablefile, hdf5

    target, marker = sys.argv[1], sys.argv[2]

    class StallingOs:
        # os for fastrest.tables.file: the first write goes through, then the writer waits to be killed
        def __getattr__(self, name):
            return getattr(os, name)

        def write(self, fd, data):
            n = os.write(fd, data)
            open(marker, "w").close()  # tell the parent we are inside write_table
            time.sleep(60)
            return n

    tablefile.CHUNK_BYTES = 4096
    tablefile.os = StallingOs()
    x = np.linspace(0.0, 1.0, 10_000)
    datasets = {f"d{i:03d}": (x * i, ("x",), "1", f"dataset {i}") for i in range(200)}
    hdf5.write_table(target, {"x": (x, "1", "x")}, datasets, {"title": "new"})
""")


def test_killed_writer_keeps_old_file(tmp_path):
    """A writer killed midway leaves the old table intact; a stray *.tmp file may remain."""
    path = write_example(tmp_path / "table.h5")
    before = path.read_bytes()
    marker = tmp_path / "inside-write_table"
    package_root = os.path.dirname(os.path.dirname(os.path.abspath(fastrest.__file__)))
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [package_root, env.get("PYTHONPATH")]))
    proc = subprocess.Popen([sys.executable, "-c", CHILD, str(path), str(marker)], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 60
        while not marker.exists():
            if proc.poll() is not None:
                pytest.fail(f"writer exited early: {proc.communicate()[1].decode()}")
            assert time.monotonic() < deadline, "writer never reached write_table"
            time.sleep(0.01)
    finally:
        proc.kill()
        proc.wait()
    if sys.platform != "win32":
        assert proc.returncode == -signal.SIGKILL

    assert path.read_bytes() == before
    assert read_table(path).attrs["title"] == "test table"
    # The killed writer's temporary file is left behind; it is never taken for a table.
    stray = list(tmp_path.glob("*.tmp"))
    assert len(stray) == 1
    with pytest.raises(TableFileError):
        read_table(stray[0])
