"""What ``--out`` or a path points at is never harmed, every option is
checked before anything is created, input files are read as table files are, counts are bounded,
a full disk gives an OSError naming the file, and Python errors name Python parameters.

Special files are made in tmp_path (no test touches the system's /dev, /proc or the home
directory); a full disk is simulated by making the one atomic writer's ``os.write`` fail with
ENOSPC. Commands that used to hang or exhaust memory run in a subprocess with a time limit.
"""
import errno
import os
import resource
import stat
import subprocess
import sys
from pathlib import Path

import pytest

import fastrest
from fastrest import cli, tables
from fastrest.export import c_header, grid, velocity
from fastrest.tables import file as tablefile

REPO = Path(__file__).resolve().parents[1]
STEEL = ["--E", "200e9", "--nu", "0.33", "--Sy", "1.12e9", "--R", "0.01", "--rho", "7800"]
TINY_GRID = dict(eps_y_min=0.004, eps_y_max=0.006, n_eps_y=6, nu_min=0.3, nu_max=0.35, n_nu=6,
                 bits_per_octave=1, eps_y_blocks=[], n_eps_y_energy=6)


def chardev(path):
    """A character device at ``path`` (the null device's numbers, but a node of our own)."""
    try:
        os.mknod(path, stat.S_IFCHR | 0o600, os.makedev(1, 3))
    except OSError as exc:
        pytest.skip(f"cannot make a character device here (root or CAP_MKNOD needed): {exc}")
    return path


def special(tmp_path, kind, name="target"):
    path = tmp_path / name
    if kind == "fifo":
        os.mkfifo(path)
    else:
        chardev(path)
    return path


def is_special(path, kind):
    mode = os.stat(path).st_mode
    return stat.S_ISFIFO(mode) if kind == "fifo" else stat.S_ISCHR(mode)


def run(args, timeout=60, limit_memory=False):
    def limit():  # a runaway allocation fails at 4 GiB instead of swapping the machine
        resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))

    env = dict(os.environ, PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    return subprocess.run([sys.executable, "-m", "fastrest", *args], capture_output=True, text=True,
                          timeout=timeout, env=env, preexec_fn=limit if limit_memory else None)


# --- 2. special files are never replaced ------------------------------------------------------

@pytest.mark.parametrize("kind", ["fifo", "chr"])
@pytest.mark.parametrize("command", [
    ["export", "c", "--materials", "0.005:0.33"],
    ["export", "grid", "--check-points", "100"],
    ["export", "velocity", *STEEL, "--V-max", "1"],
])
def test_export_refuses_special_out(tmp_path, capsys, kind, command):
    target = special(tmp_path, kind, "target.csv" if "velocity" in command else "target")
    assert cli.main(command + ["--out", str(target)]) == 1
    err = capsys.readouterr().err
    assert str(target) in err and ("FIFO" in err if kind == "fifo" else "character device" in err), err
    assert is_special(target, kind)
    assert sorted(os.listdir(tmp_path)) == [target.name]


@pytest.mark.parametrize("kind", ["fifo", "chr"])
def test_build_and_cache_refuse_special_files(tmp_path, monkeypatch, kind):
    target = special(tmp_path, kind, "t.h5")
    with pytest.raises(OSError, match="FIFO" if kind == "fifo" else "character device"):
        tables.build(target, TINY_GRID, progress=False, measure=False)
    assert is_special(target, kind)
    cache = tmp_path / "cache"
    cache.mkdir()
    monkeypatch.setenv("FASTREST_CACHE_DIR", str(cache))
    entry = special(cache, kind, f"{tables.grid_key(TINY_GRID)}.h5")
    with pytest.raises(OSError) as excinfo:
        tables.cached_table(TINY_GRID, progress=False)
    assert str(entry) in str(excinfo.value)
    assert is_special(entry, kind)


def test_figures_refuse_special_targets_and_check_options_first(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    d = tmp_path / "D"
    for dpi in ("0", "100000"):
        assert cli.main(["figures", "--out", str(d), "--dpi", dpi]) == 2
        err = capsys.readouterr().err
        assert "--dpi" in err and "[1, 1200]" in err, err
        assert not d.exists()  # nothing created before the options are checked
    with pytest.raises(ValueError, match=r"^dpi must"):
        fastrest.figures.write_all(d, dpi=0)
    with pytest.raises(TypeError, match="dpi"):
        fastrest.figures.write_all(d, dpi="150")
    fifo = special(tmp_path, "fifo", "F")
    assert cli.main(["figures", "--out", str(fifo)]) == 1
    assert str(fifo) in capsys.readouterr().err and is_special(fifo, "fifo")
    d.mkdir()
    png = special(d, "fifo", "fig5_e_vs_chang_ling.png")
    assert cli.main(["figures", "--out", str(d)]) == 1
    assert str(png) in capsys.readouterr().err
    assert os.listdir(d) == [png.name] and is_special(png, "fifo")


@pytest.mark.parametrize("out", ["", "sub/", ".", ".csv"])
def test_velocity_out_naming_no_file(tmp_path, monkeypatch, capsys, out):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "sub").mkdir()
    assert cli.main(["export", "velocity", *STEEL, "--V-max", "1", "--out", out]) == 2
    assert "--out" in capsys.readouterr().err
    assert sorted(os.listdir(tmp_path)) == ["sub"] and os.listdir(tmp_path / "sub") == []
    with pytest.raises(ValueError, match=r"^out = "):
        velocity.write_velocity(out, [velocity.pair_from_options(E=2e11, nu=0.33, Sy=1.12e9, R=0.01, rho=7800)],
                                1e-4, 1.0)


# --- 3. a full disk ---------------------------------------------------------------------------

class FullDiskOs:
    """``os`` for fastrest.tables.file: the second write fails with ENOSPC (after a short write)."""

    def __init__(self):
        self.writes = 0

    def __getattr__(self, name):
        return getattr(os, name)

    def write(self, fd, data):
        self.writes += 1
        if self.writes >= 2:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return os.write(fd, data[:max(len(data) // 2, 1)])


@pytest.mark.parametrize("what", ["grid", "velocity", "c"])
def test_full_disk_names_the_file_keeps_the_old_one(tmp_path, monkeypatch, what):
    target = tmp_path / ("v.csv" if what == "velocity" else "out")
    target.write_bytes(b"old contents")
    monkeypatch.setattr(tablefile, "CHUNK_BYTES", 4096)
    monkeypatch.setattr(tablefile, "os", FullDiskOs())
    with pytest.raises(OSError) as excinfo:
        if what == "grid":
            grid.write_grid(target, tol=1e-2, n_check=100)
        elif what == "velocity":
            pair = velocity.pair_from_options(E=2e11, nu=0.33, Sy=1.12e9, R=0.01, rho=7800)
            velocity.write_velocity(tmp_path / "v", [pair], 1e-3, 1.0)
        else:
            c_header.write_header(target, [(0.005, 0.33)])
    monkeypatch.undo()
    assert excinfo.value.errno == errno.ENOSPC
    assert str(target) in str(excinfo.value) and "No space left on device" in str(excinfo.value)
    assert target.read_bytes() == b"old contents"
    assert sorted(os.listdir(tmp_path)) == [target.name]  # no temporary file left


# --- 3. hostile inputs and unbounded counts ---------------------------------------------------

def test_pairs_fifo_does_not_block(tmp_path):
    fifo = special(tmp_path, "fifo", "pairs.csv")
    r = run(["export", "velocity", "--V-max", "5", "--pairs", str(fifo), "--out", str(tmp_path / "x")], timeout=60)
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    assert "--pairs" in r.stderr and "FIFO" in r.stderr


def test_pairs_device_and_huge_file_refused(tmp_path, capsys):
    dev = chardev(tmp_path / "dev.csv")
    assert cli.main(["export", "velocity", "--V-max", "5", "--pairs", str(dev), "--out", str(tmp_path / "x")]) == 2
    assert "character device" in capsys.readouterr().err
    big = tmp_path / "big.csv"
    with open(big, "wb") as fh:
        fh.truncate(velocity.MAX_PAIRS_BYTES + 1)  # sparse: no disk used
    with pytest.raises(ValueError, match="larger than"):
        velocity.read_pairs(big)
    many = tmp_path / "many.csv"
    many.write_text("name,E,nu,Sy,R,rho\n" + "".join(f"p{k},2e11,0.3,1e9,0.01,7800\n"
                                                      for k in range(velocity.MAX_PAIRS + 1)))
    with pytest.raises(ValueError, match=f"at most {velocity.MAX_PAIRS}"):
        velocity.read_pairs(many)
    assert sorted(os.listdir(tmp_path)) == ["big.csv", "dev.csv", "many.csv"]


def test_check_points_bounded(tmp_path):
    r = run(["export", "grid", "--out", str(tmp_path / "g.nc"), "--check-points", "10000000000"],
            timeout=60, limit_memory=True)
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    assert "--check-points" in r.stderr and f"[{grid.MIN_CHECK_POINTS}, {grid.MAX_CHECK_POINTS}]" in r.stderr
    assert os.listdir(tmp_path) == []
    with pytest.raises(ValueError, match=r"^n_check must be a whole number in \[100, 1000000\]"):
        grid.write_grid(tmp_path / "g.nc", n_check=10**10)


def test_materials_bounded(tmp_path):
    with pytest.raises(ValueError, match=f"1 to {c_header.MAX_MATERIALS}"):
        c_header.write_header(tmp_path / "x.h", [(0.005, 0.33)] * (c_header.MAX_MATERIALS + 1))
    with pytest.raises(ValueError, match="1 to"):
        c_header.scene_curves([])
    assert os.listdir(tmp_path) == []


# --- Python errors name Python parameters -------------------------------------------------------

def test_python_errors_name_python_parameters(tmp_path):
    imp = fastrest.Impact(fastrest.Material(2e11, 0.33, 1.12e9, rho=7800), 0.01)
    with pytest.raises(TypeError, match=r"^impact must be a fastrest.Impact"):
        velocity.velocity_table(None, 2, 1e-3)
    with pytest.raises(ValueError, match=r"^V_max = "):
        velocity.velocity_table(imp, 1e9, 1e-3)
    with pytest.raises(TypeError, match=r"^V_max must"):
        velocity.velocity_table(imp, "2", 1e-3)
    with pytest.raises(ValueError, match=r"^tol must"):
        velocity.velocity_table(imp, 2, 0)
    with pytest.raises(ValueError, match=r"^tol must"):
        grid.write_grid(tmp_path / "g.nc", tol=5)
    with pytest.raises(ValueError, match=r"^v_max must"):
        c_header.scene_curves([(0.005, 0.33)], v_max=-1)
    with pytest.raises(TypeError, match=r"^path must be a str"):
        c_header.write_header(5, [(0.005, 0.33)])
    assert os.listdir(tmp_path) == []


def test_load_table_bad_paths(tmp_path):
    with pytest.raises(TypeError, match=r"^path must be a str or os.PathLike"):
        tables.load_table(5)
    with pytest.raises(fastrest.TableFileError, match="NUL"):
        tables.load_table("a\0b")
    loop_a, loop_b = tmp_path / "a.h5", tmp_path / "b.h5"
    loop_a.symlink_to(loop_b)
    loop_b.symlink_to(loop_a)
    with pytest.raises(fastrest.TableFileError) as excinfo:
        tables.load_table(loop_a)
    assert str(loop_a) in str(excinfo.value)
    with pytest.raises(fastrest.TableFileError):
        tables.read(loop_a)


def test_cli_translates_parameter_names(tmp_path, capsys):
    out = str(tmp_path / "x")
    assert cli.main(["export", "velocity", *STEEL, "--V-max", "500", "--out", out]) == 2
    assert "--V-max = 500.0 m/s" in capsys.readouterr().err
    assert cli.main(["export", "c", "--materials", "0.005:0.33", "--v-max", "-1", "--out", out]) == 2
    assert "--v-max must" in capsys.readouterr().err
    assert os.listdir(tmp_path) == []


def test_symbolic_link_at_out_is_written_through_not_replaced(tmp_path):
    """A link at --out is followed, as reading follows it: its target is written, the link stays a
    link (before, the rename replaced the link itself with a regular file)."""
    from fastrest.tables.file import replace_files
    target = tmp_path / "target.txt"
    target.write_bytes(b"old")
    link = tmp_path / "link.txt"
    link.symlink_to(target)
    replace_files({link: b"new"})
    assert link.is_symlink() and target.read_bytes() == b"new"
    dangling = tmp_path / "dangling.txt"
    dangling.symlink_to(tmp_path / "made.txt")
    replace_files({dangling: b"x"})
    assert dangling.is_symlink() and (tmp_path / "made.txt").read_bytes() == b"x"
    nowhere = tmp_path / "nowhere.txt"
    nowhere.symlink_to(tmp_path / "no-dir" / "x.txt")
    with pytest.raises(OSError, match="x.txt"):
        replace_files({nowhere: b"x"})
    assert nowhere.is_symlink() and not (tmp_path / "no-dir").exists()
