"""Results for machines (orthocontact.output.tables): the CSV and JSON files
read back to what was written."""
import csv
import json
import math

from orthocontact.output.tables import write_csv, write_json


def test_csv_round_trip_floats_to_12_significant_digits(tmp_path):
    path = tmp_path / "t.csv"
    write_csv(path, ["angle_deg", "phi_deg", "rule"], [(0.0, math.pi, "coupled"), (39, -1 / 3, "eq20")])
    rows = list(csv.reader(path.open(newline="")))
    assert rows == [["angle_deg", "phi_deg", "rule"], ["0", "3.14159265359", "coupled"],
                    ["39", "-0.333333333333", "eq20"]]
    assert float(rows[1][1]) == round(math.pi, 11)
    assert "\r" in path.read_bytes().decode()   # csv's own line ends: one row a line in any reader


def test_json_is_indented_ordered_and_ends_in_a_newline(tmp_path):
    path = tmp_path / "s.json"
    data = {"z": 1, "a": [1.5, None], "m": {"x": "y"}}
    write_json(path, data)
    text = path.read_text()
    assert text.endswith("}\n") and '\n  "z": 1,' in text
    assert json.loads(text) == data and list(json.loads(text)) == ["z", "a", "m"]


def test_json_writes_a_number_that_is_not_finite_as_null(tmp_path):
    """A step study's summary.json held NaN, which no strict JSON reader takes."""
    path = tmp_path / "s.json"
    write_json(path, {"a": float("nan"), "b": [1.0, float("inf"), {"c": -float("inf")}], "d": 2.5})

    def refuse(token):
        raise ValueError(f"not JSON: {token}")
    assert json.loads(path.read_text(), parse_constant=refuse) == {"a": None, "b": [1.0, None, {"c": None}],
                                                                   "d": 2.5}
