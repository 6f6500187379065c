"""The SHA-256 digest of the shipped table's bytes after its header (fastrest/tables/default.h5).

Written by `fastrest build --default` (do not edit): fastrest parses the shipped table in-process
only while its digest is this one; any other table file is parsed in a check process first
(fastrest.tables.probe)."""
#: Hex digest (docs/table-format.md, section 1.0).
SHA256 = 'cd982e42481d5ff861b9869053b5c332fa01e797112d783716d1ecaccb2ab459'
