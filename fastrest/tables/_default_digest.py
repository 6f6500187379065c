"""The SHA-256 digest of the shipped table's bytes after its header (fastrest/tables/default.h5).

Written by `fastrest build --default` (do not edit): fastrest parses the shipped table in-process
only while its digest is this one; any other table file is parsed in a check process first
(fastrest.tables.probe)."""
#: Hex digest (docs/table-format.md, section 1.0).
SHA256 = '4c78fd46468e9252572639e7288fa9cba5609c267c1e2a9bcd9bb30596c7a41b'
