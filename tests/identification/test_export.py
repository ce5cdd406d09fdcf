"""`orthocontact export`: identify on the bundled example, export, and run
the exported FMUs with no parameter set anywhere (fmpy, libcosim): the
trajectory angle is the identified model's closed-form prediction."""
import html
import json
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
import zipfile
from datetime import datetime, timezone
from pathlib import Path

import pytest
from fmpy.ssp.ssd import read_ssv
from fmpy.validation import validate_fmu

from cli_run import one_error_line
from fmu_values import schema_errors, values_with_nothing_set
from libcosim_rig import run_rig_ssp
from orthocontact import __version__
from orthocontact.fmu.contact import ContactFMU
from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.start_values import start_values_of
from orthocontact.identification.export import load_calibration, predicted_phi_deg
from orthocontact.rig.harness import LineFit, run
from paths import SCENARIOS

DATA = SCENARIOS / "example_identification"
ANGLE = 40.0   # near the example mat's extremum


def cli(*args, timeout=300):
    return subprocess.run([sys.executable, "-m", "orthocontact", *map(str, args)], capture_output=True,
                          text=True, timeout=timeout)


@pytest.fixture(scope="module")
def exported(identified, tmp_path_factory):
    out = tmp_path_factory.mktemp("export") / "calibrated"
    p = cli("export", identified, "--out", out, "--angle", ANGLE)
    assert p.returncode == 0, p.stderr
    return out


def test_export_writes_calibrated_fmus_that_validate_and_keep_everything(identified, exported):
    d = json.loads(identified.read_text())
    names = sorted(p.relative_to(exported).as_posix() for p in exported.rglob("*") if p.is_file())
    assert names == [".orthocontact-manifest.json", "calibration.ssv", "fmi2/OrthotropicContact.fmu",
                     "fmi3/OrthotropicContact.fmu", f"rig_{ANGLE:g}.ssp"]
    for v in (2, 3):
        fmu = exported / f"fmi{v}/OrthotropicContact.fmu"
        assert validate_fmu(str(fmu)) == [] and schema_errors(fmu) == []
        stated = start_values_of(fmu)
        assert {n: stated[n] for n in ("mu1", "mu2", "eps1", "eps2")} == \
            {n: d[n]["value"] for n in ("mu1", "mu2", "eps1", "eps2")}
        assert values_with_nothing_set(fmu, ["mu1", "eps2"]) == {"mu1": d["mu1"]["value"],
                                                                "eps2": d["eps2"]["value"]}
        original, copy = zipfile.ZipFile(find_fmu(fmi_version=v)), zipfile.ZipFile(fmu)
        for name in original.namelist():   # binaries of every platform, sources, licenses
            if name != "modelDescription.xml":
                assert copy.read(name) == original.read(name), name
        doc = copy.read("documentation/calibration.html").decode()
        digest = d["data"]["sha256"]
        assert re.fullmatch("[0-9a-f]{64}", digest)
        today = datetime.now(timezone.utc).strftime("%Y-%m-%d")
        for text in (digest, today, f"orthocontact {__version__}"):
            assert text in doc
        lo, hi = d["mu1"]["ci95"]
        assert f"{lo:.6g} .. {hi:.6g}" in doc
        assert sorted(d["data"]["files"]) == ["angles.csv", "forces.csv", "ramp.csv", "rig.toml"]
        for name, sha in d["data"]["files"].items():
            assert f"<tr><td><code>{name}</code></td><td><code>{sha}</code></td></tr>" in doc
        description = re.search(r'<fmiModelDescription[^>]*description="([^"]*)"',
                                copy.read("modelDescription.xml").decode()).group(1)
        assert digest in description and today in description and "calibration.html" in description


def test_the_ssv_is_valid_and_holds_the_calibration(identified, exported):
    d = json.loads(identified.read_text())
    ps = read_ssv(str(exported / "calibration.ssv"))   # validated against the SSP schema
    values = {p.name: p.value for p in ps.parameters}
    assert {n: float(values[n]) for n in ("mu1", "mu2", "eps1", "eps2")} == \
        {n: d[n]["value"] for n in ("mu1", "mu2", "eps1", "eps2")}
    assert int(values["slidingRule"]) == 2


class NothingSet(ContactFMU):
    """The contact FMU initialized without setting any parameter: the rig
    harness's loop drives only its inputs."""

    def initialize(self, params, start_time=0.0):
        self.slave.setupExperiment(startTime=start_time)
        self.slave.enterInitializationMode()
        self.slave.exitInitializationMode()
        self.time, self.initialized = start_time, True


def test_the_exported_fmu_runs_calibrated_in_fmpy_with_nothing_set(identified, exported):
    cal = load_calibration(identified)
    rig = cal.rig.harness(c_strip=cal.c_strip)   # the data's quasi-static rig
    fmu = NothingSet(exported / "fmi2/OrthotropicContact.fmu", instance_name="nothing_set")
    try:
        # the parameters given to run() only scale the quasi-static Newton solve
        res = run(cal.rig.params_at(cal.law, ANGLE), rig, fmu=fmu)
    finally:
        fmu.close()
    expected = predicted_phi_deg(cal, ANGLE)
    assert abs(expected) > 10      # far from what the FMU's defaults give here
    assert abs(res.phi_deg - expected) <= 1e-9   # measured 4e-15 deg


@pytest.mark.needs("libcosimpy")
def test_the_exported_ssp_runs_calibrated_in_libcosim_with_no_parameter_set(identified, exported, tmp_path):
    """The SSP's parameter bindings are taken out: the FMUs' own start values
    alone make the calibrated experiment (CarriageBlock's dynamic rig)."""
    bare = tmp_path / "bare.ssp"
    with zipfile.ZipFile(exported / f"rig_{ANGLE:g}.ssp") as z, zipfile.ZipFile(bare, "w") as o:
        for info in z.infolist():
            data = z.read(info)
            if info.filename == "SystemStructure.ssd":
                text, n = re.subn(r"\s*<ssd:ParameterBindings>.*?</ssd:ParameterBindings>", "",
                                  data.decode(), flags=re.S)
                assert n == 2 and "ParameterSet" not in text
                data = text.encode()
            o.writestr(info, data)
    cal = load_calibration(identified)
    rig = cal.rig.harness(c_strip=cal.c_strip)
    n = int(rig.travel_m / (rig.velocity_m_s * rig.step_s) + 0.5)
    rows = run_rig_ssp(bare, n)
    fit = LineFit()
    for x1, x2, drive in rows:
        if x1 >= rig.fit_from * rows[-1][0]:
            fit.add(x1, x2, drive)
    # the dynamic rig has settled to the steady angle long before the fit: measured 6e-10 deg
    assert abs(fit.angle_deg() - predicted_phi_deg(cal, ANGLE)) <= 1e-6


def test_eps2_not_identified_takes_the_nominal_and_says_so(identified, tmp_path):
    d = json.loads(identified.read_text())
    ratio = d["eps_ratio"]["value"]
    for n in ("eps1", "eps2"):
        d[n] = {"identifiable": False, "reason": "no ramp.csv"}
    d["data"]["folder"] = str(DATA)
    (tmp_path / "identified.json").write_text(json.dumps(d))
    p = cli("export", tmp_path / "identified.json", "--out", tmp_path / "out")
    assert p.returncode == 0, p.stderr
    fmu = tmp_path / "out/fmi2/OrthotropicContact.fmu"
    v = start_values_of(fmu)
    assert v["eps2"] == 1e4 and v["eps1"] == ratio * 1e4   # rig.toml's eps2_nominal_N_m (default)
    doc = zipfile.ZipFile(fmu).read("documentation/calibration.html").decode()
    assert "eps2 was <b>not</b> identified" in doc and "eps2_nominal_N_m" in doc


@pytest.mark.parametrize("edit,says", [
    (lambda d: d.pop("mu1"), "mu1: expected an object"),
    (lambda d: d["mu2"].update(value=-1), "mu2.value: expected a finite number > 0"),
    (lambda d: d["assumptions"].update(rule="sticky"), "assumptions.rule: expected one of"),
    (lambda d: d["data"].update(folder="nowhere", absolute_folder="/nowhere"),
     "data.folder: nowhere not found"),
    (lambda d: d["data"].update(sha256="0" * 64), "data.sha256: expected the digest of data.files"),
    (lambda d: d["data"].pop("files"), "data.files: expected the SHA-256 of every file"),
])
def test_bad_input_is_one_line_naming_the_file_and_field(identified, tmp_path, edit, says):
    d = json.loads(identified.read_text())
    edit(d)
    bad = tmp_path / "identified.json"
    bad.write_text(json.dumps(d))
    p = cli("export", bad, "--out", tmp_path / "out")
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and str(bad) in lines[0] and says in lines[0], p.stderr
    assert not (tmp_path / "out").exists()


def scale_forces(folder: Path, pattern: str, factor: float) -> list:
    """Every force log `pattern` in folder/forces/ with force_N times
    `factor`; their paths under folder."""
    changed = []
    for f in sorted((folder / "forces").glob(pattern)):
        lines = f.read_text().splitlines()
        rows = [ln.split(",") for ln in lines[1:]]
        f.write_text("\n".join([lines[0]] + [f"{t},{float(F) * factor:.6g}" for t, F in rows]) + "\n")
        changed.append(f.relative_to(folder).as_posix())
    return changed


def test_force_logs_changed_after_identify_are_refused_by_export_and_uq_naming_them(tmp_path):
    """Every 45 deg force log times 1.1: before, the digest hashed rig.toml
    only, and export took the changed data with the original's digest."""
    import hashlib
    data = tmp_path / "recordings"
    shutil.copytree(SCENARIOS / "example_recordings", data)
    first = tmp_path / "id"
    p = cli("identify", data, "--out", first, "--no-validate")
    assert p.returncode == 0, p.stderr
    d = json.loads((first / "identified.json").read_text())["data"]
    read = {f.relative_to(data).as_posix(): hashlib.sha256(f.read_bytes()).hexdigest()
            for f in data.rglob("*.*") if f.name != "README.md"}
    assert d["files"] == read and len(read) == 153    # rig.toml, runs.csv and every recording
    p = cli("export", first / "identified.json", "--out", tmp_path / "exported", "--angle", ANGLE)
    assert p.returncode == 0, p.stderr
    fmu = zipfile.ZipFile(tmp_path / "exported/fmi2/OrthotropicContact.fmu")
    doc = fmu.read("documentation/calibration.html").decode()
    assert all(f"<tr><td><code>{n}</code></td><td><code>{h}</code></td></tr>" in doc for n, h in read.items())
    assert f"data sha256 {d['sha256']} (of 153 files" in fmu.read("modelDescription.xml").decode()

    altered = scale_forces(data, "a045_*.csv", 1.1)
    assert len(altered) == 10
    p = cli("export", first / "identified.json", "--out", tmp_path / "refused", "--angle", ANGLE)
    one_error_line(p, str(first / "identified.json"), "10 of the 153 files", *altered)
    p = cli("uq", first / "identified.json", "--scenario", first / "rig_scenario.toml", "--samples", 10,
            "--out", tmp_path / "uq")
    one_error_line(p, str(first / "identified.json"), "10 of the 153 files", *altered)
    assert not (tmp_path / "refused").exists() and not (tmp_path / "uq").exists()

    second = tmp_path / "id_altered"
    p = cli("identify", data, "--out", second, "--no-validate")
    assert p.returncode == 0, p.stderr
    d2 = json.loads((second / "identified.json").read_text())["data"]
    assert d2["sha256"] != d["sha256"]
    assert sorted(n for n in d["files"] if d["files"][n] != d2["files"][n]) == altered
    # a rig scenario of one run with the estimates of another: two runs, refused
    p = cli("uq", second / "identified.json", "--scenario", first / "rig_scenario.toml", "--samples", 10,
            "--out", tmp_path / "uq")
    one_error_line(p, f"{first / 'rig_scenario.toml'}: written by `orthocontact identify` run", "two runs")


def edited(identified, tmp_path, **values):
    """A copy of identified.json (outside its run's folder, as a user's
    edit would be) with the estimates `values` changed."""
    d = json.loads(identified.read_text())
    for n, v in values.items():
        d[n]["value"] = v
    path = tmp_path / "edited.json"
    path.write_text(json.dumps(d))
    return path


def test_export_refuses_a_value_that_cannot_be_right_and_force_overrides_it(identified, tmp_path):
    """An edited eps1 = 1e13 N/m, above identify's own limit 1e12: it was
    exported with only finite and > 0 checked, exit 0."""
    from cli_run import one_error_line
    path = edited(identified, tmp_path, eps1=1e13)
    p = cli("export", path, "--out", tmp_path / "o")
    one_error_line(p, f"{path}: eps1 = 1e+13 N/m", "none above 1e+12 N/m can be right",
                   "refused (`orthocontact export --force` exports it anyway)")
    assert not (tmp_path / "o").exists()
    p = cli("export", path, "--out", tmp_path / "o", "--force")
    assert p.returncode == 0, p.stderr
    warnings = [x for x in p.stderr.splitlines() if x.startswith("orthocontact: warning:")]
    said = "orthocontact: warning: --force: exporting a value that cannot be right (said in the FMUs' " \
           f"documentation/calibration.html and description): {path}: "
    assert len(warnings) == 2, p.stderr
    assert warnings[0] == said + ("eps1 = 1e+13 N/m: a contact's tangential stiffness is 10-1e9 N/m; "
                                  "none above 1e+12 N/m can be right")
    assert warnings[1].startswith(said + "eps_ratio = ")
    assert warnings[1].endswith("none above 1e+06 can be right")
    assert "Warning" not in p.stderr.replace("warning:", "")
    for v in (2, 3):
        doc, description = exported_notes(tmp_path / "o" / f"fmi{v}/OrthotropicContact.fmu")
        assert "<b>Exported with --force</b>" in doc
        assert "<li>error: " + html.escape(f"{path}: eps1 = 1e+13 N/m") in doc
        assert "Exported with --force despite the plausibility gate (2 finding(s)" in description
        assert f"error: {path}: eps1 = 1e+13 N/m" in description
        assert start_values_of(tmp_path / "o" / f"fmi{v}/OrthotropicContact.fmu")["eps1"] == 1e13


def test_export_refuses_an_elastic_length_the_rigs_travel_cannot_hold(identified, tmp_path):
    """eps1, eps2 = 12.59, 10.04 N/m (what a ramp in mm gave): each in its
    usual range, but mu N / eps = 0.59-1.15 m, more than the rig's 0.5 m of
    travel: the block could never have slid."""
    from cli_run import one_error_line
    path = edited(identified, tmp_path, eps1=12.59, eps2=10.04, eps_ratio=12.59 / 10.04)
    p = cli("export", path, "--out", tmp_path / "o")
    one_error_line(p, "the elastic length mu N / eps is 0.594 .. 1.14 m", "the rig's travel is 0.5 m",
                   "the block would stick over the whole travel", "N/mm",
                   "refused (`orthocontact export --force` exports it anyway)")


def exported_notes(fmu: Path) -> tuple:
    """(documentation/calibration.html, the model description's description
    attribute) of an exported FMU."""
    with zipfile.ZipFile(fmu) as z:
        return (z.read("documentation/calibration.html").decode(),
                ET.fromstring(z.read("modelDescription.xml")).get("description"))


# --- export is the last gate: a unit slip identify warns about is refused ----------------

def reduced_variant(folder: Path, rig=(), append="", ramp=None) -> Path:
    """The bundled reduced example in `folder` with rig.toml's text `old`
    replaced by `new` for each (old, new) of `rig`, `append` added to it,
    and ramp.csv's x1_m times `ramp` (None: as it is; 0: no ramp.csv)."""
    shutil.copytree(DATA, folder, ignore=shutil.ignore_patterns("README.md"))
    text = (folder / "rig.toml").read_text()
    for old, new in rig:
        assert old in text
        text = text.replace(old, new)
    (folder / "rig.toml").write_text(text + append)
    if ramp == 0:
        (folder / "ramp.csv").unlink()
    elif ramp is not None:
        lines = (folder / "ramp.csv").read_text().splitlines()
        rows = [f"{float(x) * ramp:.6g},{F}" for x, F in (ln.split(",") for ln in lines[1:])]
        (folder / "ramp.csv").write_text("\n".join([lines[0]] + rows) + "\n")
    return folder


def recordings_in_kn(folder: Path) -> Path:
    """A part of the bundled recordings (every carriage and ramp run, the
    slides at 0, 45 and 90 deg at 0.244 m/s, two each: 5 s to identify
    instead of 77 s) with every force log in kN: each ratio stays sane."""
    src = SCENARIOS / "example_recordings"
    (folder / "forces").mkdir(parents=True)
    (folder / "trajectories").mkdir()
    shutil.copy(src / "rig.toml", folder)
    lines = (src / "runs.csv").read_text().splitlines()
    runs = [lines[0]] + [ln for ln in lines[1:] if ln.split(",")[1] != "slide" or
                         re.fullmatch(r"a0(00|45|90)_v244_0[12],.*", ln)]
    (folder / "runs.csv").write_text("\n".join(runs) + "\n")
    for name in (ln.split(",")[0] for ln in runs[1:]):
        if (src / "trajectories" / f"{name}.csv").exists():
            shutil.copy(src / "trajectories" / f"{name}.csv", folder / "trajectories")
        shutil.copy(src / "forces" / f"{name}.csv", folder / "forces")
    assert scale_forces(folder, "*.csv", 1e-3) and len(runs) == 15
    return folder


def unsettled(rig: str, ramp: float, named: str, lengths: str) -> tuple:
    """A SLIPS case of a slip that keeps the rig from settling over 5 m of
    travel (`rig` more lines of rig.toml, ramp.csv's x1_m times `ramp`, 0:
    no ramp.csv): identify warns "would not settle; <named>", export
    refuses identified.json naming the elastic lengths ("<lengths> m")."""
    return (lambda d: reduced_variant(d, append="travel_m = 5.0\n" + rig, ramp=ramp),
            f"would not settle; {named}", "identified.json", f"the elastic length mu N / eps is {lengths} m")


# (the data set, what identify's warning says, the file export's refusal names, what it says)
SLIPS = {
    "mm": unsettled("", 1e3, "ramp.csv's x1_m in mm?", "0.594 .. 1.14"),
    "cm/s": (lambda d: reduced_variant(d, rig=[("velocity_m_s = 0.244", "velocity_m_s = 12.5")]),
             "rig.toml: velocity_m_s = 12.5 m/s: a lab rig's carriage moves at 0.001-2 m/s; cm/s?",
             "rig.toml", "velocity_m_s = 12.5 m/s: a lab rig's carriage moves at 0.001-2 m/s; cm/s?"),
    "kN": (recordings_in_kn, "(m g = 18.39 N, F_int = 0.00498 N): all below the usual 0.01-3 of a "
                             "friction coefficient, and 1000 times each within it; forces in kN?",
           "identified.json", "mu1, mu2 = 0.000408 .. 0.000626 (F_int = 0.00498 N)"),
    "N/mm": unsettled("eps2_nominal_N_m = 10.0\n", 0, "rig.toml's eps2_nominal_N_m in N/mm?",
                      "0.596 .. 1.15"),
    "rad": (lambda d: reduced_variant(d, rig=[("alpha_offset_deg = 90.0", "alpha_offset_deg = 1.5708")]),
            "rig.toml: alpha_offset_deg = 1.5708: looks like pi/2 in radians",
            "identified.json", "assumptions.alpha_offset_deg = 1.5708: looks like pi/2 in radians"),
}
SLIP_NAMED = {"mm": "x1_m in mm", "cm/s": "cm/s?", "kN": "forces in kN?", "N/mm": "in N/mm?",
              "rad": "in radians"}


@pytest.mark.parametrize("slip", list(SLIPS), ids=[s.replace("/", "_") for s in SLIPS])
def test_a_unit_slip_identify_warns_about_is_refused_by_export_unless_forced(tmp_path, slip):
    """Each unit slip the plausibility gate names (positions in mm, a
    velocity in cm/s, forces in kN, a stiffness in N/mm, an angle in rad),
    in a data set identify takes with a warning: export refuses it (one
    line naming the slip and --force, nothing written); with --force it
    exports, says so, and both FMUs' documentation and model description
    carry the warning.  Before, export wrote the FMUs with exit 0: for the
    bundled recordings in kN, mu1 = 0.000409 and eps2 = 9.96 N/m."""
    build, identify_says, source, export_says = SLIPS[slip]
    named = SLIP_NAMED[slip]
    data = build(tmp_path / "data")
    p = cli("identify", data, "--out", tmp_path / "id", "--no-validate")
    assert p.returncode == 0, p.stderr
    said = [x for x in p.stderr.splitlines() if identify_says in x]
    assert len(said) == 1 and said[0].startswith("orthocontact: warning: ") and named in said[0], p.stderr
    identified = tmp_path / "id" / "identified.json"
    finding = f"{identified if source == 'identified.json' else data / source}: {export_says}"
    p = cli("export", identified, "--out", tmp_path / "refused")
    one_error_line(p, f"orthocontact: error: {finding}", named,
                   "; refused (`orthocontact export --force` exports it anyway)")
    assert not (tmp_path / "refused").exists()
    finding = p.stderr.strip()[len("orthocontact: error: "):].split("; refused (`orthocontact export")[0]
    p = cli("export", identified, "--out", tmp_path / "forced", "--force")
    assert p.returncode == 0, p.stderr
    assert ("orthocontact: warning: --force: exporting an unusual value (said in the FMUs' "
            f"documentation/calibration.html and description): {finding}") in p.stderr.splitlines()
    for v in (2, 3):
        doc, description = exported_notes(tmp_path / "forced" / f"fmi{v}/OrthotropicContact.fmu")
        assert f"<li>warning: {html.escape(finding)}</li>" in doc
        assert f"warning: {finding}" in description and "Exported with --force despite" in description
