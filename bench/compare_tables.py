"""Compare the datasets two table files share: ``python -m bench.compare_tables OLD.h5 NEW.h5``.

Prints, per dataset present in both, the largest relative difference (NaNs must coincide), and the
datasets only one file has. Used to show that adding an unloading model left the other models'
values as they were (e.g. ``git show HEAD~1:fastrest/tables/default.h5 > /tmp/old.h5``).
"""
import sys

import h5py
import numpy as np


def datasets(path):
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda n, o: out.__setitem__(n, o[()]) if isinstance(o, h5py.Dataset) else None)
    return out


def main(argv):
    a, b = datasets(argv[1]), datasets(argv[2])
    worst = 0.0
    for name in sorted(set(a) & set(b)):
        x, y = np.asarray(a[name], dtype=float), np.asarray(b[name], dtype=float)
        if x.shape != y.shape or not np.array_equal(np.isnan(x), np.isnan(y)):
            print(f"{name}: shapes or NaNs differ")
            worst = np.inf
            continue
        d = float(np.nanmax(np.abs(x - y) / np.maximum(np.abs(x), 1e-300))) if x.size else 0.0
        worst = max(worst, d)
        print(f"{name:24s} max relative difference {d:.2e}")
    print(f"only in {argv[1]}: {sorted(set(a) - set(b))}")
    print(f"only in {argv[2]}: {sorted(set(b) - set(a))}")
    print(f"worst over the shared datasets: {worst:.2e}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
