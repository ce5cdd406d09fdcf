"""identified.json read back (orthocontact.identification.identified_file):
what is not identify's output is one InputError naming the file."""
import hashlib
import json
import re

import pytest

from orthocontact.errors import InputError
from orthocontact.identification.identified_file import read_identified


def test_an_object_reads_back_as_written(tmp_path):
    d = {"mu1": {"value": 0.408}, "assumptions": {"rule": "coupled"}}
    (tmp_path / "identified.json").write_text(json.dumps(d))
    assert read_identified(tmp_path / "identified.json") == d
    assert read_identified(str(tmp_path / "identified.json")) == d


@pytest.mark.parametrize("content,says", [
    (None, "not found"),
    ("{'mu1': 1}", "expected JSON written by `orthocontact identify`"),
    ("[1, 2]", "expected a JSON object written by `orthocontact identify`"),
    ("", "expected JSON"),
])
def test_what_is_not_identifys_output_names_the_file(tmp_path, content, says):
    path = tmp_path / "identified.json"
    if content is not None:
        path.write_text(content)
    with pytest.raises(InputError) as e:
        read_identified(path)
    assert str(e.value).startswith(f"{path}: ") and says in str(e.value)
    assert "\n" not in str(e.value)


def test_the_data_are_checked_file_by_file(tmp_path):
    from orthocontact.identification.identified_file import check_data
    from orthocontact.identification.measurements import data_digest
    data = tmp_path / "id" / "data"
    data.mkdir(parents=True)
    (data / "rig.toml").write_text("mass_kg = 1.875\n")
    (data / "forces.csv").write_text("mat_angle_deg,force_N\n0,12.5\n")
    files = {n: hashlib.sha256((data / n).read_bytes()).hexdigest() for n in ("forces.csv", "rig.toml")}
    d = {"data": {"folder": "data", "files": files, "sha256": data_digest(files)}}
    path = tmp_path / "id" / "identified.json"
    got = check_data(path, d)         # data.folder found relative to the file's folder too
    assert got.folder == path.parent / "data" and got.files == files
    (data / "forces.csv").unlink()
    with pytest.raises(InputError) as e:
        check_data(path, d)
    assert str(e.value).startswith(f"{path}: data.files: 1 of the 2 files the identification read")
    assert "forces.csv (missing)" in str(e.value)


def test_a_value_that_cannot_be_right_is_refused_by_the_one_reader(tmp_path):
    """Every reader of identified.json (export, uq) gets the plausibility
    gate: a hand-edited eps1 above the hard limit is refused, naming the
    override the caller gives; forced, it is read as it is."""
    d = {"mu1": {"value": 0.408}, "eps1": {"value": 1e13}, "assumptions": {"mass_kg": 1.875},
         "covariance": {"parameters": ["mu1", "eps2"], "values": [0.408, 1e4], "matrix": [[1, 0], [0, 1]]}}
    path = tmp_path / "identified.json"
    path.write_text(json.dumps(d))
    with pytest.raises(InputError) as e:
        read_identified(path, override="--force writes it anyway")
    assert str(e.value) == (f"{path}: eps1 = 1e+13 N/m: a contact's tangential stiffness is 10-1e9 N/m; "
                            "none above 1e+12 N/m can be right; refused (--force writes it anyway)")
    assert read_identified(path, force=True) == d
    # what uq draws around (covariance.values) and the assumptions are judged too
    for edit, says in ((("covariance", "values"), "covariance.values: eps2 = 1e+13 N/m"),
                       (("assumptions", "mass_kg"), "assumptions.mass_kg = 1.875e+06 kg")):
        bad = json.loads(json.dumps(d))
        bad["eps1"]["value"] = 1.25e4
        if edit[0] == "covariance":
            bad["covariance"]["values"] = [0.408, 1e13]
        else:
            bad["assumptions"]["mass_kg"] = 1.875e6
        path.write_text(json.dumps(bad))
        with pytest.raises(InputError, match=re.escape(says)):
            read_identified(path)
