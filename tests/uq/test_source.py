"""uq.json names the law it drew from (orthocontact.uq.source), as export's
FMUs name theirs: identified.json's path and SHA-256, the identify run that
wrote it and the data digest, each checked against its own source here (the
file's bytes, the output folder's manifest, the data files' sha256sum
listing)."""
import hashlib
import json
import shutil
from pathlib import Path

from cli_run import run_cli
from orthocontact.uq.source import Source, read_source
from paths import SCENARIOS


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _data_digest(identified: Path) -> str:
    """`cd DATA && sha256sum FILE... | sha256sum` over the files identified.json names, by hand."""
    data = json.loads(identified.read_text())["data"]
    folder = Path(data["absolute_folder"])
    listing = "".join(f"{_sha256(folder / name)}  {name}\n" for name in sorted(data["files"]))
    return hashlib.sha256(listing.encode()).hexdigest()


def _uq(tmp_path, identified, out):
    scenario = tmp_path / "short.toml"   # 3 angles over 0.05 m: quick
    text = (SCENARIOS / "mat_aged.toml").read_text()
    for old, new in (("travel_m = 0.5", "travel_m = 0.05"), ("start_deg = 0.0", "start_deg = 30.0"),
                     ("stop_deg = 90.0", "stop_deg = 50.0"), ("step_deg = 1.0", "step_deg = 10.0")):
        text = text.replace(old, new, 1)
    scenario.write_text(text)
    p = run_cli(["uq", identified, "--scenario", scenario, "--samples", "3", "--scheduler", "none",
                 "--out", out], cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    return json.loads((out / "uq.json").read_text())["identification"]


def test_uq_json_names_the_identification_and_the_run_that_wrote_it(tmp_path, identified):
    said = _uq(tmp_path, identified, tmp_path / "uq")
    manifest = json.loads((identified.parent / ".orthocontact-manifest.json").read_text())
    assert manifest["command"] == "identify"
    assert said == {"path": str(identified), "sha256": _sha256(identified),
                    "identify_run_id": manifest["run_id"], "data_sha256": _data_digest(identified)}
    assert said["data_sha256"] == json.loads(identified.read_text())["data"]["sha256"]


def test_a_copy_no_manifest_lists_is_named_without_a_run(tmp_path, identified):
    """A copy outside its output folder: the user's own file, no identify
    run speaks for it; its bytes and data are named all the same."""
    copy = tmp_path / "mine" / "identified.json"
    copy.parent.mkdir()
    shutil.copy(identified, copy)
    est, source = read_source(copy)
    assert source == Source(str(copy), _sha256(identified), None, _data_digest(identified))
    assert est.path == copy and est.names
