"""Every command's --help: examples, every default stated; one progress switch name."""

import argparse

import pytest

from unsew.cli import build_parser, main


def _parsers(parser, path=()):
    yield path, parser
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield from _parsers(sub, path + (name,))


def test_every_command_has_examples_and_states_its_defaults():
    seen = 0
    for path, parser in _parsers(build_parser()):
        text = parser.format_help()
        assert "examples:\n  unsew" in text, path
        for action in parser._actions:
            if action.help in (None, argparse.SUPPRESS) or not action.option_strings:
                continue
            plain_switch = isinstance(
                action, (argparse._StoreTrueAction, argparse._HelpAction, argparse._VersionAction)
            )
            if not plain_switch and not action.required:  # every option a user may leave out says what then
                assert "default" in parser._get_formatter()._expand_help(action), (path, action.dest)
        seen += 1
    assert seen >= 15


def test_fit_help_states_the_configurations_defaults():
    from unsew.commands.fit import DEMO_DEFAULTS, FIT_DEFAULTS
    from unsew.fit.config import FitConfig
    from unsew.fit.demo import DEMO_CONFIG

    cfg = FitConfig()
    assert FIT_DEFAULTS == {
        "iterations": cfg.optimizer.iterations,
        "edge_length": cfg.drape.edge_length,
        "steps": cfg.drape.steps,
    }
    assert DEMO_DEFAULTS == {
        "iterations": DEMO_CONFIG["optimizer"]["iterations"],
        "edge_length": DEMO_CONFIG["drape"]["edge_length"],
        "steps": DEMO_CONFIG["drape"]["steps"],
    }
    assert cfg.device == "cpu" and cfg.material.start == "auto" and cfg.time_limit == 540.0


@pytest.mark.parametrize(
    "command",
    [
        ["fit", "case", "--out", "r"],
        ["demo"],
        ["batch", "cases", "--out", "r"],
        ["drape", "p.json", "--out", "g.obj"],
    ],
)
def test_no_progress_everywhere_and_quiet_still_works_with_a_warning(command, capsys):
    parser = build_parser()
    dest = "no_progress" if command[0] == "drape" else "quiet"
    assert getattr(parser.parse_args(command + ["--no-progress"]), dest) is True
    assert getattr(parser.parse_args(command), dest) is False
    assert (
        "--no-progress"
        in capsys.readouterr().out + parser._subparsers._group_actions[0].choices[command[0]].format_help()
    )
    assert getattr(parser.parse_args(command + ["--quiet"]), dest) is True
    assert "--quiet is deprecated, use --no-progress" in capsys.readouterr().err


def test_top_level_help_exits_cleanly(capsys):
    with pytest.raises(SystemExit) as e:
        main(["--help"])
    assert e.value.code == 0 and "examples:" in capsys.readouterr().out


def test_drape_help_states_the_dressing_defaults():
    from unsew.dress import DRESS_SETTINGS

    text = build_parser()._subparsers._group_actions[0].choices["drape"].format_help().replace("\n", " ")
    text = " ".join(text.split())
    assert f"sewing phase (default: {DRESS_SETTINGS.sew_steps}," in text
    assert f"after sewing (default: {DRESS_SETTINGS.settle_steps}," in text


def test_fit_help_and_the_config_page_list_every_setting():
    """``unsew fit --help`` lists every setting of the fit's config with its default (read back
    as YAML: the config's own dict), and docs/config.md names each of them, with its default, and
    nothing else."""
    import re
    from pathlib import Path

    import yaml

    from unsew.fit.config import FitConfig, config_to_dict, user_settings

    fit = next(p for path, p in _parsers(build_parser()) if path == ("fit",))
    block = fit.format_help().split("settings of --config FIT.yaml", 1)[1].splitlines()[1:]
    lines: list = []
    for line in block:
        if line.startswith("    ") and lines:
            lines[-1] += " " + line.strip()
        elif line.strip():
            lines.append(line.strip())
    shown = yaml.safe_load("{" + lines[0] + "}")
    for line in lines[1:]:
        shown.update(yaml.safe_load(line))
    assert shown == config_to_dict(FitConfig())
    n = len(user_settings())
    assert f"({n})" in fit.format_help() and n == len(lines[0].split(", ")) + sum(
        len(v) for v in shown.values() if isinstance(v, dict)
    )
    page = (Path(__file__).parents[2] / "docs" / "config.md").read_text()
    listed = dict(re.findall(r"^\| `([a-z_.]+)` \| `([^`]*)` \|", page, flags=re.M))
    assert set(listed) == set(user_settings())
    for key, value in user_settings().items():  # the page's defaults are the config's
        assert yaml.safe_load(listed[key]) == (list(value) if isinstance(value, tuple) else value), key
