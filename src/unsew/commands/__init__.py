"""The subcommands of the ``unsew`` CLI, one module each (see :mod:`unsew.cli`).

``unsew --help`` imports every module here to build its parser, so their module-level imports
stay light (argparse, :mod:`unsew.errors`, :mod:`unsew.io.atomic`, ...): a module that pulls
numpy, torch or matplotlib is imported inside ``run``, where the work needs it.
"""
