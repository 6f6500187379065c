"""docs/table-format.md is complete: a NumPy evaluator written only from that page (no fastrest
import in the evaluator; hashlib checks the header, h5py reads the arrays) verifies the shipped
table and reproduces fastrest.e_star, loss_star and omega_m_star, including where fastrest refuses
(w_m* > 425). The reference is fastrest's own evaluation of the same file."""
import hashlib
import json
import math
import shutil

import h5py
import numpy as np
import pytest

import fastrest
from fastrest.jit import e_table
from fastrest.tables import default_table_path


def header_ok(data):
    """Section 1.0: the 512-byte header's size and SHA-256 digest of the bytes after it."""
    magic = b"fastrest-table-file 1\n"
    if len(data) < 512 or not data.startswith(magic):
        return False
    text, _, pad = data[:512].partition(b"\0")
    if pad.strip(b"\0"):
        return False
    lines = text[len(magic):].split(b"\n")
    if len(lines) != 3 or lines[2] or not lines[0].startswith(b"size ") or not lines[1].startswith(b"sha256 "):
        return False
    size, digest = lines[0][5:], lines[1][7:].decode("ascii")
    return (size.isdigit() and int(size) == len(data) and len(digest) == 64
            and hashlib.sha256(data[512:]).hexdigest() == digest)


class DocTable:
    """Evaluator of docs/table-format.md, sections 1-2."""

    def __init__(self, path):
        with open(path, "rb") as fh:
            self.bytes = fh.read()
        with h5py.File(path, "r") as f:
            assert f.attrs["format"] == "fastrest-table" and int(f.attrs["format_version"]) == 3
            self.arrays = {k: f[k][()] for k in f}
            a = {k: f.attrs[k] for k in f.attrs}
        for k in json.loads(a["json_attributes"]):
            a[k] = json.loads(a[k])
        self.attrs = a
        self.grid, self.cells = a["grid"], a["cells"]
        self.models = a["unloading_models"].split(",")
        self.quantities = ["omega_m_star"] + [f"{q}_{m}" for m in self.models for q in ("e", "loss")]
        self.v_safe = float(np.min(self.arrays["v1_star_max"]))

    def checksum(self):
        h = hashlib.sha256()
        for name in sorted(self.arrays):
            x = np.ascontiguousarray(self.arrays[name])
            x = x.astype(x.dtype.newbyteorder("<"))
            h.update(json.dumps([name, x.dtype.str, list(x.shape)]).encode() + b"\n")
            h.update(x.tobytes(order="C"))
        return h.hexdigest()

    @staticmethod
    def _weights(x, x0, inv_h, n):
        t = (x - x0) * inv_h
        first = min(max(math.floor(t) - 2, 0), n - 6)
        tau = t - first
        w = np.ones(6)
        for a in range(6):
            for b in range(6):
                if b != a:
                    w[a] *= (tau - b) / (a - b)
        return first, w

    def _poly(self, y, u):
        nodes = self.arrays["node"]
        L = np.ones(6)
        for j in range(6):
            for k in range(6):
                if k != j:
                    L[j] *= (u - nodes[k]) / (nodes[j] - nodes[k])
        return y @ L

    def _on_block(self, q, b, k, u, eps_y, nu):
        """Q_b(k) of section 2.3: stored cell k of block b on block b's material grid."""
        g = self.grid
        n = self.cells["blocks"][b][2]
        rate = g["c_eps_y_map_rate"]
        C = lambda x: 1.295 * math.exp(0.736 * x)  # noqa: E731
        xi = (lambda s: math.expm1(rate * s) / rate) if rate > 0 else (lambda s: s)
        xi0, xi1 = xi(C(g["nu_min"]) * g["eps_y_min"]), xi(C(g["nu_max"]) * g["eps_y_max"])
        fi, we = self._weights(xi(C(nu) * eps_y), xi0, (n - 1) / (xi1 - xi0), n)
        fj, wn = self._weights(nu, g["nu_min"], (g["n_nu"] - 1) / (g["nu_max"] - g["nu_min"]), g["n_nu"])
        data = self.arrays[f"{self.quantities[q]}_{b}"]
        return sum(we[a] * wn[a2] * self._poly(data[fi + a, fj + a2, k], u) for a in range(6) for a2 in range(6))

    def _tabled(self, q, v, eps_y, nu):
        """Sections 2.1-2.4."""
        cell, end = self.arrays["cell"], self.arrays["cell_end"]
        c = int(np.searchsorted(cell, v, side="right")) - 1
        center, half = 0.5 * (cell[c] + end[c]), 0.5 * (end[c] - cell[c])
        u = (v - center) * (1.0 / half)
        blocks = self.cells["blocks"]
        b = next(b for b, (c0, c1, _) in enumerate(blocks) if c0 <= c < c1)
        r_own = self._on_block(q, b, c - blocks[b][0], u, eps_y, nu)
        if b == 0 or c != blocks[b][0]:
            return r_own
        r_prev = self._on_block(q, b - 1, blocks[b - 1][1] - blocks[b - 1][0], u, eps_y, nu)
        t = min(max((u + 1.0) / 2.0, 0.0), 1.0)
        return r_prev + t * t * (3.0 - 2.0 * t) * (r_own - r_prev)

    def value(self, q, v, eps_y, nu):
        g = self.grid
        if not (g["eps_y_min"] <= eps_y <= g["eps_y_max"] and g["nu_min"] <= nu <= g["nu_max"] and v >= 0):
            return math.nan
        vs = 1.9 ** 1.25
        if v <= vs:  # 2.0
            model = self.models[(q - 1) // 2] if q else None
            if q == 0:
                return v ** 0.8
            if v <= 1.0:
                return 1.0 if q % 2 else 0.0
            r = -1.02 * math.expm1(-0.54 * math.log1p(math.expm1(0.8 * math.log(v)) / 6.9)) if model == "jcg" else 0.0
            return math.sqrt(1.0 - r) if q % 2 else r
        if v > self.cells["v1_star_top"]:
            return math.nan
        if v > self.v_safe:  # 2.5
            w_limit = 425.0 * (1.0 + 1e-9)
            if eps_y > 0.0102:
                C = 1.295 * math.exp(0.736 * nu)
                a_lim = (2.0 / (math.pi * C * eps_y)) ** 2
                B = 0.14 * math.exp(23.0 * eps_y)
                w_ar = a_lim if a_lim <= 1.9 else math.exp((math.log(a_lim) + B * math.log(1.9)) / (1.0 + B))
                w_limit = min(w_limit, w_ar * (1.0 + 1e-9))
            if not self._tabled(0, v, eps_y, nu) <= w_limit:
                return math.nan
        return self._tabled(q, v, eps_y, nu)


@pytest.fixture(scope="module")
def doc():
    return DocTable(default_table_path())


def test_checksum_rule(doc):
    assert doc.checksum() == doc.attrs["checksum"]


def test_header_rule(doc, tmp_path):
    data = doc.bytes
    assert header_ok(data) and data[512:520] == b"\x89HDF\r\n\x1a\n"
    # the rule refuses what fastrest refuses: one flipped bit after the header, a truncated file
    for name, bad in (("flip", data[:4096] + bytes([data[4096] ^ 1]) + data[4097:]), ("cut", data[:-1])):
        path = tmp_path / f"{name}.h5"
        path.write_bytes(bad)
        assert not header_ok(bad)
        with pytest.raises(fastrest.TableFileError):
            fastrest.tables.read(path)
    shutil.copyfile(default_table_path(), tmp_path / "ok.h5")
    fastrest.tables.read(tmp_path / "ok.h5")


def test_stored_layout(doc):
    """Sections 1.4 and the axes table: the extra stored cell of every block but the last."""
    cell, blocks = doc.arrays["cell"], doc.cells["blocks"]
    np.testing.assert_array_equal(doc.arrays["node"][[0, -1]], [-1.0, 1.0])
    for b, (c0, c1, n) in enumerate(blocks):
        stop = c1 + (b < len(blocks) - 1)
        np.testing.assert_array_equal(doc.arrays[f"cell_{b}"], cell[c0:stop])
        assert doc.arrays[f"e_brake_{b}"].shape == (n, doc.grid["n_nu"], stop - c0, 6)


def _points(n, seed):
    rng = np.random.default_rng(seed)
    e = rng.uniform(0.0005, 0.01, n)
    nu = rng.uniform(0.2, 0.45, n)
    lim = np.array([fastrest.limit(a, b).v1_star for a, b in zip(e, nu)])
    v = np.exp(rng.uniform(np.log(0.05), np.log(lim * (1 - 1e-6))))
    t = fastrest.load_table()
    edges = t.cell_edges
    cells = np.concatenate([edges[:, 0], [1.0, 1.9 ** 1.25, 8.0]])
    # inside the blended first cells of the blocks b > 0, and just below each material's limit
    first = [edges[c0] for c0, _ in t.block_cells[1:]]
    blend = np.concatenate([lo + (hi - lo) * rng.uniform(0, 1, 40) for lo, hi in first])
    extra = np.concatenate([cells, np.nextafter(cells, 0), np.nextafter(cells, 2 * cells), blend])
    k = rng.integers(0, n, extra.size)
    ok = extra <= lim[k] * (1 - 1e-6)
    near = lim[:60] * (1 - 10.0 ** rng.uniform(-8, -5, 60))
    return (np.concatenate([v, extra[ok], near]), np.concatenate([e, e[k][ok], e[:60]]),
            np.concatenate([nu, nu[k][ok], nu[:60]]))


@pytest.mark.slow
def test_doc_evaluator_matches_fastrest(doc):
    v, e, n = _points(700, 12)
    assert doc.quantities == ["omega_m_star", "e_jcg", "loss_jcg", "e_etsion", "loss_etsion", "e_brake", "loss_brake"]
    for q, name in enumerate(doc.quantities):
        kind, _, model = name.partition("_")
        if name == "omega_m_star":
            ref = fastrest.omega_m_star(v, e, n)
        else:
            ref = (fastrest.e_star if kind == "e" else fastrest.loss_star)(v, e, n, model)
        got = np.array([doc.value(q, *p) for p in zip(v, e, n)])
        scale = np.maximum(np.abs(ref), 1.0) if kind != "e" else np.abs(ref)
        err = np.abs(got - ref) / scale
        print(f"{name}: {v.size} points, max difference {err.max():.2g}")
        assert err.max() <= 1e-14, (name, err.max(), v[np.argmax(err)])


def test_doc_evaluator_refuses_where_fastrest_does(doc):
    """NaN exactly where fastrest's jitted e_table gives NaN (and e_star raises), around the limit."""
    data = fastrest.load_table().data
    rng = np.random.default_rng(5)
    for e, nu in zip(rng.uniform(0.0005, 0.01, 40), rng.uniform(0.2, 0.45, 40)):
        lim = fastrest.limit(e, nu).v1_star
        for v in lim * np.array([1 - 1e-9, 1 + 1e-7, 1.001, 1.05]):
            ref = e_table(data, v, e, nu, 0)
            got = doc.value(1, v, e, nu)
            assert math.isnan(ref) == math.isnan(got), (v, e, nu, ref, got)
            if math.isnan(ref):
                with pytest.raises(ValueError):
                    fastrest.e_star(v, e, nu)
            else:
                assert abs(got - ref) <= 1e-14 * ref
    e, nu = 0.004, 0.3
    lim = fastrest.limit(e, nu).v1_star
    assert math.isnan(doc.value(1, lim * 1.001, e, nu))
    assert math.isnan(doc.value(1, 2.0, 0.02, 0.3))  # outside the table's eps_y
