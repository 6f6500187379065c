"""Temporary files left beside a target by a killed writer are removed by the next write to it:
only old regular files of exactly the writer's naming pattern, never a link's target."""
import os
import time

import pytest

from fastrest.tables import file as tfile
from fastrest.tables.temp_files import STALE_TEMP_SECONDS, remove_stale_temps

OLD = time.time() - 2 * STALE_TEMP_SECONDS


def plant(path, data=b"partial", mtime=OLD):
    path.write_bytes(data)
    os.utime(path, (mtime, mtime))
    return path


@pytest.fixture
def scene(tmp_path):
    """A directory with a stale temp file of t.h5 and files that must survive."""
    d = tmp_path / "out"
    d.mkdir()
    outside = plant(tmp_path / "precious.h5", b"keep me")
    s = {"stale": plant(d / ".t.h5.ab_12xyz.tmp"),
         "young": plant(d / ".t.h5.young123.tmp", mtime=time.time()),     # a concurrent writer's
         "other target": plant(d / ".u.h5.ab_12xyz.tmp"),
         "uppercase": plant(d / ".t.h5.AB_12XYZ.tmp"),
         "seven chars": plant(d / ".t.h5.ab12xyz.tmp"),
         "suffix": plant(d / ".t.h5.ab_12xyz.tmp.keep"),
         "no dot": plant(d / "t.h5.ab_12xyz.tmp"),
         "outside": outside}
    link = d / ".t.h5.link0000.tmp"
    link.symlink_to(outside)
    os.utime(link, (OLD, OLD), follow_symlinks=False)
    s["link"] = link
    directory = d / ".t.h5.dir00000.tmp"
    directory.mkdir()
    os.utime(directory, (OLD, OLD))
    s["directory"] = directory
    return d, s


def survivors_intact(s):
    for key, p in s.items():
        if key != "stale":
            assert os.path.lexists(p), key
    assert s["outside"].read_bytes() == b"keep me"
    assert s["link"].is_symlink() and s["directory"].is_dir()


def test_replace_files_removes_only_stale_temps_of_its_target(scene):
    d, s = scene
    tfile.replace_files({d / "t.h5": b"new content"})
    assert (d / "t.h5").read_bytes() == b"new content"
    assert not os.path.lexists(s["stale"])
    survivors_intact(s)


def test_write_atomic_of_a_table_file_cleans_too(scene):
    d, s = scene
    digest = tfile.write_atomic(d / "t.h5", bytearray(tfile.USERBLOCK + 16))
    assert tfile.read_verified(d / "t.h5")[1] == digest
    assert not os.path.lexists(s["stale"])
    survivors_intact(s)


def test_remove_stale_temps_reports_what_it_removed(scene):
    d, s = scene
    assert remove_stale_temps(d / "t.h5") == [str(s["stale"])]
    assert remove_stale_temps(d / "t.h5") == []
    survivors_intact(s)
    # the young one goes once it is old enough
    assert remove_stale_temps(d / "t.h5", older_than=-1.0) == [str(s["young"])]


def test_missing_directory_is_not_an_error(tmp_path):
    assert remove_stale_temps(tmp_path / "no" / "such" / "t.h5") == []
