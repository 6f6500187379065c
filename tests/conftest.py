"""Shared pytest configuration: bounded hypothesis runs, and the tests of stored values.

Hypothesis runs at most ``max_examples`` examples per property test and has no deadline, because
the first call of a numba kernel compiles it (or loads it from the cache), which can take seconds.
Select a longer run with ``HYPOTHESIS_PROFILE=fastrest-long pytest ...``.

The tests listed in :data:`STORED_VALUES` carry the ``stored_values`` marker: CI runs them a
second time under other libm and SIMD code paths (``.ci/run``).
"""
import os
from pathlib import Path

import pytest
from hypothesis import settings

settings.register_profile("fastrest", max_examples=50, deadline=None)
settings.register_profile("fastrest-long", max_examples=1000, deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "fastrest"))

ROOT = Path(__file__).resolve().parents[1]

#: Tests that compare numbers which went through libm (exp, log, pow), a search, a quadrature or an
#: iteration with values stored elsewhere: the shipped table, its measured errors and the figures
#: stated from them, published data (the paper's tables, tmdsimpy's forces), MODEL.md's check values,
#: 40-digit references and the printed results of docstring examples. Another CPU or libm moves such
#: numbers by a few ulp per libm call (more after an iteration or a search): these tests must allow
#: for that. ``.ci/run`` runs them (``-m stored_values``, without the slow ones) a second time with
#: glibc's non-FMA code paths, NumPy's baseline SIMD, Numba's generic CPU and OpenBLAS's Prescott
#: kernels, which on an AVX2 machine move ~1 % of the shipped table's values by up to 1,024 ulp.
#: Entries are test files or test functions (node ids without parameters).
STORED_VALUES = (
    "tests/test_tables.py::test_default_table_matches_direct",
    "tests/test_tables.py::test_default_table_hard_cases_match_direct",
    "tests/test_tables.py::test_default_table_edges_and_corners_match_direct",
    "tests/test_tables.py::test_shipped_default_table_matches_generator",
    "tests/test_tables.py::test_measured_error_comparison_tolerates_rounding_only",
    "tests/test_tables.py::test_default_table_metadata",
    "tests/test_accuracy_bounds.py",
    "tests/test_table_w_star.py::test_loading_energy_matches_quadrature_over_the_domain",
    "tests/test_table_w_star.py::test_w_star_matches_40_digit_reference",
    "tests/test_direct.py",
    "tests/test_models.py",
    "tests/test_loading.py",
    "tests/test_unloading.py",
    "tests/test_curve.py::test_hertz_range_cells_reproduce_closed_form_to_a_few_ulp",
    "tests/test_force_law.py::test_brake_matches_tmdsimpy_reference_data",
    "tests/test_hardening_contact.py::test_hardening_matches_tmdsimpy_reference_data",
    "tests/test_export_grid.py::test_elastic_range_is_gridded",
    "tests/test_docstrings.py::test_examples_run",
    "tests/test_tables_docs.py::test_examples_run",
    "tests/test_stated_figures.py",
)


def _listed(nodeid, entry):
    return nodeid == entry or nodeid.startswith(entry + "[") or nodeid.startswith(entry + "::")


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    """Mark the tests of STORED_VALUES; when ``-m`` selects them, every entry must still name a
    file and, where that file was collected, a test (a renamed test must not drop out silently)."""
    matched = set()
    collected_files = set()
    for item in items:
        collected_files.add(item.nodeid.split("::", 1)[0])
        for entry in STORED_VALUES:
            if _listed(item.nodeid, entry):
                item.add_marker(pytest.mark.stored_values)
                matched.add(entry)
    if "stored_values" not in (config.option.markexpr or ""):
        return
    for entry in STORED_VALUES:
        path = entry.split("::", 1)[0]
        if not (ROOT / path).is_file():
            raise pytest.UsageError(f"tests/conftest.py STORED_VALUES: {entry} names no test file")
        if path in collected_files and entry not in matched:
            raise pytest.UsageError(f"tests/conftest.py STORED_VALUES: {entry} names no test")
