"""Each subpackage has a door: its __init__.py exports its public names
(`__all__`), and the other subpackages import through it (`from ..fmu import
find_fmu`), not from its modules (`from ..fmu.files import find_fmu`), so a
module can move or split inside its subpackage without its importers
knowing.  The few imports that still reach into another subpackage's modules
are listed in REACH_INS, each with why; one not listed fails here.  No
subpackage imports a name the package's root defines (the root re-exports;
`__version__` is orthocontact.version's).  And the doors stay light:
`orthocontact --help` imports none of casadi, matplotlib, dask, fmpy."""
from __future__ import annotations

import ast
import importlib
import subprocess
import sys

from paths import PKG

# (importing module, module of another subpackage it reaches) -> why.
REACH_INS = {
    ("cli.commands", "reproduction.sensitivity"):
        "the study's steps read as sensitivity.takes, .plan, .work, .run, .write_outputs: as names of "
        "reproduction's door they would be the whole reproduction's",
    ("cli.commands", "identification.job"):
        "imported as `identify`: identify.load_folder, .run, .summary_text, .validation_work; run and "
        "summary_text are design_output's verbs too",
    ("cli.commands", "identification.design"):
        "the design's own verbs, design.plan, .Space, .angles_of, .velocities_of, not identification's",
    ("cli.commands", "identification.design_output"):
        "design_output.write_outputs and .summary_text: the job's and uq's verbs too",
    ("reproduction.planar_outputs", "rig.planar"):
        "the planar body's model, read as planar.twist, .towed_block, .PlanarBody, .steady_yaw: rig's "
        "door is the carriage rig's",
    ("reproduction.pushed_outputs", "rig.pushed"):
        "the pushed block's model, read as pushed.push, .PushedBlock, .PushNotSolved, .FIT_FROM, "
        ".MAX_TILT_RAD",
}
MOST_REACH_INS = 20
HEAVY = ("casadi", "matplotlib", "dask", "distributed", "fmpy")


def package_modules(pkg=PKG) -> dict:
    """Every module of the package by dotted name under it (a subpackage by
    its own name: its door; the root's __init__ as "") -> whether it is a
    package."""
    found = {}
    for p in pkg.rglob("*.py"):
        parts = list(p.relative_to(pkg).with_suffix("").parts)
        if parts[-1] == "__init__":
            found[".".join(parts[:-1])] = True
        else:
            found[".".join(parts)] = False
    return found


def subpackage_of(module: str, modules: dict) -> str | None:
    """The subpackage a module belongs to, or None for the root's own modules."""
    top = module.split(".")[0]
    return top if top and modules.get(top) else None


def imported(source: str, module: str, modules: dict) -> list:
    """The package modules each import of `source` (the module `module`)
    names: (line, module imported from, names it imports)."""
    base = module.split(".") if modules[module] else module.split(".")[:-1]
    base = [b for b in base if b]
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                up = base[:len(base) - (node.level - 1)] if node.level > 1 else base
                target = up + (node.module.split(".") if node.module else [])
            elif (node.module or "").split(".")[0] == "orthocontact":
                target = node.module.split(".")[1:]
            else:
                continue
            found.append((node.lineno, ".".join(target), [a.name for a in node.names]))
        elif isinstance(node, ast.Import):
            found += [(node.lineno, a.name.split(".", 1)[1], []) for a in node.names
                      if a.name.startswith("orthocontact.")]
    return found


def reach_ins(source: str, module: str, modules: dict) -> list:
    """The imports in `source` (the module `module`) that reach into a module
    of another subpackage: (line, that module), whether by its path
    (`from ..fmu.files import find_fmu`) or through the door (`from ..rig
    import planar`)."""
    own = subpackage_of(module, modules)
    found = []
    for line, target, names in imported(source, module, modules):
        other = subpackage_of(target, modules)
        if other is None or other == own:
            continue
        if target in modules and not modules[target]:
            found.append((line, target))
        elif modules.get(target):
            found += [(line, f"{target}.{n}") for n in names if f"{target}.{n}" in modules]
    return found


def all_reach_ins() -> list:
    modules = package_modules()
    found = []
    for p in sorted(PKG.rglob("*.py")):
        parts = list(p.relative_to(PKG).with_suffix("").parts)
        module = ".".join(parts[:-1]) if parts[-1] == "__init__" else ".".join(parts)
        found += [(module, line, target) for line, target in reach_ins(p.read_text(), module, modules)]
    return found


def test_only_the_listed_imports_reach_into_another_subpackages_modules():
    found = all_reach_ins()
    unlisted = [f"{m}:{line} imports {t}" for m, line, t in found if (m, t) not in REACH_INS]
    assert unlisted == [], "import through the door (`from ..sub import name`), or list it in REACH_INS"
    assert {(m, t) for m, _, t in found} == set(REACH_INS), "a listed reach-in that is gone: unlist it"
    assert len(found) <= MOST_REACH_INS


def test_the_reach_in_finder_sees_a_module_by_its_path_or_through_the_door():
    modules = {"": True, "errors": False, "fmu": True, "fmu.files": False, "fmu.params": False,
               "rig": True, "rig.harness": False, "rig.planar": False}
    assert reach_ins("from ..fmu.files import find_fmu\nfrom ..fmu import ContactParams\n",
                     "rig.harness", modules) == [(1, "fmu.files")]
    assert reach_ins("from ..rig import Rig, planar\n", "fmu.params", modules) == [(1, "rig.planar")]
    assert reach_ins("def f():\n    import orthocontact.fmu.params\n", "rig.harness", modules) == \
        [(2, "fmu.params")]
    assert reach_ins("from orthocontact.fmu.files import x\n", "rig.harness", modules) == [(1, "fmu.files")]
    assert reach_ins("from .experiment.scenario import load\n", "", {**modules, "experiment": True,
                                                                     "experiment.scenario": False}) == \
        [(1, "experiment.scenario")]
    # its own subpackage's modules, the layers' bottom modules and the doors are no reach-ins
    assert reach_ins("from .files import find_fmu\nfrom ..errors import InputError\n"
                     "from .. import rig\nfrom ..rig import Rig\n", "fmu.params", modules) == []


def doors() -> list:
    return sorted(m for m, is_package in package_modules().items() if is_package and m)


def test_every_door_exports_its_names_and_each_is_there():
    for name in doors():
        door = importlib.import_module(f"orthocontact.{name}")
        exported = getattr(door, "__all__", None)
        assert exported, f"orthocontact.{name}: its __init__.py names no __all__"
        assert len(set(exported)) == len(exported), name
        missing = [n for n in exported if not hasattr(door, n)]
        assert missing == [], f"orthocontact.{name}.__all__ names what it does not have: {missing}"


def test_what_a_subpackage_imports_through_anothers_door_is_in_its_all():
    modules = package_modules()
    exports = {name: set(importlib.import_module(f"orthocontact.{name}").__all__) for name in doors()}
    outside = []
    for p in sorted(PKG.rglob("*.py")):
        parts = list(p.relative_to(PKG).with_suffix("").parts)
        module = ".".join(parts[:-1]) if parts[-1] == "__init__" else ".".join(parts)
        own = subpackage_of(module, modules)
        for line, target, names in imported(p.read_text(), module, modules):
            if modules.get(target) and target and target != own:
                outside += [f"{module}:{line} {target}.{n}" for n in names
                            if n not in exports[target] and f"{target}.{n}" not in modules]
    assert outside == []


def test_no_subpackage_imports_a_name_the_root_defines():
    """`from .. import X` in a subpackage names a subpackage or one of the
    root's modules (errors, version, ...), never what the root's __init__
    itself defines or re-exports (it imports the subpackages: a name read from
    above every layer)."""
    modules = package_modules()
    found = []
    for p in sorted(PKG.rglob("*.py")):
        parts = list(p.relative_to(PKG).with_suffix("").parts)
        module = ".".join(parts[:-1]) if parts[-1] == "__init__" else ".".join(parts)
        if subpackage_of(module, modules) is None:
            continue
        for line, target, names in imported(p.read_text(), module, modules):
            if target == "":
                found += [f"{module}:{line} {n}" for n in names if n not in modules]
    assert found == []


def test_help_imports_no_heavy_library():
    """The doors import their modules at once; none of them may import a
    heavy library at import time (each imports it where it is used)."""
    code = ("import sys\nfrom orthocontact.cli import main\n"
            "try:\n    main(['--help'])\nexcept SystemExit:\n    pass\n"
            f"print('heavy:', *(m for m in {HEAVY!r} if m in sys.modules), file=sys.stderr)")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0 and "usage: orthocontact" in p.stdout, p.stderr
    assert p.stderr.splitlines()[-1] == "heavy:", p.stderr
