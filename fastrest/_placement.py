"""Node placement shared by the exported grids (:mod:`fastrest.tables._rectilinear`, :mod:`fastrest.export`):
bisection until linear interpolation meets a tolerance."""
import numpy as np

from .energy import V_SWITCH

__all__ = ["JUMP_GAP", "JUMP", "scaled_error", "interior", "place_rows"]

#: The model jumps at V1* = 1.9^1.25 (w_m* = 1.9: the Jackson-Green loading law does not meet
#: Hertz's there, JGM eqs 8-10), so rows stand on both sides of it: at 1.9^1.25 (Hertz side) and
#: at 1.9^1.25 (1 + JUMP_GAP) (JG side); linear interpolation is not checked across that gap.
JUMP_GAP = 1e-9
JUMP = (V_SWITCH, V_SWITCH * (1.0 + JUMP_GAP))


def scaled_error(got, ref):
    """|got - ref| / max(|ref|, 1): absolute for e and 1 - e^2, relative for w_m* > 1."""
    return np.abs(got - ref) / np.maximum(np.abs(ref), 1.0)


def interior(a, b, k):
    t = np.arange(1, k + 1) / (k + 1)
    return a[:, None] + (b - a)[:, None] * t[None, :]


def place_rows(value_fn, knots, tol, max_rows=200000, log=False, skip=JUMP[0], what="rows"):
    """Rows (sorted) refining ``knots`` by bisection until linear interpolation of ``value_fn``
    (x -> (nq, n) array) is within tol at 7 points inside every interval (if ``log``: points and
    midpoints uniform in ln x, interpolation checked both linear in x and linear in ln x), except
    the interval starting at ``skip`` (the model's jump)."""
    x = np.unique(np.asarray(knots, dtype=np.float64))
    to_t, from_t = (np.log, np.exp) if log else ((lambda a: a), (lambda a: a))
    while True:
        a, b = x[:-1], x[1:]
        ta, tb = to_t(a), to_t(b)
        t = from_t(interior(ta, tb, 7))
        fa, fb, ft = value_fn(a), value_fn(b), value_fn(t.ravel()).reshape(-1, *t.shape)
        err = np.full(a.size, -1.0)
        weights = [(t - a[:, None]) / (b - a)[:, None]]
        if log:  # also linear in ln x
            weights.append(np.broadcast_to(np.arange(1, 8) / 8.0, t.shape))
        for w in weights:
            lin = fa[:, :, None] * (1 - w) + fb[:, :, None] * w
            e = scaled_error(lin, ft)
            err = np.maximum(err, np.max(np.where(np.isnan(e), -1.0, e), axis=(0, 2)))
        bad = (err > tol) & (a != skip)
        if not bad.any():
            return x
        if np.any(bad & (b - a <= 1e-12 * np.abs(b))):
            k = int(np.flatnonzero(bad & (b - a <= 1e-12 * np.abs(b)))[0])
            raise ValueError(f"tol = {tol!r} cannot be met: the function jumps near {a[k]!r}")
        if x.size + np.count_nonzero(bad) > max_rows:
            raise ValueError(f"tol = {tol!r} cannot be met with at most {max_rows} {what}; "
                             "give a larger tol")
        x = np.unique(np.concatenate([x, from_t(0.5 * (ta[bad] + tb[bad]))]))
