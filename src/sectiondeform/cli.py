"""The ``sectiondeform`` command: a thin layer over the library.

Each subcommand is a module of :mod:`sectiondeform.commands` with
``add_args(parser)`` and ``run(args) -> int``; its docstring's first line is
its help. Errors of the project (:class:`~sectiondeform.errors.SectionDeformError`)
print one line on stderr and exit with status 2.
"""

from __future__ import annotations

import argparse
import difflib
import importlib
import pkgutil
import sys

from . import __version__, commands
from .commands._io_args import coordinate_tokens
from .errors import SectionDeformError, spelled

__all__ = ["main", "build_parser"]


def _command_modules():
    for info in sorted(pkgutil.iter_modules(commands.__path__), key=lambda m: m.name):
        if not info.name.startswith("_"):
            yield info.name.replace("_", "-"), importlib.import_module(f"{commands.__name__}.{info.name}")


class _OneLineParser(argparse.ArgumentParser):
    """A parser whose usage errors are one line on stderr (exit 2), pointing to ``--help``."""

    def error(self, message):
        hint = self._nearest(message)
        self.exit(2, f"{self.prog}: error: {' '.join(message.split())}{hint} (see {self.prog} --help)\n")

    def _options(self) -> dict[str, list[str]]:
        """Every option string of this parser and of its subcommands, each with the subcommands that have it."""
        out: dict[str, list[str]] = {o: [] for o in self._option_string_actions}
        for action in self._actions:
            if isinstance(action, argparse._SubParsersAction):
                for name, sub in action.choices.items():
                    for o in sub._option_string_actions:
                        out.setdefault(o, []).append(name)
        return out

    def _nearest(self, message: str) -> str:
        """``; did you mean --area-ratio?`` for a misspelt option among unrecognized arguments, or ``; --quiet is an
        option of sweep, validate`` for another command's option, else ``""``.
        """
        if not message.startswith("unrecognized arguments: "):
            return ""
        options = self._options()
        known = sorted(o for o in options if o.startswith("--"))
        for word in message.split(": ", 1)[1].split():
            if word.startswith("--"):
                name = word.split("=")[0]
                if options.get(name):  # spelt right: another command's
                    return f"; {name} is an option of {', '.join(sorted(options[name]))}, not of this command"
                close = difflib.get_close_matches(name, known, n=1, cutoff=0.75)
                if close:
                    return f"; did you mean {close[0]}?"
        return ""


def build_parser() -> argparse.ArgumentParser:
    """The argument parser with every subcommand."""
    parser = _OneLineParser(
        prog="sectiondeform",
        description="Deform the cross-section of an elastomer body onto a deformed support, following a mechanical law.",
    )
    parser.add_argument("--version", action="version", version=f"sectiondeform {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for name, module in _command_modules():
        doc = (module.__doc__ or "").strip()
        first = doc.splitlines()[0] if doc else name
        p = sub.add_parser(name, help=first, description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
        module.add_args(p)
        p.set_defaults(_run=module.run)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status (0 success, 2 bad input or failure)."""
    parser = build_parser()
    args = parser.parse_args(coordinate_tokens(sys.argv[1:] if argv is None else list(argv)))
    try:
        return int(args._run(args) or 0)
    except SectionDeformError as exc:  # the library's option names in the command line's words
        from .commands._common import OPTION_FLAGS

        print(f"sectiondeform {args.command}: error: {spelled(str(exc), OPTION_FLAGS)}", file=sys.stderr)
        return 2
    except OSError as exc:  # a file that cannot be read or written: one line, not a traceback
        print(f"sectiondeform {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:  # pragma: no cover - interactive
        print("interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
