"""One version: the file VERSION is what the package's metadata,
orthocontact.__version__, every model's FMUs (their model descriptions and
documentation), the repository's copies of the descriptions, the cross-check
folder and `orthocontact --version` say; and the GUID / instantiationToken
changes whenever a model description does."""
import re
import shutil
import subprocess
import sys
import zipfile
from importlib.metadata import version as installed_version
from pathlib import Path
from xml.etree import ElementTree

from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.variables import models
from paths import PKG, ROOT

VERSION = (ROOT / "VERSION").read_text().strip()
MODELS = tuple(models().values())


def _attr(xml: str, name: str) -> str:
    """An attribute of the root element, fmiModelDescription."""
    return ElementTree.fromstring(xml.encode()).get(name)


def test_version_file_holds_one_version_and_nothing_else_states_one():
    assert re.fullmatch(r"\d+\.\d+\.\d+", VERSION)
    pyproject = (ROOT / "pyproject.toml").read_text()
    assert re.search(r'^dynamic = \["version"\]', pyproject, re.M)
    assert not re.search(r"^version\s*=", pyproject, re.M)   # no second, static version
    assert re.search(r'^input = "VERSION"', pyproject, re.M)
    cmake = (ROOT / "CMakeLists.txt").read_text()
    assert "project(orthocontact VERSION ${OC_VERSION}" in cmake
    for module in ("__init__.py", "version.py"):
        assert not re.search(r'__version__\s*=\s*["\']', (PKG / module).read_text()), module


def test_package_fmus_documentation_crosscheck_and_cli_agree():
    import orthocontact
    assert orthocontact.__version__ == VERSION
    assert installed_version("orthocontact") == VERSION  # a stale install fails here
    for model in MODELS:
        for v in (2, 3):
            z = zipfile.ZipFile(find_fmu(fmi_version=v, model=model))
            md = z.read("modelDescription.xml").decode()
            assert _attr(md, "version") == VERSION, (model, v)
            assert f"<h1>{model} {VERSION}: FMI {v}.0 Co-Simulation</h1>" in \
                z.read("documentation/index.html").decode()
    for copy in ("modelDescription.xml", "modelDescription-fmi3.xml"):
        assert _attr((ROOT / copy).read_text(), "version") == VERSION, copy
    for fmi, platform in (("2.0", "linux64"), ("3.0", "x86_64-linux")):
        base = ROOT / "cross-check" / "fmus" / fmi / "cs" / platform / "orthocontact"
        assert sorted(p.name for p in base.iterdir()) == [VERSION], "one folder, of this version"
        assert sorted(p.name for p in (base / VERSION).iterdir()) == sorted(MODELS), "one folder a model"
        for model in MODELS:
            readme = (base / VERSION / model / "README.md").read_text()
            assert f"from orthocontact {VERSION}." in readme, (fmi, model)
    out = subprocess.run([sys.executable, "-m", "orthocontact", "--version"], capture_output=True,
                         text=True, timeout=60, check=True).stdout.splitlines()
    assert out[0] == f"orthocontact {VERSION}"
    listed = sorted(re.fullmatch(r"  FMI (\d)\.0 FMU: (\w+) (\S+) \(.*\)", line).groups()
                    for line in out[1:])
    assert listed == sorted((str(v), m, VERSION) for m in MODELS for v in (2, 3))


# -- the token --------------------------------------------------------------------

def _compiler():
    cc = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if cc:
        return [cc]
    return [sys.executable, "-m", "ziglang", "cc"]   # the package's build requirement


CONTACT_TABLE = "models/OrthotropicContact/table.h"   # under fmu_src/


def _token(tmp, fmu_src: Path, table: str, version: str) -> tuple[str, str]:
    """gen_model_description built on `fmu_src` for `table` and `version`:
    (the token it computes, the FMI 2.0 description it writes)."""
    gen = tmp / f"gen{len(list(tmp.glob('gen*')))}"
    subprocess.run(_compiler() + ["-std=c99", "-I", str(fmu_src),
                                  f'-DFMU_TABLE_HEADER="{table}"', f'-DFMU_VERSION="{version}"',
                                  *map(str, sorted((fmu_src / "glue").glob("gen_model_description*.c"))),
                                  "-o", str(gen), "-lm"],
                   check=True, capture_output=True, timeout=120)
    header = subprocess.run([str(gen), "token"], check=True, capture_output=True, text=True).stdout
    xml = subprocess.run([str(gen), "fmi2"], check=True, capture_output=True, text=True).stdout
    return re.search(r'#define FMU_TOKEN "(\{[0-9a-f-]+\})"', header).group(1), xml


def test_token_is_the_descriptions_and_changes_with_them(tmp_path):
    src = tmp_path / "fmu_src"
    shutil.copytree(ROOT / "fmu_src", src)
    token, xml = _token(tmp_path, src, CONTACT_TABLE, VERSION)
    for v in (2, 3):
        md = zipfile.ZipFile(find_fmu(fmi_version=v)).read("modelDescription.xml").decode()
        assert _attr(md, "guid" if v == 2 else "instantiationToken") == token
    assert xml == zipfile.ZipFile(find_fmu(fmi_version=2)).read("modelDescription.xml").decode()

    rig_token, _ = _token(tmp_path, src, "models/CarriageBlock/table.h", VERSION)
    other_version, _ = _token(tmp_path, src, CONTACT_TABLE, VERSION + "1")
    table = (src / CONTACT_TABLE).read_text()
    # One attribute of the description changed by one character: the model's description.
    edited = table.replace("by an implicit", "by an Implicit", 1)
    assert edited != table
    (src / CONTACT_TABLE).write_text(edited)
    other_description, other_xml = _token(tmp_path, src, CONTACT_TABLE, VERSION)
    assert other_xml.replace(other_description, token) != xml   # the description did change
    assert len({token, rig_token, other_version, other_description}) == 4
