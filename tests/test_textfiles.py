"""The one reader of users' text files: encodings, line ends, OS errors, and
the record of what was read (provenance)."""
import hashlib
import json
import re
import shutil
from pathlib import Path

import pytest

from cli_run import one_error_line, run_cli
from orthocontact.errors import InputError
from orthocontact.textfiles import files_read, read_rows, read_text, read_toml, sha256_of
from paths import ROOT, SCENARIOS


def test_bom_and_line_ends_are_read_as_plain_text(tmp_path):
    p = tmp_path / "a.csv"
    p.write_bytes(b"\xef\xbb\xbfx,y\r\n1,2\r3,4\n")
    assert read_text(p, "a CSV file") == "x,y\n1,2\n3,4\n"


def test_not_utf8_is_one_line_naming_the_file(tmp_path):
    p = tmp_path / "a.csv"
    p.write_bytes(b"x\n\xe9\n")
    with pytest.raises(InputError, match=r"a\.csv: byte 2: not UTF-8"):
        read_text(p, "a CSV file")


def test_missing_and_folder_are_named(tmp_path):
    with pytest.raises(InputError, match="not found; expected a CSV"):
        read_text(tmp_path / "none.csv", "a CSV")
    with pytest.raises(InputError, match="is a folder; expected a CSV"):
        read_text(tmp_path, "a CSV")


def test_files_read_records_the_digest_of_every_read(tmp_path):
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_bytes(b"alpha\n")
    b.write_bytes(b"beta\n")
    read_text(a, "x")   # outside any record
    with files_read() as outer:
        read_text(a, "x")
        with files_read() as inner:
            read_text(b, "x")
    assert set(outer) == {str(a), str(b)} and set(inner) == {str(b)}
    assert outer[str(a)].sha256 == hashlib.sha256(b"alpha\n").hexdigest() == sha256_of(a)


# --- CSV rows: what a spreadsheet in another locale writes -------------------

def rows_of(tmp_path, blob: bytes):
    p = tmp_path / "a.csv"
    p.write_bytes(blob)
    return read_rows(p, "a CSV file")


def test_rows_keep_their_line_numbers_without_blank_and_comment_lines(tmp_path):
    got = rows_of(tmp_path, b"\xef\xbb\xbf# from the lab\r\nx , y\r\n\r\n1, 2\r\n,\r\n# note\r\n3,4\r\n")
    assert got == [(2, ["x", "y"]), (4, ["1", "2"]), (7, ["3", "4"])]


def test_a_semicolon_file_with_decimal_commas_is_read_as_with_points(tmp_path):
    # Excel where the decimal separator is a comma: ; between cells, 0,5 in them.
    got = rows_of(tmp_path, b"t_s;x1_m;x2_m\n0,004;-1,25e-3;\n0,008;0;5\n")
    assert got == [(1, ["t_s", "x1_m", "x2_m"]), (2, ["0.004", "-1.25e-3", ""]), (3, ["0.008", "0", "5"])]
    assert rows_of(tmp_path, b"x\ty\n0,5\t2\n")[1] == (2, ["0.5", "2"])           # tabs alike
    assert rows_of(tmp_path, b"x;y\n0.5;2.25\n")[1] == (2, ["0.5", "2.25"])      # points stay points
    assert rows_of(tmp_path, b"run;kind\na000_v1;slide\n")[1] == (2, ["a000_v1", "slide"])


@pytest.mark.parametrize("blob,says", [
    (b"x,y\n0,5,1\n",
     "line 2: 3 cells (0,5,1) where the header names 2 columns: decimal commas such as 0,5?"),
    (b'x,y\n"0,5",1\n',
     "line 2: '0,5': a decimal comma (or a thousands separator) in a comma-separated file"),
    (b"x;y\n1.234,5;2\n", "line 2: '1.234,5': a number with a thousands separator"),
    # two points in one cell and none in the other: as many points as cells
    (b"x,y\n1.234.5,7\n",
     "line 2: '1.234.5': a decimal comma (or a thousands separator) in a comma-separated file"),
    (b"x;y\n0,5;1\n1.234;2\n", "line 3: '1.234' beside decimal commas such as '0,5' (line 2) in a file "
                               "separated by semicolons"),
])
def test_what_cannot_be_read_unambiguously_is_one_line_saying_what_to_do(tmp_path, blob, says):
    with pytest.raises(InputError) as e:
        rows_of(tmp_path, blob)
    assert str(e.value).startswith(f"{tmp_path / 'a.csv'}: ") and says in str(e.value)
    assert "\n" not in str(e.value)


def test_trailing_empty_cells_are_not_extra_columns(tmp_path):
    assert rows_of(tmp_path, b"x,y\n1,2,\n")[1] == (2, ["1", "2", ""])


def test_toml_with_a_decimal_comma_names_the_line_and_the_fix(tmp_path):
    p = tmp_path / "rig.toml"
    p.write_bytes(b"\xef\xbb\xbfg = 9.806\r\nmass_kg = 1,875   # kg\r\n")
    with pytest.raises(InputError, match=r"rig\.toml: line 2: mass_kg = 1,875: a decimal comma; "
                                         r"TOML numbers take a decimal point \(mass_kg = 1\.875\)"):
        read_toml(p, "rig.toml")
    p.write_bytes(b"\xef\xbb\xbfg = 9.806\r\nmass_kg = 1.875\r\n")
    assert read_toml(p, "rig.toml") == {"g": 9.806, "mass_kg": 1.875}


# --- every format through the real command ----------------------------------
# Each case alters a copy of a bundled data set and is identified again: read
# (BOM, CRLF, a semicolon file with decimal commas) it gives the original's
# estimates bit for bit; refused (a decimal comma in a comma-separated file or
# in TOML) it is one line saying so.

ESTIMATES = ("mu1", "mu2", "eps_ratio", "eps1", "eps2")


def altered(blob: bytes, case: str, name: str) -> bytes:
    text = blob.decode()
    if case == "bom":
        return b"\xef\xbb\xbf" + blob
    if case == "crlf":
        return text.replace("\n", "\r\n").encode()
    if case == "semicolons":     # as Excel saves it where the decimal separator is a comma
        return text.replace(",", ";").replace(".", ",").encode()
    assert case == "decimal_comma"
    if name.endswith(".toml"):
        return re.sub(r"= (\d+)\.(\d+)", r"= \1,\2", text, count=1).encode()
    head, *rest = text.splitlines(True)
    return (head + "".join(ln.replace(".", ",") for ln in rest)).encode()


def identify(data: Path, out: Path):
    return run_cli(["identify", data, "--out", out, "--no-validate"], cwd=ROOT, timeout=300)


def estimates(out: Path) -> dict:
    d = json.loads((out / "identified.json").read_text())
    return {k: d[k]["value"] for k in ESTIMATES}


def truth(tmp_path_factory, data: str) -> dict:
    """The estimates identify gives from the bundled data set `data`, unaltered."""
    out = tmp_path_factory.mktemp("truth") / "out"
    p = identify(SCENARIOS / data, out)
    assert p.returncode == 0, p.stderr
    return estimates(out)


@pytest.fixture(scope="module")
def reduced_truth(tmp_path_factory):
    return truth(tmp_path_factory, "example_identification")


@pytest.mark.parametrize("name,case", [
    (name, case) for name in ("forces.csv", "angles.csv", "ramp.csv", "rig.toml")
    for case in ("bom", "crlf", "semicolons", "decimal_comma")
    if not (name == "rig.toml" and case == "semicolons")])    # TOML has no separator
def test_reduced_data_every_file_every_case(tmp_path, reduced_truth, name, case):
    data = tmp_path / "data"
    shutil.copytree(SCENARIOS / "example_identification", data)
    (data / name).write_bytes(altered((data / name).read_bytes(), case, name))
    p = identify(data, tmp_path / "out")
    if case == "decimal_comma":
        says = "a decimal comma; TOML numbers take a decimal point" if name == "rig.toml" else \
            "where the header names 2 columns: decimal commas such as 0,5?"
        one_error_line(p, f"{data / name}: line ", says)
        assert not (tmp_path / "out").exists()
    else:
        assert p.returncode == 0, p.stderr
        assert estimates(tmp_path / "out") == reduced_truth


@pytest.fixture(scope="module")
def recordings_truth(tmp_path_factory):
    return truth(tmp_path_factory, "example_recordings")


@pytest.mark.parametrize("case", ["bom", "crlf", "semicolons"])
def test_raw_recordings_every_file_altered_read_as_the_original(tmp_path, recordings_truth, case):
    # rig.toml, runs.csv and every trajectory and force log, in one identification
    data = tmp_path / "data"
    shutil.copytree(SCENARIOS / "example_recordings", data)
    files = [f for f in data.rglob("*")
             if f.suffix == ".csv" or (f.suffix == ".toml" and case != "semicolons")]
    assert len(files) > 100
    for f in files:
        f.write_bytes(altered(f.read_bytes(), case, f.name))
    p = identify(data, tmp_path / "out")
    assert p.returncode == 0, p.stderr
    assert estimates(tmp_path / "out") == recordings_truth


@pytest.mark.parametrize("name,says", [
    ("rig.toml", "line 1: mass_kg = 1,875: a decimal comma"),
    ("runs.csv", "line 2: 5 cells (a000_v244_01,slide,0,0,244) where the header names 4 columns: "
                 "decimal commas such as 0,5?"),
    ("trajectories/a045_v244_01.csv", "line 2: 6 cells (0,00845,"),
    ("forces/a045_v244_01.csv", "line 2: 4 cells (0,00365,0,0718) where the header names 2 columns"),
])
def test_raw_recordings_with_decimal_commas_in_a_comma_file_are_one_line(tmp_path, name, says):
    data = tmp_path / "data"
    shutil.copytree(SCENARIOS / "example_recordings", data)
    (data / name).write_bytes(altered((data / name).read_bytes(), "decimal_comma", name))
    p = identify(data, tmp_path / "out")
    one_error_line(p, f"{data / name}: {says}")


@pytest.mark.parametrize("case", ["bom", "crlf", "decimal_comma"])
def test_a_scenario_file_every_case(tmp_path, case):
    text = (SCENARIOS / "case4.toml").read_text().replace("step_deg = 1.0", "step_deg = 45.0")
    (tmp_path / "plain.toml").write_text(text)
    (tmp_path / "s.toml").write_bytes(altered(text.encode(), case, "s.toml"))
    p = run_cli(["run", tmp_path / "s.toml", "--out", tmp_path / "out", "--workers", "1"], cwd=ROOT)
    if case == "decimal_comma":
        one_error_line(p, f"{tmp_path / 's.toml'}: line 8: mu1 = 0,1: a decimal comma; TOML numbers "
                          "take a decimal point (mu1 = 0.1)")
        return
    assert p.returncode == 0, p.stderr
    q = run_cli(["run", tmp_path / "plain.toml", "--out", tmp_path / "plain", "--workers", "1"], cwd=ROOT)
    assert q.returncode == 0, q.stderr
    assert (tmp_path / "out" / "sweep.csv").read_bytes() == (tmp_path / "plain" / "sweep.csv").read_bytes()


@pytest.mark.parametrize("case", ["bom", "crlf"])
def test_identified_json_with_a_bom_or_crlf_is_read(tmp_path, identified, case):
    # uq reads it (export too, through the same reader); a copy outside its
    # output folder, so that the folder's manifest does not speak for it
    copy = tmp_path / "identified.json"
    copy.write_bytes(altered(identified.read_bytes(), case, copy.name))
    args = ["--scenario", SCENARIOS / "mat_aged.toml", "--samples", "2", "--scheduler", "none"]
    p = run_cli(["uq", copy, *args, "--out", tmp_path / "a"], cwd=ROOT)
    q = run_cli(["uq", identified, *args, "--out", tmp_path / "b"], cwd=ROOT)
    assert p.returncode == 0 and q.returncode == 0, p.stderr + q.stderr
    assert (tmp_path / "a" / "uq_bands.csv").read_bytes() == (tmp_path / "b" / "uq_bands.csv").read_bytes()
