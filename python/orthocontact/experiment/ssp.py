"""The experiment as a system of FMUs: an SSP 1.0 package (System Structure &
Parameterization) coupling the CarriageBlock rig FMU with the
OrthotropicContact FMU at one mat/axis angle of a scenario.

The package holds SystemStructure.ssd and both FMUs (FMI 2.0) under
resources/; the scenario's values are bound as inline parameter sets, and
the FMUs inside carry the same values as their own start values
(fmu.start_values), so that an importer that ignores the bindings (fmpy's
SSP reader, fmu-manipulation-toolbox's container) still runs the scenario,
not the FMUs' defaults.  The step
size is given both as the SSP default experiment's OSP annotation (libcosim's
fixed-step algorithm) and as the scenario's communication step.

Units: angles in degrees at this interface (as in scenario files), the FMUs'
own units inside (rad, N/m, kg, m/s, N)."""
from __future__ import annotations

import math
import zipfile
from pathlib import Path

from ..fmu import MODEL_IDENTIFIER, RIG_MODEL_IDENTIFIER, find_fmu, write_with_start_values
from ..runtime import locked_folder
from .scenario import Scenario

NS = ('xmlns:ssd="http://ssp-standard.org/SSP1/SystemStructureDescription" '
      'xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon" '
      'xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues" '
      'xmlns:osp="http://opensimulationplatform.com/SSP/OSPAnnotations"')


RIG_CONNECTORS = (("T1", "input"), ("T2", "input"), ("u1", "output"), ("u2", "output"),
                  ("N", "output"), ("x1", "output"), ("x2", "output"), ("driveForce", "output"))


CONTACT_CONNECTORS = (("u1", "input"), ("u2", "input"), ("N", "input"), ("T1", "output"),
                      ("T2", "output"), ("s1", "output"), ("s2", "output"),
                      ("dissipatedEnergy", "output"))


CONNECTIONS = (("rig", "u1", "contact", "u1"), ("rig", "u2", "contact", "u2"),
               ("rig", "N", "contact", "N"), ("contact", "T1", "rig", "T1"),
               ("contact", "T2", "rig", "T2"))


# One name for the parameter sets of both components: Ecos applies the sets
# of the name it is given at initialization, so differently named sets
# reached only one of the two FMUs.
PARAMETER_SET = "scenario"


def _fmt(x: float) -> str:
    return repr(float(x))


def _component(name, source, connectors, reals, integers=()):
    lines = [f'      <ssd:Component name="{name}" source="{source}" '
             f'type="application/x-fmu-sharedlibrary">', "        <ssd:Connectors>"]
    for c, kind in connectors:
        lines.append(f'          <ssd:Connector name="{c}" kind="{kind}"><ssc:Real/></ssd:Connector>')
    lines += ["        </ssd:Connectors>", "        <ssd:ParameterBindings>",
              "          <ssd:ParameterBinding>", "            <ssd:ParameterValues>",
              f'              <ssv:ParameterSet version="1.0" name="{PARAMETER_SET}">',
              "                <ssv:Parameters>"]
    for k, v in reals:
        lines.append(f'                  <ssv:Parameter name="{k}">'
                     f'<ssv:Real value="{_fmt(v)}"/></ssv:Parameter>')
    for k, v in integers:
        lines.append(f'                  <ssv:Parameter name="{k}">'
                     f'<ssv:Integer value="{int(v)}"/></ssv:Parameter>')
    lines += ["                </ssv:Parameters>", "              </ssv:ParameterSet>",
              "            </ssd:ParameterValues>", "          </ssd:ParameterBinding>",
              "        </ssd:ParameterBindings>", "      </ssd:Component>"]
    return lines


def parameter_values_file(values: dict, name: str, description: str = "") -> str:
    """An SSP parameter values file (.ssv) of one FMU's parameters (floats as
    Real, ints as Integer), for tools that apply such a file to a component."""
    from xml.sax.saxutils import quoteattr  # here, not at the start: it imports urllib.request (25 ms)
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             '<ssv:ParameterSet xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues" '
             f'version="1.0" name={quoteattr(name)}'
             + (f" description={quoteattr(description)}" if description else "") + ">",
             "  <ssv:Parameters>"]
    for k, v in values.items():
        value = (f'<ssv:Real value="{_fmt(v)}"/>' if isinstance(v, float)
                 else f'<ssv:Integer value="{int(v)}"/>')
        lines.append(f'    <ssv:Parameter name={quoteattr(k)}>{value}</ssv:Parameter>')
    lines += ["  </ssv:Parameters>", "</ssv:ParameterSet>", ""]
    return "\n".join(lines)


def rig_values(sc: Scenario) -> dict:
    """The CarriageBlock FMU's parameters for the scenario's rig."""
    rig = sc.rig
    values = {"mass": rig.mass_kg, "g": rig.g, "fInt": rig.f_int_N, "velocity": rig.velocity_m_s,
              "muStrip": rig.mu_strip, "cStrip": rig.c_strip}
    return {k: float(v) for k, v in values.items()}


def contact_values(sc: Scenario, angle_deg: float) -> dict:
    """The OrthotropicContact FMU's parameters at the mat angle [deg]
    (floats; slidingRule an int)."""
    return sc.params_at(angle_deg).fmu_values()


def _split(values: dict):
    reals = [(k, float(v)) for k, v in values.items() if isinstance(v, float)]
    return reals, [(k, v) for k, v in values.items() if not isinstance(v, float)]


def system_structure(sc: Scenario, angle_deg: float) -> str:
    """SystemStructure.ssd for the scenario at the mat angle [deg]."""
    from xml.sax.saxutils import quoteattr  # as parameter_values_file
    rig = sc.rig
    stop = rig.travel_m / rig.velocity_m_s
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             f'<ssd:SystemStructureDescription {NS} version="1.0" '
             f'name={quoteattr(f"{sc.name} at {angle_deg:g} deg")}>',
             f'  <ssd:System name="experiment" description={quoteattr(sc.title)}>',
             "    <ssd:Elements>"]
    lines += _component("rig", f"resources/{RIG_MODEL_IDENTIFIER}.fmu", RIG_CONNECTORS,
                        *_split(rig_values(sc)))
    lines += _component("contact", f"resources/{MODEL_IDENTIFIER}.fmu", CONTACT_CONNECTORS,
                        *_split(contact_values(sc, angle_deg)))
    lines += ["    </ssd:Elements>", "    <ssd:Connections>"]
    for a, ca, b, cb in CONNECTIONS:
        lines.append(f'      <ssd:Connection startElement="{a}" startConnector="{ca}" '
                     f'endElement="{b}" endConnector="{cb}"/>')
    lines += ["    </ssd:Connections>", "  </ssd:System>",
              f'  <ssd:DefaultExperiment startTime="0" stopTime="{_fmt(stop)}">',
              "    <ssd:Annotations>",
              '      <ssc:Annotation type="com.opensimulationplatform">',
              f'        <osp:Algorithm><osp:FixedStepAlgorithm baseStepSize="{_fmt(rig.step_s)}"/>'
              "</osp:Algorithm>",
              "      </ssc:Annotation>", "    </ssd:Annotations>", "  </ssd:DefaultExperiment>",
              "</ssd:SystemStructureDescription>", ""]
    return "\n".join(lines)


def write_ssp(sc: Scenario, angle_deg: float, out: Path, contact_fmu=None) -> Path:
    """Writes the .ssp (a zip) with both FMI 2.0 FMUs under resources/, each
    carrying the scenario's values as its start values.  contact_fmu: the
    contact FMU to put in (default: the scenario's, else the installed one);
    its other parameters' start values stay as they are."""
    if not math.isfinite(angle_deg):
        raise ValueError(f"angle must be finite, got {angle_deg!r}")
    out = Path(out)
    contact = Path(contact_fmu or sc.fmu or find_fmu(fmi_version=2))
    rig = find_fmu(fmi_version=2, model=RIG_MODEL_IDENTIFIER)
    # The FMUs and the package are made in a locked folder beside `out`
    # (runtime.folders): the package takes its name by a rename, and what a killed
    # run left there goes with the next package written to `out`.
    work = locked_folder(out.parent, f".{out.name}.partial-")
    try:
        contact = write_with_start_values(contact, work.path / "contact.fmu", contact_values(sc, angle_deg))
        rig = write_with_start_values(rig, work.path / "rig.fmu", rig_values(sc))
        tmp = work.path / out.name
        with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
            z.writestr("SystemStructure.ssd", system_structure(sc, angle_deg))
            z.write(contact, f"resources/{MODEL_IDENTIFIER}.fmu")
            z.write(rig, f"resources/{RIG_MODEL_IDENTIFIER}.fmu")
        tmp.replace(out)
    finally:
        work.remove()
    return out
