"""``unsew pattern new GARMENT [--measurements M.yaml] --out P.json``: write a base pattern."""

from __future__ import annotations

import argparse
import sys

from unsew.errors import InputError
from unsew.pattern.base import make_base_pattern
from unsew.pattern.measurements import Measurements

__all__ = ["run", "load_measurements"]


#: Keys of ``unsew body measure --json`` that describe the measurements rather than being one.
_ABOUT = ("rigged",)
#: Metres per unit of a file's ``units`` key.
_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001}


def load_measurements(path):
    """Read body measurements from a YAML (or JSON) mapping ``name: value``, in metres unless
    the mapping says ``units: cm`` or ``mm`` (``unsew body measure --json`` output is accepted as
    it is); unknown names or implausible values raise :class:`~unsew.errors.InputError`."""
    from pathlib import Path

    import yaml

    p = Path(path)
    if not p.is_file():
        raise InputError(f"measurements file {p} not found")
    try:
        data = yaml.safe_load(p.read_text(encoding="utf-8"))
    except yaml.YAMLError as exc:
        line = getattr(getattr(exc, "problem_mark", None), "line", None)
        where = f" (line {line + 1})" if line is not None else ""
        raise InputError(f"measurements file {p} is not valid YAML{where}") from None
    if data is None:
        data = {}
    if not isinstance(data, dict):
        raise InputError(f"measurements file {p} must be a mapping like 'bust: 0.94' (metres)")
    units = data.pop("units", "m")
    if units not in _UNITS:
        raise InputError(f"measurements file {p}: units {units!r} must be one of {', '.join(_UNITS)}")
    for k in _ABOUT:
        data.pop(k, None)
    scale = _UNITS[units]
    if scale != 1.0:
        data = {
            k: v * scale if isinstance(v, (int, float)) and not isinstance(v, bool) else v
            for k, v in data.items()
        }
    return Measurements.from_dict(data)


def run(args: argparse.Namespace) -> int:
    from unsew.commands._output import check_out
    from unsew.io.garmentcode import save_pattern
    from unsew.pattern.validate import validate_pattern

    if not str(args.out).lower().endswith(".json"):
        raise InputError(f"--out {args.out} should name a .json file (GarmentCode specification)")
    check_out(args.out, overwrite=args.overwrite)
    m = load_measurements(args.measurements) if args.measurements else None
    pattern = make_base_pattern(args.garment, m)
    for w in validate_pattern(pattern):
        print(f"unsew: warning: {w}", file=sys.stderr)
    save_pattern(pattern, args.out)
    print(f"wrote {args.out}: {args.garment}, {len(pattern.panels)} panels, {len(pattern.stitches)} stitches")
    return 0
