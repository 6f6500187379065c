"""The release files tell one story: fastrest/_version.py, CITATION.cff and CHANGELOG.md name the
same version and date, the changelog keeps an empty-headed ``[Unreleased]`` section above the
newest release, and every release heading has a date (.ci/wheel checks the same on the built wheel)."""
import re
from pathlib import Path

import fastrest

REPO = Path(__file__).resolve().parents[1]


def _changelog_releases():
    text = (REPO / "CHANGELOG.md").read_text()
    return re.findall(r"^## \[([^\]]+)\](?: - (\S+))?\s*$", text, re.M)


def test_version_citation_and_changelog_agree():
    cff = (REPO / "CITATION.cff").read_text()
    version = re.search(r"^version:\s*\"?([^\"\s]+)\"?\s*$", cff, re.M)[1]
    date = re.search(r"^date-released:\s*\"?([\d-]+)\"?\s*$", cff, re.M)[1]
    releases = _changelog_releases()
    assert releases[0] == ("Unreleased", "")
    assert releases[1] == (fastrest.__version__, date) and version == fastrest.__version__, (releases[:2], version)


def test_every_release_has_a_date_and_none_is_proposed():
    for name, date in _changelog_releases()[1:]:
        assert re.fullmatch(r"\d+\.\d+\.\d+", name) and re.fullmatch(r"\d{4}-\d{2}-\d{2}", date), (name, date)
    text = (REPO / "CHANGELOG.md").read_text().lower()
    for phrase in ("proposed as", "never tagged", "earlier checkout"):
        assert phrase not in text, phrase
