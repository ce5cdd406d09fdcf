"""An output folder's manifest (orthocontact.output.manifest): it lists what a
run wrote with each file's SHA-256, an earlier run's files are removed and
nothing else, and outputs read together must come from one run as it wrote
them."""
import hashlib
import json

import pytest

from orthocontact.errors import InputError
from orthocontact.output.manifest import (
    MANIFEST,
    listing,
    new_manifest,
    one_run,
    read_manifest,
    remove_earlier,
    write_manifest,
    written_by,
)


def sha(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def a_run(folder, files: dict, command="identify"):
    """Writes `files` (path -> bytes) into `folder` and its manifest, as a run does."""
    for name, data in files.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_bytes(data)
    m = new_manifest(folder, command, "9.9.9")
    write_manifest(folder, m)
    return m


def test_the_manifest_lists_every_file_written_with_its_digest(tmp_path):
    m = a_run(tmp_path, {"identified.json": b"{}\n", "case4/sweep.csv": b"a,b\n"})
    assert m.files == {"case4/sweep.csv": sha(b"a,b\n"), "identified.json": sha(b"{}\n")}
    d = json.loads((tmp_path / MANIFEST).read_text())
    assert d["command"] == "identify" and d["version"] == "9.9.9" and len(d["run_id"]) == 32
    assert read_manifest(tmp_path) == m
    assert listing(tmp_path) == m.files          # the manifest does not list itself
    assert new_manifest(tmp_path, "identify", "9.9.9").run_id != m.run_id


@pytest.mark.parametrize("files,says", [
    ('{"written_by": "orthocontact", "run_id": "r", "files": {"../outside.txt": "0"}}',
     "files: expected paths"),
    ('{"written_by": "orthocontact", "run_id": "r", "files": {"/etc/passwd": "0"}}', "files: expected paths"),
    ('{"written_by": "someone", "run_id": "r", "files": {}}', "expected the manifest an orthocontact"),
    ("not json", "expected the manifest an orthocontact"),
])
def test_a_manifest_orthocontact_did_not_write_is_refused(tmp_path, files, says):
    (tmp_path / MANIFEST).write_text(files)
    with pytest.raises(InputError, match=says) as e:
        read_manifest(tmp_path)
    assert "\n" not in str(e.value) and str(tmp_path / MANIFEST) in str(e.value)


def test_an_earlier_runs_files_go_the_users_and_changed_ones_stay(tmp_path):
    old = a_run(tmp_path, {"reduction.csv": b"1\n", "figs/a.png": b"png", "figs/b.png": b"png2",
                           "identified.md": b"# old\n", "shared.json": b"old"})
    (tmp_path / "my_notes.txt").write_text("mine")
    (tmp_path / "figs" / "mine.png").write_bytes(b"my figure")
    (tmp_path / "identified.md").write_text("# old, with my notes\n")
    kept = remove_earlier(tmp_path, old, keep={"shared.json": "x"})
    assert kept == ["identified.md"]
    assert sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*")) == [
        MANIFEST, "figs", "figs/mine.png", "identified.md", "my_notes.txt", "shared.json"]
    old2 = a_run(tmp_path / "sub", {"x/y/z.csv": b"1"})
    remove_earlier(tmp_path / "sub", old2, keep={})
    assert sorted(p.name for p in (tmp_path / "sub").iterdir()) == [MANIFEST]   # emptied folders go


def test_nothing_is_removed_through_a_symbolic_link(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "a.csv").write_bytes(b"1")
    out = tmp_path / "out"
    out.mkdir()
    old = a_run(out, {"sub/a.csv": b"1"})
    (out / "sub" / "a.csv").unlink()
    (out / "sub").rmdir()
    (out / "sub").symlink_to(outside)
    remove_earlier(out, old, keep={})
    assert (outside / "a.csv").read_bytes() == b"1"


def test_outputs_of_one_run_pass_and_mixed_or_changed_ones_are_named(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir(), b.mkdir()
    run_a = a_run(a, {"identified.json": b"A", "rig_scenario.toml": b"rig A"})
    a_run(b, {"identified.json": b"B", "rig_scenario.toml": b"rig B"})
    assert written_by(a / "identified.json") == run_a
    one_run(a / "identified.json", a / "rig_scenario.toml")
    (tmp_path / "mine.toml").write_text("a user's scenario")
    one_run(a / "identified.json", tmp_path / "mine.toml", None)      # no manifest: the user's own
    with pytest.raises(InputError) as e:
        one_run(a / "identified.json", b / "rig_scenario.toml")
    assert str(e.value).startswith(f"{b / 'rig_scenario.toml'}: written by `orthocontact identify` run")
    assert "two runs" in str(e.value)
    (a / "rig_scenario.toml").write_bytes(b"rig B")                    # a file of another run put in
    with pytest.raises(InputError, match="rig_scenario.toml: not the file `orthocontact identify` run"):
        one_run(a / "identified.json", a / "rig_scenario.toml")
