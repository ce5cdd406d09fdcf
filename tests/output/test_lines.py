"""The command's lines on stderr (orthocontact.output.lines): notes, and
warnings that --strict counts."""
from orthocontact.output.lines import forget_warnings, note, warn, warnings_said


def test_warnings_are_counted_for_strict(capsys):
    forget_warnings()
    warn("angles.csv: a value looks like radians")
    warn("second")
    assert warnings_said() == 2
    assert capsys.readouterr().err.splitlines() == [
        "orthocontact: warning: angles.csv: a value looks like radians", "orthocontact: warning: second"]
    forget_warnings()
    assert warnings_said() == 0


def test_a_note_is_no_warning(capsys):
    forget_warnings()
    note("out: replaced an earlier run")
    assert warnings_said() == 0
    assert capsys.readouterr().err == "orthocontact: out: replaced an earlier run\n"
