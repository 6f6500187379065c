"""The SHA-256 digest of the shipped table's bytes after its header (fastrest/tables/default.h5).

Written by `fastrest build --default` (do not edit): fastrest parses the shipped table in-process
only while its digest is this one; any other table file is parsed in a check process first
(fastrest.tables.probe)."""
#: Hex digest (docs/table-format.md, section 1.0).
SHA256 = '732551d41a9dae18dfb637d2d4f9ad2aa5c7cc678f3237ee1da6f65aa242b873'
