"""docs/table-format.md is complete: a NumPy evaluator written only from that page (no fastrest
import in the evaluator; h5py reads the file) reproduces fastrest.e_star, loss_star and
omega_m_star of the shipped table. The reference is fastrest's own evaluation of the same file."""
import hashlib
import json
import math

import h5py
import numpy as np
import pytest

import fastrest
from fastrest.tables import default_table_path


class DocTable:
    """Evaluator of docs/table-format.md, sections 1-2."""

    def __init__(self, path):
        with h5py.File(path, "r") as f:
            assert f.attrs["format"] == "fastrest-table" and int(f.attrs["format_version"]) == 2
            self.arrays = {k: f[k][()] for k in f}
            a = {k: f.attrs[k] for k in f.attrs}
        for k in json.loads(a["json_attributes"]):
            a[k] = json.loads(a[k])
        self.attrs = a
        self.grid, self.cells = a["grid"], a["cells"]
        self.models = a["unloading_models"].split(",")
        self.quantities = ["omega_m_star"] + [f"{q}_{m}" for m in self.models for q in ("e", "loss")]

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

    def _tabled(self, q, v, eps_y, nu):
        g, cl = self.grid, self.cells
        if v > cl["v1_star_top"]:
            return math.nan
        cell, end = self.arrays["cell"], self.arrays["cell_end"]
        c = int(np.searchsorted(cell, v, side="right")) - 1
        center, half = 0.5 * (cell[c] + end[c]), 0.5 * (end[c] - cell[c])
        u = (v - center) * (1.0 / half)
        b, (c0, c1, n) = next((b, blk) for b, blk in enumerate(cl["blocks"]) if blk[0] <= c < blk[1])
        k = g["c_eps_y_map_rate"]
        C = lambda x: 1.295 * math.exp(0.736 * x)  # noqa: E731
        xi = (lambda s: math.expm1(k * s) / k) if k > 0 else (lambda s: s)
        xi0, xi1 = xi(C(g["nu_min"]) * g["eps_y_min"]), xi(C(g["nu_max"]) * g["eps_y_max"])
        fi, we = self._weights(xi(C(nu) * eps_y), xi0, (n - 1) / (xi1 - xi0), n)
        fj, wn = self._weights(nu, g["nu_min"], (g["n_nu"] - 1) / (g["nu_max"] - g["nu_min"]), g["n_nu"])
        data = self.arrays[f"{self.quantities[q]}_{b}"]
        total = 0.0
        for a in range(6):
            for bb in range(6):
                total += we[a] * wn[bb] * self._poly(data[fi + a, fj + bb, c - c0], u)
        return total

    def value(self, q, v, eps_y, nu):
        g = self.grid
        if not (g["eps_y_min"] <= eps_y <= g["eps_y_max"] and g["nu_min"] <= nu <= g["nu_max"] and v >= 0):
            return math.nan
        vs = 1.9 ** 1.25
        if v <= vs:
            model = self.models[(q - 1) // 2] if q else None
            w = v ** 0.8
            if q == 0:
                return w
            if v <= 1.0:
                return 1.0 if q % 2 else 0.0
            r = -1.02 * math.expm1(-0.54 * math.log1p(math.expm1(0.8 * math.log(v)) / 6.9)) if model == "jcg" else 0.0
            return math.sqrt(1.0 - r) if q % 2 else r
        if v > np.min(self.arrays["v1_star_max"]):
            if not self._tabled(0, v, eps_y, nu) <= 425.0 * (1.0 + 1e-9):
                return math.nan
        return self._tabled(q, v, eps_y, nu)


@pytest.fixture(scope="module")
def doc():
    return DocTable(default_table_path())


def test_checksum_rule(doc):
    assert doc.checksum() == doc.attrs["checksum"]


def _points(n, seed):
    rng = np.random.default_rng(seed)
    e = rng.uniform(0.0005, 0.01, n)
    nu = rng.uniform(0.2, 0.45, n)
    lim = np.array([fastrest.limits.v1_star_limit(a, b) for a, b in zip(e, nu)])
    v = np.exp(rng.uniform(np.log(0.05), np.log(lim * (1 - 1e-6))))
    t = fastrest.load_table()
    cells = np.concatenate([t.gen["edges"][:, 0], [1.0, 1.9 ** 1.25, 8.0]])
    extra = np.concatenate([cells, np.nextafter(cells, 0), np.nextafter(cells, 2 * cells)])
    k = rng.integers(0, n, extra.size)
    ok = extra <= lim[k] * (1 - 1e-6)
    return (np.concatenate([v, extra[ok]]), np.concatenate([e, e[k][ok]]), np.concatenate([nu, nu[k][ok]]))


def test_doc_evaluator_matches_fastrest(doc):
    v, e, n = _points(700, 12)
    for q, name in enumerate(doc.quantities):
        kind, _, model = name.partition("_")
        if name == "omega_m_star":
            ref = fastrest.omega_m_star(v, e, n)
        else:
            ref = (fastrest.e_star if kind == "e" else fastrest.loss_star)(v, e, n, model)
        got = np.array([doc.value(q, *p) for p in zip(v, e, n)])
        scale = np.maximum(np.abs(ref), 1.0) if kind != "e" else np.abs(ref)
        err = np.abs(got - ref) / scale
        print(name, err.max())
        assert err.max() <= 1e-14, (name, err.max(), v[np.argmax(err)])


def test_doc_evaluator_refuses_past_the_limit(doc):
    e, nu = 0.004, 0.3
    lim = fastrest.limits.v1_star_limit(e, nu)
    for v in (lim * 1.001, lim * 1.05):
        with pytest.raises(ValueError):
            fastrest.e_star(v, e, nu)
        assert math.isnan(doc.value(1, v, e, nu))
    assert math.isnan(doc.value(1, 2.0, 0.02, 0.3))  # outside the table's eps_y
