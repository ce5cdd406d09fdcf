"""The binaries for every desktop platform, cross-built with zig: the right
format and architecture, every FMI function exported, Linux ones needing no
glibc newer than 2.17, and the aarch64 Linux one run under qemu-user."""
import math
import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import fmpy
import numpy as np
import pytest

import binformat
from orthocontact.fmu.contact import ContactFMU
from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.params import ContactParams
from paths import C_FIXTURES, ROOT

HEADERS = Path(fmpy.__file__).parent / "c-code"
PLATFORMS = {
    2: {"linux64": ("ELF", "x86_64", "so"), "win64": ("PE", "x86_64", "dll"),
        "darwin64": ("Mach-O", "x86_64", "dylib")},
    3: {"x86_64-linux": ("ELF", "x86_64", "so"), "aarch64-linux": ("ELF", "aarch64", "so"),
        "x86_64-windows": ("PE", "x86_64", "dll"), "x86_64-darwin": ("Mach-O", "x86_64", "dylib"),
        "aarch64-darwin": ("Mach-O", "aarch64", "dylib")},
}
CASES = [(v, p) for v in PLATFORMS for p in PLATFORMS[v]]


def fmi_functions(version):
    header = (HEADERS / f"fmi{version}Functions.h").read_text()
    return set(re.findall(rf"FMI{version}_Export\s+\w+TYPE\s+(fmi{version}\w+)\s*;", header))


@pytest.mark.parametrize("version,platform", CASES, ids=[f"fmi{v}-{p}" for v, p in CASES])
def test_binary_format_architecture_and_exports(version, platform):
    fmt, arch, ext = PLATFORMS[version][platform]
    data = zipfile.ZipFile(find_fmu(fmi_version=version)).read(
        f"binaries/{platform}/OrthotropicContact.{ext}")
    b = binformat.read(data)
    assert (b.format, b.arch) == (fmt, arch)
    assert fmi_functions(version) <= b.exports
    leaked = {e for e in b.exports if e.startswith(("oc_", "fmu_"))}
    assert not leaked  # the core and the shared glue stay internal
    if fmt == "ELF":
        newest = max(tuple(int(x) for x in v.split(".")) for v in b.glibc_needed)
        assert newest <= (2, 17), f"needs GLIBC_{'.'.join(map(str, newest))}"


@pytest.mark.needs("qemu-aarch64")
def test_aarch64_linux_binary_runs_under_qemu_like_the_x86_64_one(tmp_path):
    qemu, sysroot = shutil.which("qemu-aarch64"), Path("/usr/aarch64-linux-gnu")
    fmu = find_fmu(fmi_version=3)
    z = zipfile.ZipFile(fmu)
    so = tmp_path / "OrthotropicContact.so"
    so.write_bytes(z.read("binaries/aarch64-linux/OrthotropicContact.so"))
    driver = tmp_path / "fmu_run"
    subprocess.run([sys.executable, "-m", "ziglang", "cc", "-target", "aarch64-linux-gnu.2.17",
                    "-O1", "-I", str(HEADERS), str(C_FIXTURES / "fmu_run.c"), "-ldl", "-o",
                    str(driver)], check=True, capture_output=True, timeout=300,
                   cwd=tmp_path)   # outside the checkout: zig finds the runtime the FMU build cached
    from fmpy import read_model_description
    token = read_model_description(str(fmu)).guid
    h, n = 1e-3, 400
    rows = [(k * h, 3e-5 * k, 1e-5 * k * math.sin(0.02 * k), 18.39 if k % 150 < 130 else 0.0)
            for k in range(n + 1)]
    csv_in = tmp_path / "in.csv"
    csv_in.write_text("".join(f"{t!r},{a!r},{b!r},{c!r}\n" for t, a, b, c in rows))
    proc = subprocess.run([qemu, "-L", str(sysroot), str(driver), str(so), token, str(csv_in)],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    arm = np.array([[float(x) for x in line.split(",")] for line in proc.stdout.split()])
    assert arm.shape == (n, 7)
    # The same path through fmpy on the x86_64 binary.
    with ContactFMU(fmu, instance_name="x86") as f:
        f.initialize(ContactParams(0.408, 0.625, 12510.0, 1e4, math.pi / 2, 0.0))  # defaults
        ref = []
        for _t, a, b, c in rows[:-1]:
            f.set_inputs(a, b, c)
            f.do_step(h)
            o = f.outputs()
            ref.append([o[k] for k in ("T1", "T2", "s1", "s2", "dissipatedEnergy", "contactState")])
    ref = np.array(ref)
    assert set(ref[:, 5]) == {0, 1, 2}
    np.testing.assert_array_equal(arm[:, 6], ref[:, 5])
    # Both are built without FMA contraction (-ffp-contract=off) and use only
    # IEEE-exact operations on the hot path; measured: bit for bit the same.
    np.testing.assert_array_equal(arm[:, 1:6], ref[:, :5])


def _builder_paths():
    """Absolute paths of this build machine, as bytes: the repository, the home
    and temporary folders, the Python environment, and the usual roots of
    build machines on any system."""
    import tempfile
    mine = {str(ROOT), str(Path.home()), tempfile.gettempdir(), sys.prefix}
    generic = {"/root/", "/home/", "/tmp/", "/work/", "/Users/", "/private/var/"}
    return sorted(p.encode() for p in mine | generic if len(p) > 1)


def test_no_builder_path_in_any_binary():
    """A shipped binary names nothing of the machine that built it (the macOS
    ones would carry their output path as install name otherwise)."""
    drive = re.compile(rb"[A-Za-z]:\\[\x20-\x7e]")   # a Windows absolute path
    checked = 0
    from orthocontact.fmu.variables import models
    for model in models().values():
        for version in (2, 3):
            z = zipfile.ZipFile(find_fmu(fmi_version=version, model=model))
            for name in z.namelist():
                if not name.startswith("binaries/") or name.endswith("/"):
                    continue
                data = z.read(name)
                found = [p for p in _builder_paths() if p in data] + drive.findall(data)
                assert not found, f"{model} FMI {version}.0 {name} contains {found}"
                b = binformat.read(data)
                if b.format == "Mach-O":
                    assert b.install_name == f"@rpath/{model}.dylib", name
                checked += 1
    assert checked == len(models()) * sum(len(PLATFORMS[v]) for v in PLATFORMS)  # every platform and model
