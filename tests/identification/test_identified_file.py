"""identified.json read back (orthocontact.identification.identified_file):
what is not identify's output is one InputError naming the file."""
import json

import pytest

from orthocontact.errors import InputError
from orthocontact.identification.identified_file import read_identified


def test_an_object_reads_back_as_written(tmp_path):
    d = {"mu1": {"value": 0.408}, "assumptions": {"rule": "coupled"}}
    (tmp_path / "identified.json").write_text(json.dumps(d))
    assert read_identified(tmp_path / "identified.json") == d
    assert read_identified(str(tmp_path / "identified.json")) == d


@pytest.mark.parametrize("content,says", [
    (None, "cannot read"),
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
