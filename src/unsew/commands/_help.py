"""What every command's ``--help`` shares: a formatter that keeps the examples' line breaks and
states each option's default, the fit's config settings, and the deprecated ``--quiet`` spelling of
``--no-progress``."""

from __future__ import annotations

import argparse
import sys

__all__ = ["HelpFormatter", "examples", "add_progress_switch", "FIT_SETTINGS", "fit_settings"]

#: Stands in an epilog for :func:`fit_settings`, filled in when the help is printed (reading the
#: fit's config imports the simulator, which building the parser must not).
FIT_SETTINGS = "<fit settings>"


class HelpFormatter(argparse.HelpFormatter):
    """Descriptions wrapped, example lists (:func:`examples`) as written; an option with a real
    default (not None, not a plain on/off switch) and no ``default`` in its help gets
    ``(default: VALUE)`` appended."""

    def _fill_text(self, text: str, width: int, indent: str) -> str:
        if text.startswith("examples:"):
            text = text.replace(FIT_SETTINGS, fit_settings()) if FIT_SETTINGS in text else text
            return "".join(indent + line for line in text.splitlines(keepends=True))
        return super()._fill_text(text, width, indent)

    def _get_help_string(self, action: argparse.Action) -> str:
        text = action.help or ""
        if "default" in text or action.default in (None, False, True, argparse.SUPPRESS):
            return text
        if action.option_strings or action.nargs in (argparse.OPTIONAL, argparse.ZERO_OR_MORE):
            text += " (default: %(default)s)"
        return text


def fit_settings(width: int = 100) -> str:
    """The fit's config settings (:func:`unsew.fit.config.user_settings`) with their defaults in
    YAML: the top-level ones, then a line per group (wrapped at ``width`` characters)."""
    import yaml

    from unsew.fit.config import FitConfig, config_to_dict, user_settings

    def flow(v) -> str:
        text = yaml.safe_dump(v, default_flow_style=True, sort_keys=False, width=10**6)
        return text.removesuffix("\n").removesuffix("\n...").strip()

    lines = [f"settings of --config FIT.yaml ({len(user_settings())}), their defaults:"]
    top: list = []
    for key, value in config_to_dict(FitConfig()).items():
        if isinstance(value, dict):
            items = [f"{k}: {flow(v)}" for k, v in value.items()]
            lines += _wrapped(f"{key}: {{", items, "}", width)
        else:
            top.append(f"{key}: {flow(value)}")
    return "\n".join([lines[0], *_wrapped("", top, "", width), *lines[1:]])


def _wrapped(head: str, items: list, tail: str, width: int) -> list:
    """``head`` + ``items`` joined by ", " + ``tail``, indented two spaces, broken between items."""
    lines, cur = [], "  " + head
    for k, item in enumerate(items):
        piece = item + (", " if k < len(items) - 1 else tail)
        if len(cur) + len(piece.rstrip()) > width and cur.strip():
            lines.append(cur.rstrip())
            cur = "    "
        cur += piece
    return lines + [cur.rstrip()]


def examples(*lines: str) -> str:
    """An epilog listing example command lines."""
    return "examples:\n" + "\n".join(f"  {line}" for line in lines)


class _Deprecated(argparse.Action):
    """A hidden old spelling: sets the new switch and says which name to use."""

    def __init__(self, option_strings, dest, *, new: str, **kw):
        self.new = new
        super().__init__(option_strings, dest, nargs=0, default=False, help=argparse.SUPPRESS, **kw)

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"unsew: warning: {option_string} is deprecated, use {self.new}", file=sys.stderr)
        setattr(namespace, self.dest, True)


def add_progress_switch(p: argparse.ArgumentParser, *, dest: str = "quiet") -> None:
    """``--no-progress`` (stored in ``dest``), and ``--quiet`` as its hidden deprecated alias."""
    p.add_argument("--no-progress", dest=dest, action="store_true", help="no progress bars")
    p.add_argument("--quiet", dest=dest, action=_Deprecated, new="--no-progress")
