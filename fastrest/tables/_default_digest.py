"""The SHA-256 digest of the shipped table's bytes after its header (fastrest/tables/default.h5).

Written by `fastrest build --default` (do not edit): fastrest parses the shipped table in-process
only while its digest is this one; any other table file is parsed in a check process first
(fastrest.tables.probe)."""
#: Hex digest (docs/table-format.md, section 1.0).
SHA256 = 'c022e5a132cb8160af79e7632d7a9e605d51e5e8adc5a493abb8cf96eec0c0cf'
