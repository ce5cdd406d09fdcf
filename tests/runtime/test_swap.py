"""A folder's content replaced in one step (orthocontact.runtime.swap): two
folders exchanged atomically, a folder mirrored by hard links, the merge of
one folder's files into another by moving or linking."""
import os

import pytest

from orthocontact.runtime.swap import can_exchange, exchange, link_tree, merge_into, prune_empty


def make_tree(folder, files: dict) -> None:
    """Writes `files` (path under `folder` -> text) with their folders; an
    empty `files` makes `folder` alone: tree()'s inverse for plain files."""
    folder.mkdir(parents=True, exist_ok=True)
    for rel, text in files.items():
        (folder / rel).parent.mkdir(parents=True, exist_ok=True)
        (folder / rel).write_text(text)


def tree(folder) -> dict:
    """Every file under `folder` -> its text (a symbolic link -> '-> target')."""
    out = {}
    for p in sorted(folder.rglob("*")):
        rel = p.relative_to(folder).as_posix()
        if p.is_symlink():
            out[rel] = "-> " + os.readlink(p)
        elif p.is_file():
            out[rel] = p.read_text()
    return out


def test_two_folders_are_exchanged_in_one_step(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    make_tree(a, {"sub/x": "a's"})
    make_tree(b, {"y": "b's"})
    assert can_exchange(b)
    exchange(a, b)
    assert tree(a) == {"y": "b's"} and tree(b) == {"sub/x": "a's"}
    with pytest.raises(OSError):
        exchange(a, tmp_path / "missing")   # nothing changed
    assert tree(a) == {"y": "b's"}


def test_no_exchange_for_a_link_or_a_mount_point(tmp_path):
    (tmp_path / "real").mkdir()
    (tmp_path / "link").symlink_to(tmp_path / "real")
    assert not can_exchange(tmp_path / "link")   # its target would stay as it is
    assert not can_exchange("/proc")             # a mount point cannot be renamed
    assert not can_exchange(tmp_path / "missing")


def test_a_tree_of_hard_links_skips_what_it_is_told_and_keeps_modes(tmp_path):
    src = tmp_path / "src"
    make_tree(src, {"keep.txt": "k", "sub/gone.csv": "g", "sub/stays.csv": "s"})
    (src / "to_sub").symlink_to("sub")
    os.chmod(src / "sub", 0o750)
    link_tree(src, tmp_path / "dst", skip={"sub/gone.csv"})
    dst = tmp_path / "dst"
    assert tree(dst) == {"keep.txt": "k", "sub/stays.csv": "s", "to_sub": "-> sub"}
    assert (dst / "keep.txt").stat().st_ino == (src / "keep.txt").stat().st_ino   # a link, not a copy
    assert (dst / "sub").stat().st_mode & 0o777 == 0o750


@pytest.mark.parametrize("place", ["move", "link"])
def test_a_merge_replaces_the_files_written_and_keeps_the_rest(tmp_path, place):
    src, dst = tmp_path / "src", tmp_path / "dst"
    make_tree(src, {"case4/summary.json": "new", "report.md": "new report", "was_a_folder": "a file now"})
    make_tree(dst, {"case4/summary.json": "old", "case4/notes.txt": "mine", "was_a_folder/x": "x"})
    merge_into(src, dst, os.replace if place == "move" else os.link)
    assert tree(dst) == {"case4/notes.txt": "mine", "case4/summary.json": "new", "report.md": "new report",
                         "was_a_folder": "a file now"}
    assert (src / "report.md").exists() == (place == "link")


def test_a_linked_merge_never_puts_a_folder_where_a_file_is(tmp_path):
    src, dst = tmp_path / "src", tmp_path / "dst"
    make_tree(src, {"x/a": "a"})
    make_tree(dst, {"x": "the user's file"})
    with pytest.raises(NotADirectoryError):
        merge_into(src, dst, os.link)
    assert (dst / "x").read_text() == "the user's file"


def test_folders_emptied_are_pruned_up_to_the_first_that_is_not(tmp_path):
    make_tree(tmp_path, {"a/keep": "k"})
    (tmp_path / "a" / "b").mkdir()
    (tmp_path / "c" / "d").mkdir(parents=True)
    prune_empty(tmp_path, ["a/b/gone.csv", "c/d/gone.csv"])
    assert sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*")) == ["a", "a/keep"]
