"""What a reduction gives on (orthocontact.identification.reduction_output):
reduction.csv and reduction.json read back to the runs' values, with empty
cells (null in JSON) where a kind of run has no such value."""
import csv
import json

from orthocontact.identification.reduction import Reduction, RunReduction
from orthocontact.identification.reduction_output import COLUMNS, rows, write_table


def reduction():
    slide = RunReduction("s01", "slide", 30.0, 0.244, window_s=(0.5, 2.5), window_x1_m=(0.1, 0.58),
                         speed_m_s=0.2441, phi_deg=-11.5123456789012, phi_se_deg=0.002,
                         phi_halves_deg=(-11.51, -11.52), force_N=14.25, force_se_N=0.01, samples=400,
                         flags=["dropout", "outlier"])
    ramp = RunReduction("r01", "ramp", 0.0, 0.001, stiffness_N_m=12510.0, stiffness_se_N_m=30.0, samples=80)
    return Reduction([slide, ramp], ["s01: tracker drop-out"])


def test_the_table_and_json_read_back(tmp_path):
    red = reduction()
    assert [r["run"] for r in rows(red)] == ["s01", "r01"] and list(rows(red)[0]) == list(COLUMNS)
    write_table(red, tmp_path)
    table = list(csv.DictReader((tmp_path / "reduction.csv").open(newline="")))
    assert list(table[0]) == list(COLUMNS)
    s, r = table
    assert float(s["phi_deg"]) == round(-11.5123456789012, 8) and s["flags"] == "dropout outlier"
    assert (s["window_t0_s"], s["window_x1_end_m"], s["samples"]) == ("0.5", "0.58", "400")
    assert s["stiffness_N_m"] == "" and r["phi_deg"] == "" and r["stiffness_N_m"] == "12510"
    j = json.loads((tmp_path / "reduction.json").read_text())
    assert j["warnings"] == ["s01: tracker drop-out"]
    assert j["runs"][0]["phi_deg"] == -11.5123456789012 and j["runs"][1]["phi_deg"] is None
    assert j["runs"][1]["stiffness_se_N_m"] == 30.0 and set(j["method"]) >= {"window", "phi", "force"}
