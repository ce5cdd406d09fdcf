"""identified.json's object read back, typed
(orthocontact.identification.identified_json): what the one writer writes
reads back to the same object, and the first field that is not as identify
writes it is named in one line."""
import dataclasses
import math
from pathlib import Path

import pytest

from orthocontact.errors import InputError
from orthocontact.identification import identified
from orthocontact.identification.identified_json import from_json
from orthocontact.identification.measurements import data_digest

FILES = {"rig.toml": "0" * 64, "angles.csv": "1" * 64}


def made_by_hand(**changes) -> identified.IdentifiedFile:
    """Angles alone at two velocities: l1/l2 fitted, the rest not identified."""
    f = identified.IdentifiedFile(
        estimates={**{n: identified.NotIdentified("needs forces.csv") for n in identified.REPORTED},
                   "l1_l2_ratio": identified.Estimate(0.82, 0.01, (0.8, 0.84), math.inf,
                                                      note="what angles alone determine")},
        max_rule=None, eq40=None, eq41=None, eq1=None,
        noise_estimate={"angles_deg": 0.3, "angles_deg_by_velocity": {"0.125": 0.35, "0.244": 0.25}},
        noise_model={"angles_deg": {"between_runs": 0.3}}, intervals="log scale",
        noise_assumed=("angles_deg",), fit_residuals={"angles": {"rms": 0.3}}, dof=3,
        covariance=identified.Covariance(("l1_l2_ratio",), (0.82,), ((1e-4,),)), covariance_joint=None,
        points=identified.Points(angles=((30.0, -10.0), (60.0, -9.0), (30.0, -10.5), (60.0, -8.5)),
                                 angle_velocities=(0.125, 0.125, 0.244, 0.244), forces=None),
        ramp_stick_points=0, validation_fmu=None,
        data=identified.DataRecord(folder="d", absolute_folder="/d", forces=0, angles=4, ramp=0,
                                   files=FILES, sha256=data_digest(FILES)),
        assumptions=identified.Assumptions(rule="coupled", alpha_offset_deg=90.0, beta_offset_deg=0.0,
                                           mass_kg=1.875, g=9.806, f_int_N=5.0, ramp_angle_deg=0.0,
                                           mu_strip=0.0, c_strip_N_s_m=0.0,
                                           phi_convention="counterclockwise", ci="95%"),
        fit=identified.FitRecord(converged=True, convergence={"solver": True, "noise_model": True},
                                 reweighting_rounds=3,
                                 solves=({"status": "Solve_Succeeded", "iterations": 5,
                                          "step_left_se": 1e-9, "converged": True},),
                                 lack_of_fit={}),
        reduction=identified.ReductionSummary(runs={"slide": 4, "carriage": 0, "ramp": 0}, left_out=(),
                                              flagged={}, table="reduction.csv",
                                              figures=("reduction_30deg.png",), scenario=None))
    return dataclasses.replace(f, **changes)


def test_the_json_object_reads_back_as_the_object():
    f = made_by_hand()
    d = f.as_json()
    assert d["schema_version"] == identified.SCHEMA_VERSION
    assert list(d)[:7] == ["schema_version", *identified.REPORTED, "l1_l2_ratio"]
    assert d["eps2"] == {"identifiable": False, "reason": "needs forces.csv"}
    assert d["l1_l2_ratio"]["dof"] == "inf"       # JSON has no infinity: the text "inf"
    assert "covariance_joint" not in d and d["noise_assumed"] == ["angles_deg"]
    back = from_json(Path("identified.json"), d)
    assert back == f and back.path == Path("identified.json")
    assert back.value("l1_l2_ratio") == 0.82 and back.value("mu1") is None


@pytest.mark.parametrize(("edit", "says"), [
    (lambda d: d["assumptions"].pop("rule"), "assumptions.rule: expected one of"),
    (lambda d: d["data"].update(sha256="0" * 64), "data.sha256: expected the digest"),
    (lambda d: d["points"].update(angle_velocities=[0.1]), "points.angle_velocities: expected one velocity"),
    (lambda d: d["noise_estimate"].update(angles_deg=-1), "noise_estimate.angles_deg: expected a number"),
    (lambda d: d["reduction"].update(runs=[]), "reduction.runs: expected {kind: count}"),
    (lambda d: d.update(intervals=1), "intervals: expected a string"),
    (lambda d: d["fit"].update(converged=False), "fit.converged: expected true (as its convergence says)"),
])
def test_a_field_not_as_identify_writes_it_is_named(edit, says):
    d = made_by_hand().as_json()
    edit(d)
    with pytest.raises(InputError) as e:
        from_json(Path("identified.json"), d)
    assert str(e.value).startswith(f"identified.json: {says}") and "\n" not in str(e.value)


def test_the_first_field_in_the_files_order_is_the_one_named():
    d = made_by_hand().as_json()
    d["assumptions"]["mass_kg"] = -1
    d["data"]["folder"] = ""
    with pytest.raises(InputError, match=r"^identified.json: assumptions.mass_kg: expected a finite number"):
        from_json(Path("identified.json"), d)
