"""Errors that reach the user as one line.

Every check at a boundary (files, meshes, patterns, configs) raises :class:`UnsewError`
(or a subclass) with a message that says what is wrong and how to fix it. The CLI prints
``unsew: error: <message>`` and exits with status 2; it never shows a traceback for these.
"""

__all__ = ["UnsewError", "InputError", "OutputError", "PatternError", "SimulationError"]


class UnsewError(Exception):
    """An error the user can act on; its message is one line."""


class InputError(UnsewError):
    """A file, mesh, body or option given by the user is missing or malformed."""


class OutputError(UnsewError, OSError):
    """An output cannot be written (unwritable place, disk full, not a regular file).

    Also an :class:`OSError`, so code that tolerates a failed optional write (a cache) keeps
    catching it.
    """


class PatternError(InputError):
    """A sewing pattern is malformed (open loop, self-intersection, bad stitch, ...): bad input."""


class SimulationError(UnsewError):
    """A simulation diverged or was set up with impossible inputs."""
