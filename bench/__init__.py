"""fastrest's benchmark suite.

``python -m bench`` (from the repository root) measures speed against error of every path
(direct solver, curves, tables, the paper's fits), the modes of use (batch sizes, threads, scalar calls,
calls inside ``@njit``, multi-material points, table and curve builds, first use in a fresh process,
peak memory) and checks the performance targets (bench/targets.py). It writes ``RESULTS.md``, ``speed_vs_error.png``,
``readme_table.md`` and ``results.json`` to ``--out-dir`` (default ``bench/``).
``python -m bench --quick`` is a smaller run (under a minute) for tests;
``python -m bench --update-readme`` copies ``bench/readme_table.md`` into README.md.
The errors stated for the default curve and the direct solver are the worst of the run's sample
and the stored search of ``python -m bench.stated_figures`` (bench/STATED_FIGURES.md);
``python -m bench --rerender`` renders the reports again from ``results.json`` with that search
folded in, without timing anything.
"""
