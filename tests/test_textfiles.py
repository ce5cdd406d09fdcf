"""The one reader of users' text files: encodings, line ends, OS errors, and
the record of what was read (provenance)."""
import hashlib

import pytest

from orthocontact.errors import InputError
from orthocontact.textfiles import files_read, read_text, sha256_of


def test_bom_and_line_ends_are_read_as_plain_text(tmp_path):
    p = tmp_path / "a.csv"
    p.write_bytes(b"\xef\xbb\xbfx,y\r\n1,2\r3,4\n")
    assert read_text(p, "a CSV file") == "x,y\n1,2\n3,4\n"


def test_not_utf8_is_one_line_naming_the_file(tmp_path):
    p = tmp_path / "a.csv"
    p.write_bytes(b"x\n\xe9\n")
    with pytest.raises(InputError, match=r"a\.csv: byte 2: not UTF-8"):
        read_text(p, "a CSV file")


def test_missing_and_folder_are_named(tmp_path):
    with pytest.raises(InputError, match="not found; expected a CSV"):
        read_text(tmp_path / "none.csv", "a CSV")
    with pytest.raises(InputError, match="is a folder; expected a CSV"):
        read_text(tmp_path, "a CSV")


def test_files_read_records_the_digest_of_every_read(tmp_path):
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_bytes(b"alpha\n")
    b.write_bytes(b"beta\n")
    read_text(a, "x")   # outside any record
    with files_read() as outer:
        read_text(a, "x")
        with files_read() as inner:
            read_text(b, "x")
    assert set(outer) == {str(a), str(b)} and set(inner) == {str(b)}
    assert outer[str(a)].sha256 == hashlib.sha256(b"alpha\n").hexdigest() == sha256_of(a)
