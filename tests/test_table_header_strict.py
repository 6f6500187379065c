"""The table file header is read exactly as docs/table-format.md writes it: N without leading
zeros, D in lowercase hex; anything else is a damaged header."""
import hashlib

import pytest

from fastrest.tables.file import USERBLOCK, TableFileError, header, read_verified

BODY = b"\x89HDF" + bytes(range(256)) * 2


def write(tmp_path, size_text, digest):
    text = b"fastrest-table-file 1\n" + f"size {size_text}\nsha256 {digest}\n".encode("ascii")
    path = tmp_path / "t.h5"
    path.write_bytes(text.ljust(USERBLOCK, b"\0") + BODY)
    return path


def test_the_written_header_reads_back(tmp_path):
    digest = hashlib.sha256(BODY).hexdigest()
    path = tmp_path / "t.h5"
    path.write_bytes(header(digest, USERBLOCK + len(BODY)) + BODY)
    assert read_verified(path)[1] == digest
    assert read_verified(write(tmp_path, str(USERBLOCK + len(BODY)), digest))[1] == digest


@pytest.mark.parametrize("size_text", ["0{n}", "00{n}", "+{n}", " {n}", "{n}.0"])
def test_size_with_leading_zero_or_sign_is_a_damaged_header(tmp_path, size_text):
    path = write(tmp_path, size_text.format(n=USERBLOCK + len(BODY)), hashlib.sha256(BODY).hexdigest())
    with pytest.raises(TableFileError, match="damaged fastrest header"):
        read_verified(path)


def test_uppercase_digest_is_a_damaged_header(tmp_path):
    path = write(tmp_path, str(USERBLOCK + len(BODY)), hashlib.sha256(BODY).hexdigest().upper())
    with pytest.raises(TableFileError, match="damaged fastrest header"):
        read_verified(path)
