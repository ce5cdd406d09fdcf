"""The cells of an FMI 2.0 run from its FMI 3.0 twin
(orthocontact.reproduction.fmi3_twin): taken only from an installed FMU
whose run is this one; otherwise none, and why."""
from orthocontact.fmu import PAD_MODEL, find_fmu
from orthocontact.reproduction.fmi3_twin import fmi3_twin


def test_the_twins_result_is_taken_when_its_run_is_this_one():
    got, why = fmi3_twin(PAD_MODEL, lambda twin: ("ran", twin), lambda again: True, "push")
    assert got == ("ran", find_fmu(fmi_version=3, model=PAD_MODEL))
    assert why == ("the same push on the installed FMI 3.0 ContactPad FMU, equal to this run at every step "
                   "(FMI 2.0 has no arrays)")


def test_a_twin_whose_run_differs_gives_no_cells_and_says_what_differed():
    got, why = fmi3_twin(PAD_MODEL, lambda twin: "other", lambda again: False, "twist", differs="torque")
    assert got is None and "does not give this FMU's torque bit for bit" in why


def test_no_installed_twin_gives_no_cells_and_says_so():
    ran = []
    got, why = fmi3_twin("NoSuchModel", ran.append, lambda again: True, "push")
    assert got is None and ran == [] and "no FMI 3.0 NoSuchModel FMU is installed" in why
