"""The `orthocontact` command (orthocontact.cli.main, python -m orthocontact):
--version, and an error is one line with exit 2."""
from cli_run import timed_run as run

from orthocontact.cli.main import main


def test_version_names_the_package_and_both_fmus(tmp_path):
    from orthocontact import __version__
    p, _ = run(["--version"], tmp_path)
    assert p.returncode == 0
    assert p.stdout.splitlines()[0] == f"orthocontact {__version__}"
    assert "FMI 2.0 FMU:" in p.stdout and "FMI 3.0 FMU:" in p.stdout and "not found" not in p.stdout


def test_main_in_process_an_error_is_one_line_and_exit_2(tmp_path, capsys):
    assert main(["run", str(tmp_path / "none.toml"), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and err[0].startswith("orthocontact: error: ") and "none.toml" in err[0]
    assert main(["run", str(tmp_path / "none.toml"), "--out", str(tmp_path / "o"), "--fmi", "3",
                 "--master", "c"]) == 2
    assert "--master c runs FMI 2.0 FMUs" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()
