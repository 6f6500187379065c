"""The benchmark suite (bench/) runs and writes parseable results. No timing thresholds."""
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
NUMBER = re.compile(r"\d+(\.\d+)?(e[+-]?\d+)?")


def table_rows(text, after_heading):
    """The rows (lists of cells) of the first markdown table after a heading."""
    lines = text[text.index(after_heading):].splitlines()[1:]
    rows, seen = [], False
    for line in lines:
        if line.startswith("|"):
            seen = True
            rows.append([c.strip() for c in line.strip().strip("|").split("|")])
        elif seen:
            break
    assert len(rows) >= 3, f"no table after {after_heading!r}"
    assert set(rows[1][0]) <= set("-:"), "second row must be the header separator"
    return rows[0], rows[2:]


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("bench")
    p = subprocess.run([sys.executable, "-m", "bench", "--quick", "--out-dir", str(out)], cwd=REPO,
                       capture_output=True, text=True, timeout=900)
    assert p.returncode == 0, p.stderr[-3000:]
    return out


@pytest.mark.slow
def test_quick_run_writes_results(quick_run):
    text = (quick_run / "RESULTS.md").read_text()
    for heading in ("# fastrest benchmark results", "## Machine and software", "## Headline",
                    "## 1. Speed against error", "## 2. Modes", "### Batch `Curve.e` against n",
                    "### Threads", "### Scalar calls from Python", "### Inside a user's `@njit` loop",
                    "### Multi-material points", "### Table build and one curve",
                    "### First use in a fresh process", "### Peak memory", "## 3. Targets"):
        assert heading in text, heading
    assert "nproc" in text and "numba" in text and "python -m bench --quick" in text

    header, rows = table_rows(text, "## 1. Speed against error")
    labels = " ".join(r[0] for r in rows)
    for method in ("direct solver", "Curve.e", "default table", "fit (42)-(44)", "fit (45)", "memory copy"):
        assert method in labels, method
    for r in rows:
        assert NUMBER.search(r[1]) and "ns" in r[1], r  # time per evaluation
        assert r[3].endswith("x"), r                        # ratio to the fit

    header, rows = table_rows(text, "## 3. Targets")
    assert len(rows) >= 10
    for r in rows:
        assert r[-1] in ("**met**", "**not met**"), r
        assert NUMBER.search(r[2]), r

    header, rows = table_rows(text, "### Batch `Curve.e` against n")
    assert [r[0] for r in rows][:3] == ["1e+03", "1e+04", "1e+05"]
    assert all("ns" in r[1] for r in rows)


@pytest.mark.slow
def test_quick_run_readme_table_and_plot(quick_run):
    table = (quick_run / "readme_table.md").read_text()
    header, rows = table_rows("start\n" + table, "start")
    assert 3 <= len(rows) <= 12
    assert "time" in " ".join(header)
    assert sum(bool(NUMBER.search(r[1])) for r in rows) == len(rows)
    png = (quick_run / "speed_vs_error.png").read_bytes()
    assert len(png) > 10_000 and png[:8] == b"\x89PNG\r\n\x1a\n"
    results = json.loads((quick_run / "results.json").read_text())
    assert results["quick"] is True


def test_update_readme_replaces_marked_block(tmp_path, monkeypatch):
    monkeypatch.syspath_prepend(str(REPO))
    from bench.report import END, START, update_readme

    out = tmp_path / "bench"
    out.mkdir()
    (out / "readme_table.md").write_text("| a | b |\n|---|---|\n| x | 1 ns |\n")
    readme = tmp_path / "README.md"
    readme.write_text(f"# t\n\nbefore\n\n{START}\nold text\n{END}\n\nafter\n")
    update_readme(readme, out)
    new = readme.read_text()
    assert "old text" not in new and "| x | 1 ns |" in new
    assert "before" in new and "after" in new
    assert "[bench/RESULTS.md](bench/RESULTS.md)" in new and "bench/speed_vs_error.png" in new
    assert new.count(START) == 1 and new.count(END) == 1
    update_readme(readme, out)  # idempotent
    assert readme.read_text() == new

    (out / "results.json").write_text(json.dumps({"quick": True}))
    with pytest.raises(ValueError, match="quick"):
        update_readme(readme, out)
    update_readme(readme, out, force=True)
