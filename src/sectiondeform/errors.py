"""The error family of sectiondeform.

Every error carries a one-line message that names the input at fault (a
case field such as ``upper.bspline.knots``, or a point index) and says what
would be accepted. The command line maps :class:`SectionDeformError` to exit
status 2.
"""

from __future__ import annotations

import itertools
import re


class SectionDeformError(Exception):
    """Base class of every error raised on purpose by sectiondeform.

    Its message is always one line: any line breaks (a wrapped library
    message) are collapsed to single spaces.
    """

    def __str__(self) -> str:
        return " ".join(super().__str__().split())


OPTION_PHRASE = re.compile(r"\boption ([a-z][a-z_]*)\b(?: at ([-+0-9.eE]*[0-9]|[a-z][a-z_]*\b))?")
"""How a message names an option of the library: ``option simplify``, or with a value ``option snap at 0.1``
or ``option model at hyperelastic`` (neutral words, no syntax of any surface).

A surface writes it in its own words with :func:`spelled`: the command line
as its flag (``--simplify TOL``), the page as its field's label.
"""


def _flag(name: str) -> str:
    """A surface's name of an option without its placeholders: ``--snap D`` -> ``--snap``, ``chordal error`` as is."""
    return " ".join(itertools.takewhile(lambda word: not word.isupper(), name.split())) or name


def spelled(text: str, names: dict) -> str:
    """``text`` with every ``option KEY`` that ``names`` holds written ``names[KEY]`` (its flag and the value
    with ``at VALUE``), and a leading field ``KEY:`` as the flag.

    Parameters
    ----------
    text : str
        A message of the library.
    names : dict of str to str
        The surface's spelling of each option key.

    Examples
    --------
    >>> names = {"simplify": "--simplify TOL", "split": "--split XA,YA XB,YB", "snap": "--snap D"}
    >>> spelled("simplify: must be > 0; give option split, or option snap at 0.2", names)
    '--simplify: must be > 0; give --split XA,YA XB,YB, or --snap 0.2'
    >>> spelled("use the hyperelastic model (option model at hyperelastic)", {"model": "--model NAME"})
    'use the hyperelastic model (--model hyperelastic)'
    """
    field, sep, rest = text.partition(": ")
    if sep and field in names:
        text = _flag(names[field]) + sep + rest

    def spell(m):
        name = names.get(m.group(1))
        if name is None:
            return m.group(0)
        return f"{_flag(name)} {m.group(2)}" if m.group(2) else name
    return OPTION_PHRASE.sub(spell, text)


class CaseError(SectionDeformError, ValueError):
    """A case file or case dictionary is malformed; the message names the field."""

    def __init__(self, field: str, problem: str):
        self.field = field
        self.problem = problem
        super().__init__(f"{field}: {problem}" if field else problem)


class GeometryError(SectionDeformError, ValueError):
    """The section's geometry is unusable (open, self-intersecting, degenerate)."""


class MeshError(SectionDeformError):
    """A mesh could not be built, or has an inverted element."""


class LocateError(SectionDeformError):
    """A point could not be located in a mesh; the message names the point."""


class LawError(SectionDeformError, ValueError):
    """The mechanical law cannot be met (bad parameter, no admissible scale)."""


class ConvergenceError(SectionDeformError):
    """An iterative solver did not converge; the message says where it stopped.

    Parameters
    ----------
    message : str
        What stopped, and where.
    advice : str, optional
        The message's closing hint (appended after "; ").
    state : object, optional
        The last equilibrium the solver reached, for a caller that can say
        why none is near (:func:`~sectiondeform.fem.diagnosis.physical_reason`);
        never pickled (the message alone crosses processes).
    """

    def __init__(self, message: str, advice: str = "", state=None):
        super().__init__(f"{message}; {advice}" if advice else message)
        self.args = (str(self),)
        self.stopped, self.advice, self.state = message, advice, state

    def __reduce__(self):
        return type(self), self.args


class MissingExtraError(SectionDeformError, ImportError):
    """An optional dependency is missing; the message names the extra to install."""

    def __init__(self, package: str, extra: str, feature: str):
        super().__init__(
            f"{feature} needs the package '{package}': "
            f"pip install 'sectiondeform[{extra}]'"
        )


def require(module: str, extra: str, feature: str):
    """Import an optional module or raise :class:`MissingExtraError`.

    Parameters
    ----------
    module : str
        Importable module name, e.g. ``"matplotlib.pyplot"``.
    extra : str
        Name of the package extra that provides it, e.g. ``"plot"``.
    feature : str
        What the caller wanted to do, for the message.

    Returns
    -------
    module
        The imported module.

    Raises
    ------
    MissingExtraError
        If the module cannot be imported.

    Examples
    --------
    >>> require("math", "none", "arithmetic").sqrt(4.0)
    2.0
    """
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError as exc:  # pragma: no cover - depends on environment
        raise MissingExtraError(module.split(".")[0], extra, feature) from exc
