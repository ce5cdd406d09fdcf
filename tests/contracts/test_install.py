"""Installs of every kind: an editable install (`pip install -e .`) in a fresh
virtual environment finds the FMUs it built and runs `orthocontact run` end to
end; a missing FMU is one clear line, never a traceback."""
import os
import subprocess
import sys
from pathlib import Path

from paths import PKG, ROOT, SCENARIOS


def _sh(cmd, **kw):
    p = subprocess.run(cmd, capture_output=True, text=True, **kw)
    assert p.returncode == 0, f"{cmd}\n{p.stdout[-3000:]}\n{p.stderr[-3000:]}"
    return p


def test_editable_install_finds_its_fmus_and_runs(tmp_path):
    venv = tmp_path / "venv"
    _sh([sys.executable, "-m", "venv", str(venv)])
    py = venv / "bin" / "python"
    pip = [str(py), "-m", "pip", "install", "-q", "--disable-pip-version-check"]
    # The build requirements and dependencies are this environment's, seen
    # through a .pth file (installing casadi, numpy and matplotlib afresh took
    # most of a minute); the package itself in editable mode, in the new
    # environment, whose site-packages come first.  Host binaries only
    # (OC_CROSS=OFF), unoptimised (Debug builds faster): what is
    # tested is where an editable install finds its FMUs, not the cross build
    # or the optimiser; a build folder of its own.
    site = _sh([str(py), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"]).stdout.strip()
    shared = _sh([sys.executable, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"]).stdout
    (Path(site) / "zz_shared_dependencies.pth").write_text(shared)
    _sh(pip + ["--no-build-isolation", "--no-deps", "-e", str(ROOT),
               "-Cbuild-dir=build/editable-test", "-Ccmake.define.OC_CROSS=OFF", "-Ccmake.build-type=Debug"],
        timeout=900)
    probe = _sh([str(py), "-c", "import orthocontact, orthocontact.fmu as f; "
                 "print(orthocontact.__file__); print(f.find_fmu()); print(f.find_fmu(fmi_version=3))"],
                cwd=tmp_path).stdout.splitlines()
    assert probe[0] == str(PKG / "__init__.py")  # editable: the source
    assert all(Path(x).is_file() for x in probe[1:3])
    sc = tmp_path / "quick.toml"
    sc.write_text((SCENARIOS / "case4.toml").read_text()
                  .replace("step_deg = 1.0", "step_deg = 30.0").replace("travel_m = 0.2", "travel_m = 0.02"))
    for fmi in ("2", "3"):
        _sh([str(venv / "bin" / "orthocontact"), "run", str(sc), "--out", str(tmp_path / f"out{fmi}"),
             "--fmi", fmi, "--workers", "2"], cwd=tmp_path, timeout=300)
        assert (tmp_path / f"out{fmi}" / "summary.json").is_file()


def test_missing_fmu_is_one_line_not_a_traceback(tmp_path):
    env = dict(os.environ, ORTHOCONTACT_FMU=str(tmp_path / "nowhere.fmu"))
    p = subprocess.run([sys.executable, "-m", "orthocontact", "run", str(SCENARIOS / "case4.toml"),
                        "--out", str(tmp_path / "out")], capture_output=True, text=True, env=env,
                       timeout=120)
    assert p.returncode == 2
    assert p.stderr.strip() == \
        f"orthocontact: error: FMU not found: {tmp_path / 'nowhere.fmu'} ($ORTHOCONTACT_FMU)"
    assert not (tmp_path / "out").exists()


def test_license_in_the_repo_the_package_and_both_fmus():
    import zipfile
    from importlib.metadata import metadata

    from orthocontact.fmu.files import find_fmu
    text = (ROOT / "LICENSE").read_text()
    assert text.startswith("BSD 2-Clause License")
    assert "BSD-2-Clause" in (ROOT / "pyproject.toml").read_text()
    meta = metadata("orthocontact")
    assert "BSD-2-Clause" in (meta.get("License") or meta.get("License-Expression") or "")
    for v, member in ((2, "documentation/LICENSE.txt"), (3, "documentation/licenses/LICENSE.txt")):
        z = zipfile.ZipFile(find_fmu(fmi_version=v))
        assert z.read(member).decode() == text
        md = z.read("modelDescription.xml").decode()
        assert 'license="BSD-2-Clause' in md and 'copyright="Copyright' in md and 'author="' in md
        assert "BSD 2-Clause License" in z.read("documentation/index.html").decode() or \
            "BSD-2-Clause" in z.read("documentation/index.html").decode()
