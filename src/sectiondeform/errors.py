"""The error family of sectiondeform.

Every error carries a one-line message that names the input at fault (a
case field such as ``upper.bspline.knots``, or a point index) and says what
would be accepted. The command line maps :class:`SectionDeformError` to exit
status 2.
"""

from __future__ import annotations


class SectionDeformError(Exception):
    """Base class of every error raised on purpose by sectiondeform.

    Its message is always one line: any line breaks (a wrapped library
    message) are collapsed to single spaces.
    """

    def __str__(self) -> str:
        return " ".join(super().__str__().split())


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
    """An iterative solver did not converge; the message says where it stopped."""


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
