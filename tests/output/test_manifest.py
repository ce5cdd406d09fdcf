"""An output folder's manifest (orthocontact.output.manifest): it lists what a
run wrote with each file's SHA-256, and outputs read together must come from
one run as it wrote them (what a new run removes: tests/output/test_folder.py)."""
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
