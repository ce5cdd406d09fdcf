"""report.md and report.json (orthocontact.reproduction.paper_report): the
sign reading it states, its counts and headline, the calibration chain
by hand."""
from model_notes import errata_numbers
from paths import SCENARIOS


def test_the_report_says_which_sign_reading_it_uses_and_its_sign_free_figures(tmp_path):
    from orthocontact.experiment.scenario import load
    from orthocontact.reproduction import paper_report
    free = paper_report.sign_free_peaks(load(SCENARIOS / "mat_aged.toml"))
    got = errata_numbers()
    assert f"{free['associated']['peak_abs_phi_deg']:.2f}" == got["associated"][1]
    assert f"{free['associated']['angle_deg']:.2f}" == got["associated"][3]
    text = " ".join(paper_report.SIGN_READING)
    assert "reads both Case 5 and the experiment as clockwise" in text and "1.875" in text
    assert "erratum 6" in text
