"""The command line frame: help, version, errors as one line."""

import subprocess
import sys

import unsew
from unsew.cli import main


def test_version(capsys):
    try:
        main(["--version"])
    except SystemExit as exc:
        assert exc.code == 0
    assert unsew.__version__ in capsys.readouterr().out


def test_no_command_prints_help_and_fails(capsys):
    assert main([]) == 2
    err = capsys.readouterr().err
    assert "usage: unsew" in err and "fit" in err and "pattern" in err


def test_help_lists_commands(capsys):
    try:
        main(["--help"])
    except SystemExit as exc:
        assert exc.code == 0
    out = capsys.readouterr().out
    assert "usage: unsew" in out and "demo" in out


def test_unknown_command_fails():
    r = subprocess.run([sys.executable, "-m", "unsew", "no-such-command"], capture_output=True, text=True)
    assert r.returncode != 0
    assert "Traceback" not in r.stderr


def test_import_is_light():
    code = "import sys, unsew; import unsew.cli; print('torch' in sys.modules, 'scipy' in sys.modules)"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert r.stdout.strip() == "False False"
