"""Measurement data and their files (orthocontact.identification.measurements):
Excel's CSV UTF-8 is read, an invisible character in a header is shown,
written data read back, the digest follows the files."""
import json
import shutil

import numpy as np

from cli_run import one_error_line
from cli_run import run_cli as run
from orthocontact.experiment.rig_setup import RigSetup
from orthocontact.identification.measurements import (
    data_digest,
    data_files,
    load_data,
    visible,
    write_measurements,
)
from orthocontact.textfiles import files_read
from paths import SCENARIOS

DATA = SCENARIOS / "example_identification"


def test_excel_csv_utf8_with_a_byte_order_mark_is_read(tmp_path):
    data = tmp_path / "data"
    shutil.copytree(DATA, data)
    for name in ("forces.csv", "angles.csv", "ramp.csv"):
        f = data / name
        f.write_bytes(b"\xef\xbb\xbf" + f.read_bytes().replace(b"\n", b"\r\n"))
    p = run(["identify", data, "--out", tmp_path / "out", "--no-validate"], tmp_path)
    assert p.returncode == 0, p.stderr
    ref = run(["identify", DATA, "--out", tmp_path / "ref", "--no-validate"], tmp_path)
    assert ref.returncode == 0, ref.stderr
    got = json.loads((tmp_path / "out" / "identified.json").read_text())
    want = json.loads((tmp_path / "ref" / "identified.json").read_text())
    # the files' digest differs (their bytes do): everything read from them does not
    assert got.pop("data")["sha256"] != want.pop("data")["sha256"]
    assert json.dumps(got).replace(str(data), "DATA") == json.dumps(want).replace(str(DATA), "DATA")


def test_an_invisible_character_in_a_header_is_shown_escaped(tmp_path):
    data = tmp_path / "data"
    shutil.copytree(DATA, data)
    f = data / "forces.csv"
    f.write_text(f.read_text(encoding="utf-8").replace("mat_angle_deg", "mat_angle_deg\u200b", 1),
                 encoding="utf-8")
    p = run(["identify", data, "--out", tmp_path / "out"], tmp_path)
    one_error_line(p, "forces.csv: line 1: expected column 'mat_angle_deg'", "mat_angle_deg\\u200b")


def test_visible_escapes_exactly_what_a_reader_cannot_see():
    assert visible("mat_angle_deg,force_N") == "mat_angle_deg,force_N"
    assert visible("\ufeffmat angle\u200b\u00a0\t") == "\\ufeffmat angle\\u200b\\u00a0\\u0009"
    assert visible("φ 39.2°") == "φ 39.2°"   # printable non-ASCII stays


def test_written_measurements_read_back(tmp_path):
    rig = RigSetup(mass_kg=1.875, f_int_N=5.0)
    forces = np.array([[0.0, 12.5], [90.0, 16.5], [45.0, 14.25]])
    angles = np.array([[30.0, -11.5], [40.0, -11.4]])
    write_measurements(tmp_path / "d", rig, forces=forces, angles=angles)
    data = load_data(tmp_path / "d")
    assert data.rig.mass_kg == 1.875 and data.rig.f_int_N == 5.0
    np.testing.assert_array_equal(data.forces, forces)
    np.testing.assert_array_equal(data.angles, angles)
    assert data.ramp is None
    # the digest covers the files read: one changed digit changes it
    digests = []
    for _ in range(2):
        with files_read() as read:
            load_data(tmp_path / "d")
        files = data_files(tmp_path / "d", read)
        assert sorted(files) == ["angles.csv", "forces.csv", "rig.toml"]
        digests.append(data_digest(files))
        f = tmp_path / "d" / "forces.csv"
        f.write_text(f.read_text().replace("16.5", "16.6"))
    assert digests[0] != digests[1]


def test_a_ramp_in_mm_is_refused_naming_the_unit(tmp_path):
    """ramp.csv's x1_m x 1000 (mm in a metre column): it gave eps1 = 12.59,
    eps2 = 10.04 N/m (truth 12510, 10000), exit 0, no word; its stick branch
    reaches 1.965 m in a rig with 0.5 m of travel."""
    d = tmp_path / "d"
    shutil.copytree(DATA, d)
    rows = np.loadtxt(DATA / "ramp.csv", delimiter=",", skiprows=1)
    np.savetxt(d / "ramp.csv", np.column_stack([rows[:, 0] * 1000, rows[:, 1]]), delimiter=",",
               header="x1_m,force_N", comments="")
    p = run(["identify", d, "--out", tmp_path / "o", "--no-validate"], tmp_path)
    one_error_line(p, f"{d / 'ramp.csv'}: x1_m reaches 1.965 m, beyond the rig's travel 0.5 m",
                   "x1_m in mm? the column is in m")
    assert not (tmp_path / "o").exists()
    # the gate is in the reader: the same refusal for every caller
    import pytest

    from orthocontact.errors import InputError
    with pytest.raises(InputError, match="x1_m in mm"):
        load_data(d)


def test_a_velocity_column_in_cm_s_is_refused(tmp_path):
    d = tmp_path / "d"
    shutil.copytree(DATA, d)
    lines = (d / "angles.csv").read_text().splitlines()
    (d / "angles.csv").write_text("\n".join([lines[0] + ",velocity_m_s"] + [x + ",24.4" for x in lines[1:]])
                                  + "\n")
    p = run(["identify", d, "--out", tmp_path / "o", "--no-validate"], tmp_path)
    one_error_line(p, "angles.csv: row 1: velocity_m_s = 24.4 m/s", "cm/s?")
