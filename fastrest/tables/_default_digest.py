"""The SHA-256 digest of the shipped table's bytes after its header (fastrest/tables/default.h5).

Written by `fastrest build --default` (do not edit): fastrest parses the shipped table in-process
only while its digest is this one; any other table file is parsed in a check process first
(fastrest.tables.probe)."""
#: Hex digest (docs/table-format.md, section 1.0).
SHA256 = '9bb536b4f4f6307dae78adc0778beda2f8a066be454452f5ba7b818e66149147'
