"""A corpus of damaged, foreign, hostile and special table files, and a runner that loads each in a
subprocess with a time limit (a crash or hang is a failure, not a test-runner crash).

Run ``python tests/damaged_corpus.py [--base FILE] [--random N]`` to build the corpus from a table
file (default: a small table built on the spot) and print the counts; ``tests/test_table_files.py``
runs it. Every case must be refused with :class:`fastrest.TableFileError` (``--resealed N`` adds
metadata flips with a recomputed digest: refused, or loaded with exactly the base table's numbers).

Categories:

* ``truncated``: the file cut at 0, 1, 100, 511, 512, 513 bytes, at fractions of its length, one
  byte short;
* ``header``, ``metadata``, ``data``: one byte XOR-ed with a random non-zero byte in the 512-byte
  fastrest header, in HDF5 metadata (any byte outside the datasets' raw data) or in raw data;
* ``page``: a 4 KiB page of zeros (the first, the last, random ones); ``appended``: bytes added;
* ``hostile``: well-formed files with a recomputed header digest (and, where the arrays changed,
  a recomputed ``checksum`` attribute), as an attacker would make them: external and soft links,
  groups, named datatypes, virtual datasets, external raw storage (a zero device made in the work directory, another file),
  chunked or compressed data, huge declared shapes, wrong dtypes (float32, float16, int, bool,
  big-endian, complex, strings), NaN or inf in the data, grid attributes with huge counts, deeply
  nested JSON, wrong attribute types, implausible values (e = 0, a loss not 1 - e^2), a foreign HDF5 file, an HDF5 file without a header (a table
  of an older fastrest);
* ``special``: a FIFO, a directory, symbolic links to zero/null/urandom devices made in the work directory and to a FIFO, a dangling
  link, a missing file, an empty file, a sparse file larger than the size limit.
"""
import argparse
import hashlib
import json
import os
import stat
import shutil
import sys
import tempfile
import time
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from corpus_runner import LazyFile, run_corpus, summary  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
USERBLOCK = 512
PAGE = 4096

# --- what an attacker does: rewrite the header (and the arrays' checksum) to match -------------

def reseal(path):
    """Recompute the fastrest header (size, SHA-256 of the bytes after it) of a modified file."""
    Path(path).write_bytes(bytes(_sealed(bytearray(Path(path).read_bytes()))))


def recompute_checksum(path):
    """Set the ``checksum`` attribute to the SHA-256 of the arrays as they now are, then reseal."""
    sys.path.insert(0, str(REPO))
    from fastrest.tables.hdf5 import checksum_arrays

    with h5py.File(path, "r+") as f:
        arrays = {name: f[name][()] for name in f if isinstance(f.get(name, getlink=True), h5py.HardLink)
                  and isinstance(f[name], h5py.Dataset)}
        f.attrs["checksum"] = checksum_arrays(arrays)
    reseal(path)


def replace_dataset(f, name, values, **kwargs):
    """Replace dataset ``name`` by ``values`` (other dtype or storage), keeping its scales and attributes."""
    old = f[name]
    scales = [[s for s in dim.values()] for dim in old.dims]
    attrs = {k: old.attrs[k] for k in ("units", "long_name") if k in old.attrs}
    del f[name]
    new = f.create_dataset(name, data=values, **kwargs)
    for i, dim in enumerate(scales[:new.ndim]):
        for s in dim:
            new.dims[i].attach_scale(s)
    new.attrs.update(attrs)


def raw_ranges(path):
    """(offset, size) of every dataset's raw data in the file."""
    with h5py.File(path, "r") as f:
        out = []
        for name in f:
            off, size = f[name].id.get_offset(), f[name].id.get_storage_size()
            if off is not None and size:
                out.append((off, size))
    return sorted(out)


# --- the corpus --------------------------------------------------------------------------------

def _sealed(d):
    digest = hashlib.sha256(d[USERBLOCK:]).hexdigest()
    text = f"fastrest-table-file 1\nsize {len(d)}\nsha256 {digest}\n".encode()
    d[:USERBLOCK] = text + bytes(USERBLOCK - len(text))
    return d


def _flipped(data, offset, value, seal=False):
    def make():
        d = bytearray(data)
        d[offset] ^= value
        return bytes(_sealed(d) if seal else d)
    return make


def _zeroed(data, page):
    def make():
        d = bytearray(data)
        d[page * PAGE:(page + 1) * PAGE] = bytes(len(d[page * PAGE:(page + 1) * PAGE]))
        return bytes(d)
    return make


def byte_cases(base, n_random=40, n_pages=8, seed=2024, n_resealed=0):
    """(category, name, make) of the byte-level damages of the file ``base``; make() -> bytes.

    ``n_resealed``: also that many metadata flips with a recomputed header digest (category
    ``resealed``): crafted files that reach HDF5's parser (in fastrest's check process, which may
    crash or hang without harm). Such a flip may also hit bytes HDF5 never reads: the file then
    loads with the base's numbers (:func:`resealed_ok`).
    """
    data = Path(base).read_bytes()
    n = len(data)
    rng = np.random.default_rng(seed)
    in_raw = np.zeros(n, dtype=bool)
    for offset, size in raw_ranges(base):
        in_raw[offset:offset + size] = True
    in_raw[:USERBLOCK] = True  # the header is its own category
    meta = np.flatnonzero(~in_raw)
    in_raw[:USERBLOCK] = False
    raw = np.flatnonzero(in_raw)
    out = []
    cuts = sorted({0, 1, 100, 511, 512, 513, 1024, n // 4, n // 2, 3 * n // 4, n - PAGE, n - 1})
    out += [("truncated", f"cut-{c}", (lambda c=c: data[:c])) for c in cuts if 0 <= c < n]
    flips = [("header", x) for x in [0, 21, 27, 40, 100, 200, 511] + list(rng.integers(0, USERBLOCK, 3))]
    flips += [("metadata", x) for x in rng.choice(meta, n_random)]
    flips += [("data", x) for x in rng.choice(raw, max(n_random // 4, 1))]
    out += [(c, f"{c}-{int(x)}", _flipped(data, int(x), int(rng.integers(1, 256)))) for c, x in flips]
    # only pages that zeroing changes: a page already all zeros (e.g. zero-valued data at the end
    # of the file) is no damage, and the unchanged file rightly loads
    changed = [p for p in range((n - 1) // PAGE + 1) if any(data[p * PAGE:(p + 1) * PAGE])]
    last = changed[-1]
    pages = sorted({0, last} | set(int(p) for p in rng.choice(changed, min(n_pages, len(changed)), replace=False)))
    out += [("page", f"page-{p}", _zeroed(data, p)) for p in pages]
    out += [("resealed", f"resealed-{int(x)}", _flipped(data, int(x), int(rng.integers(1, 256)), seal=True))
            for x in rng.choice(meta, n_resealed)]
    out += [("appended", "appended-zeros", lambda: data + bytes(PAGE)),
            ("appended", "appended-copy", lambda: data + data)]
    return out


def resealed_ok(results, base_fingerprint):
    """The resealed cases whose outcome is wrong: anything but refused (TableFileError) or accepted
    with exactly the base table's numbers."""
    return [r for r in results if r[0] == "resealed" and r[2] not in ("refused", f"accepted {base_fingerprint}")]


def device_nodes(workdir):
    """Character devices like /dev/zero, /dev/null, /dev/urandom, made in ``workdir`` (as root; a
    hostile file may point at such a device: the corpus never touches the system's /dev).
    {name: path}; empty where mknod is not permitted."""
    d = Path(workdir) / "dev"
    d.mkdir(exist_ok=True)
    out = {}
    for name, minor in (("zero", 5), ("null", 3), ("urandom", 9)):
        path = d / name
        try:
            if not path.exists():
                os.mknod(path, stat.S_IFCHR | 0o600, os.makedev(1, minor))
        except (PermissionError, AttributeError, OSError):
            continue
        out[name] = path
    return out


def hostile_cases(base, workdir):
    """(category, name, builder) of well-formed hostile files; builder(path) writes one."""
    other = Path(workdir) / "other-data.bin"
    # a zero device of our own (else a regular file of zeros: the case still points outside the file)
    zero = device_nodes(workdir).get("zero")
    if zero is None:
        zero = Path(workdir) / "zeros.bin"
        zero.write_bytes(bytes(1 << 16))
    zero = str(zero)
    other.write_bytes(np.zeros(1 << 16).tobytes())

    def edit(fn, checksum=False):
        def build(path):
            shutil.copyfile(base, path)
            with h5py.File(path, "r+") as f:
                fn(f)
            (recompute_checksum if checksum else reseal)(path)
        return build

    def set_attr(key, value):
        def fn(f):
            f.attrs[key] = value
        return fn

    def set_json(key, change):
        def fn(f):
            d = json.loads(f.attrs[key])
            change(d)
            f.attrs[key] = json.dumps(d)
        return fn

    def compact():
        dcpl = h5py.h5p.create(h5py.h5p.DATASET_CREATE)
        dcpl.set_layout(h5py.h5d.COMPACT)
        return dcpl

    def vds(f):
        layout = h5py.VirtualLayout(shape=(100,), dtype="f8")
        layout[:] = h5py.VirtualSource(str(other), "x", shape=(100,))
        f.create_virtual_dataset("vds", layout)

    def vds_replacing(f):
        shape = f["v1_star_max"].shape
        del f["v1_star_max"]
        layout = h5py.VirtualLayout(shape=shape, dtype="f8")
        layout[:] = h5py.VirtualSource(zero, "x", shape=shape)
        f.create_virtual_dataset("v1_star_max", layout)

    def values(name, fn):
        def change(f):
            v = f[name][()]
            replace_dataset(f, name, fn(v))
        return change

    def nan_at(name, value):
        def change(f):
            v = f[name][()]
            v.flat[v.size // 2] = value
            f[name][...] = v
        return change

    cases = {
        "external-link": edit(lambda f: f.__setitem__("ext", h5py.ExternalLink("/etc/passwd", "/x"))),
        "external-link-to-table": edit(lambda f: f.__setitem__("ext", h5py.ExternalLink(str(base), "/nu"))),
        "soft-link": edit(lambda f: f.__setitem__("soft", h5py.SoftLink("/nu"))),
        "soft-link-loop": edit(lambda f: f.__setitem__("loop", h5py.SoftLink("/loop"))),
        "group": edit(lambda f: f.create_group("g").create_dataset("x", data=np.arange(3.0))),
        "named-datatype": edit(lambda f: f.__setitem__("dt", np.dtype("f8"))),
        "virtual-dataset": edit(vds),
        "virtual-dataset-replacing-data": edit(vds_replacing),
        "external-storage-dev-zero": edit(lambda f: replace_dataset(
            f, "v1_star_max", None, shape=f["v1_star_max"].shape, dtype="f8",
            external=[(zero, 0, 8 * f["v1_star_max"].size)])),
        "external-storage-file": edit(lambda f: replace_dataset(
            f, "v1_star_max", None, shape=f["v1_star_max"].shape, dtype="f8",
            external=[(str(other), 0, 8 * f["v1_star_max"].size)])),
        "extra-dataset-external-storage": edit(lambda f: f.create_dataset(
            "x", shape=(1000,), dtype="f8", external=[(zero, 0, 8000)])),
        "huge-declared-shape-64GiB": edit(lambda f: f.create_dataset("huge", shape=(1 << 33,), dtype="f8")),
        "huge-declared-shape-71TiB": edit(lambda f: f.create_dataset("huge", shape=(1 << 20, 1 << 20, 9), dtype="f8")),
        "huge-chunked": edit(lambda f: f.create_dataset("huge", shape=(1 << 40,), dtype="f8", chunks=(1024,))),
        "chunked-gzip-data": edit(lambda f: replace_dataset(f, "v1_star_max", f["v1_star_max"][()],
                                                           chunks=True, compression="gzip"), checksum=True),
        "compact-layout": edit(lambda f: replace_dataset(f, "v1_star_max", f["v1_star_max"][()], dcpl=compact()),
                               checksum=True),
        "float32-data": edit(values("v1_star_max", lambda v: v.astype(np.float32)), checksum=True),
        "float16-data": edit(values("v1_star_max", lambda v: v.astype(np.float16)), checksum=True),
        "int-data": edit(values("v1_star_max", lambda v: v.astype(np.int64)), checksum=True),
        "bool-data": edit(values("v1_star_max", lambda v: v > 0), checksum=True),
        "big-endian-data": edit(values("v1_star_max", lambda v: v.astype(">f8")), checksum=True),
        "complex-data": edit(values("v1_star_max", lambda v: v.astype(np.complex128)), checksum=True),
        "string-data": edit(values("v1_star_max", lambda v: np.full(v.shape, b"x")), checksum=True),
        "nan-in-data": edit(nan_at("e_jcg_0", np.nan), checksum=True),
        "inf-in-data": edit(nan_at("loss_jcg_0", np.inf), checksum=True),
        "nan-in-axis": edit(nan_at("nu", np.nan), checksum=True),
        "nan-in-v1_star_max": edit(nan_at("v1_star_max", np.nan), checksum=True),
        "inf-in-W_star": edit(nan_at("W_star", np.inf), checksum=True),
        "zero-data": edit(values("e_jcg_0", np.zeros_like), checksum=True),
        "e-above-one-loss-inconsistent": edit(values("e_etsion_0", lambda v: v * 1.01), checksum=True),
        "omega-zero": edit(values("omega_m_star_0", np.zeros_like), checksum=True),
        "grid-n_nu-1e9": edit(set_json("grid", lambda g: g.update(n_nu=10**9))),
        "grid-n_eps_y-1e9": edit(set_json("grid", lambda g: g.update(n_eps_y=10**9))),
        "grid-n_eps_y_energy-1e9": edit(set_json("grid", lambda g: g.update(n_eps_y_energy=10**9))),
        "grid-block-count-1e9": edit(set_json("grid", lambda g: g.update(eps_y_blocks=[[16.0, 10**9]]))),
        "grid-bits-10": edit(set_json("grid", lambda g: g.update(bits_per_octave=10))),
        "grid-not-a-dict": edit(set_attr("grid", json.dumps([1, 2, 3]))),
        "grid-nan": edit(set_json("grid", lambda g: g.update(eps_y_max=float("nan")))),
        "cells-v1_star_top-1e300": edit(set_json("cells", lambda c: c.update(v1_star_top=1e300))),
        "cells-blocks-huge": edit(set_json("cells", lambda c: c.update(blocks=[[0, 10**12, 10**9]]))),
        "cells-count-huge": edit(set_json("cells", lambda c: c.update(count=10**12))),
        "deeply-nested-json": edit(set_attr("grid", "[" * 200000 + "]" * 200000)),
        "json-attributes-missing-key": edit(set_attr("json_attributes", json.dumps(["nowhere"]))),
        "json-attributes-not-a-list": edit(set_attr("json_attributes", json.dumps(12))),
        "format-version-string": edit(set_attr("format_version", "3")),
        "format-version-huge": edit(set_attr("format_version", np.uint64(2**64 - 1))),
        "format-version-old": edit(set_attr("format_version", np.int64(2))),
        "checksum-not-a-string": edit(set_attr("checksum", np.arange(4.0))),
        "checksum-missing": edit(lambda f: f.attrs.__delitem__("checksum")),
        "unloading-models-foreign": edit(set_attr("unloading_models", "jcg,other")),
        "many-attributes": edit(lambda f: [f.attrs.__setitem__(f"a{i}", i) for i in range(100)]),
        "missing-dataset": edit(lambda f: f.__delitem__("e_jcg_0")),
        "renamed-dataset": edit(lambda f: f.move("cell_end", "cell_stop")),
        "missing-dataset-checksum-recomputed": edit(lambda f: f.__delitem__("e_jcg_0"), checksum=True),
        "renamed-dataset-checksum-recomputed": edit(lambda f: f.move("cell_end", "cell_stop"), checksum=True),
        "extra-dataset-checksum-recomputed": edit(lambda f: f.create_dataset("extra", data=np.arange(3.0)),
                                                  checksum=True),
    }

    def foreign(path):
        bio_path = str(path) + ".h5tmp"
        with h5py.File(bio_path, "w", userblock_size=USERBLOCK) as f:
            f["data"] = np.arange(10.0)
        os.replace(bio_path, path)
        reseal(path)

    def unsealed(path):  # an HDF5 table without the header: what fastrest < format 3 wrote
        with h5py.File(path, "w") as g, h5py.File(base, "r") as f:
            for name in f.attrs:
                g.attrs[name] = f.attrs[name]
            for name in f:
                g.create_dataset(name, data=f[name][()])

    cases["foreign-hdf5-with-header"] = foreign
    cases["hdf5-without-header"] = unsealed
    return [("hostile", name, build) for name, build in cases.items()]


def special_cases(workdir):
    """(category, name, path) of special files and paths (created here)."""
    d = Path(workdir) / "special"
    d.mkdir(exist_ok=True)
    out = []
    fifo = d / "fifo.h5"
    if hasattr(os, "mkfifo"):
        os.mkfifo(fifo)
        out.append(("special", "fifo", fifo))
        (d / "link-to-fifo.h5").symlink_to(fifo)
        out.append(("special", "symlink-to-fifo", d / "link-to-fifo.h5"))
    out.append(("special", "directory", d))
    for name, dev in device_nodes(workdir).items():
        link = d / f"link-{name}.h5"
        link.symlink_to(dev)
        out.append(("special", f"symlink-to-{name}-device", link))
    (d / "dangling.h5").symlink_to(d / "nowhere")
    out.append(("special", "dangling-symlink", d / "dangling.h5"))
    out.append(("special", "missing", d / "missing.h5"))
    (d / "empty.h5").write_bytes(b"")
    out.append(("special", "empty", d / "empty.h5"))
    with open(d / "sparse-2GiB.h5", "wb") as fh:
        fh.truncate(2 << 30)
    out.append(("special", "sparse-2GiB", d / "sparse-2GiB.h5"))
    return out


def make_corpus(base, workdir, n_random=40, n_pages=8, seed=2024, lazy=False, n_resealed=0):
    """The corpus in ``workdir``: a list of (category, name, path); with ``lazy`` the byte-level
    cases are :class:`LazyFile` objects instead of paths."""
    workdir = Path(workdir)
    files = workdir / "files"
    files.mkdir(parents=True, exist_ok=True)
    out = []
    for category, name, make in byte_cases(base, n_random, n_pages, seed, n_resealed):
        f = LazyFile(files / f"{name}.h5", make)
        out.append((category, name, f if lazy else f.materialise()))
    for category, name, build in hostile_cases(base, workdir):
        p = files / f"{category}-{name}.h5"
        build(p)
        out.append((category, name, p))
    return out + special_cases(workdir)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--base", help="table file to damage (default: a small table built now)")
    p.add_argument("--random", type=int, default=40, help="random metadata byte flips (data: a quarter)")
    p.add_argument("--pages", type=int, default=8, help="random 4 KiB pages zeroed (plus the first and last)")
    p.add_argument("--resealed", type=int, default=0,
                   help="also N metadata flips with a recomputed digest (refused, or the base's numbers)")
    p.add_argument("--timeout", type=float, default=20.0, help="seconds per file")
    args = p.parse_args(argv)
    sys.path.insert(0, str(REPO))
    with tempfile.TemporaryDirectory() as tmp:
        base = args.base
        if base is None:
            from fastrest import tables
            base = Path(tmp) / "base.h5"
            tables.build(base, dict(eps_y_min=0.004, eps_y_max=0.006, n_eps_y=6, nu_min=0.3, nu_max=0.35,
                                    n_nu=6, bits_per_octave=1, eps_y_blocks=[], n_eps_y_energy=6),
                         progress=False, measure=False)
        t0 = time.perf_counter()
        cases = make_corpus(base, Path(tmp) / "corpus", args.random, args.pages, lazy=True,
                            n_resealed=args.resealed)
        results = run_corpus(cases, args.timeout)
        dt = time.perf_counter() - t0
        from corpus_runner import fingerprint
        from fastrest import tables
        base_fp = fingerprint(tables.read(base))
    counts, total = summary(results)
    for category, c in counts.items():
        print(f"{category:10s} {sum(c.values()):5d} files: " + ", ".join(f"{k} {v}" for k, v in sorted(c.items())))
    print(f"{'total':10s} {sum(total.values()):5d} files: " + ", ".join(f"{k} {v}" for k, v in sorted(total.items()))
          + f"  ({dt:.1f} s)")
    same = sum(r[0] == "resealed" and r[2] == f"accepted {base_fp}" for r in results)
    if args.resealed:
        print(f"resealed accepted with the base table's numbers: {same}")
    wrong = resealed_ok(results, base_fp) + [r for r in results if r[0] != "resealed" and r[2] != "refused"]
    for category, name, outcome in wrong:
        print(f"  WRONG {category}/{name}: {outcome}")
    return 0 if not wrong else 1


if __name__ == "__main__":
    sys.exit(main())
