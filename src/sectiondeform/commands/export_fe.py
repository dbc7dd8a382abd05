"""Write an Abaqus / CalculiX input deck (.inp) of a case: mesh, rubber, support motion, step.

The deck runs as it is in Abaqus/Standard and in CalculiX: plane-strain
elements (default CPE6, which does not lock for nearly incompressible rubber
in CalculiX), or axisymmetric ones (default CAX6) for a body of revolution,
written in (r, z); one element set, section and material per body (a
section-case/2 case), bonded bodies sharing their nodes; the rubber of each
body (neo-Hookean by default, C10 = mu/2, D1 = 2/kappa; Mooney-Rivlin, Yeoh);
the support's nodes moved onto the target by the arc-length rule; one NLGEOM
static step; displacements written out. What the deck cannot express (an
area ratio other than 1 on a plane section, a volume ratio other than 1) is
written at its top and warned about.

Example: sectiondeform export-fe case.json -o deck.inp --element CPE8R
"""

from __future__ import annotations

from pathlib import Path

from ..errors import CaseError
from ..io import read_case
from ..io.json import atomic_write
from ._common import apply_overrides, eprint


def add_fe_args(parser) -> None:
    """``--element``, ``--mesh-size`` and ``--area-ratio`` (shared with solve-fe)."""
    from ..external import DEFAULT_AXI_ELEMENT, DEFAULT_ELEMENT, DEFAULT_MESH_SIZE

    parser.add_argument("--element", default=None, metavar="TYPE",
                        help=f"element type: CPE3, CPE6, CPE4, CPE4R, CPE8, CPE8R (CAX... for a body of revolution), "
                             f"or a hybrid one (H, Abaqus only); default {DEFAULT_ELEMENT}, {DEFAULT_AXI_ELEMENT} for "
                             "a body of revolution")
    parser.add_argument("--mesh-size", type=float, default=DEFAULT_MESH_SIZE, metavar="H",
                        help=f"triangle size as a fraction of the mean thickness (default {DEFAULT_MESH_SIZE})")
    parser.add_argument("--area-ratio", type=float, metavar="R", help="override the law: final area = R x initial area")


def add_contact_penalty_arg(parser) -> None:
    """``--contact-penalty`` (shared with solve-fe)."""
    parser.add_argument("--contact-penalty", default=None, metavar="K",
                        help="with rigid parts: the slope of the linear pressure-overclosure law (moduli per unit "
                             "length), or 'hard'; default 50 x 3 mu / h (h the smallest element size)")


def contact_penalty(args):
    """The ``--contact-penalty`` value: None, ``"hard"`` or a number > 0."""
    value = getattr(args, "contact_penalty", None)
    if value is None or str(value).lower() == "hard":
        return None if value is None else "hard"
    try:
        k = float(value)
    except ValueError:
        k = float("nan")
    if not k > 0 or k == float("inf"):
        raise CaseError("--contact-penalty", f"must be a finite number > 0 or 'hard', got {value!r}")
    return k


def read_fe_case(path: Path, args):
    """The problem of a command line (any case format, either version), with ``--area-ratio`` applied."""
    return apply_overrides(read_case(path), args)


def add_args(parser) -> None:
    parser.add_argument("case", type=Path, help="case file")
    parser.add_argument("-o", "--output", type=Path, required=True, metavar="DECK", help="the deck to write (.inp)")
    add_fe_args(parser)
    add_contact_penalty_arg(parser)


def run(args) -> int:
    from ..external.deck import build_deck, deck_text

    if args.output.suffix.lower() != ".inp":
        raise CaseError("--output", f"a deck is an .inp file, got {args.output.name!r}")
    if not args.output.parent.is_dir():
        raise CaseError("--output", f"the folder {str(args.output.parent)!r} does not exist")
    case = read_fe_case(args.case, args)
    deck = build_deck(case, args.element, args.mesh_size, contact_penalty(args))
    text = deck_text(deck)
    atomic_write(args.output, lambda tmp: tmp.write_text(text, encoding="ascii"))
    for line in deck.unexpressed:
        eprint(f"sectiondeform export-fe: warning: {line}")
    m = deck.mesh
    print(f"wrote {args.output}: {len(m.points)} nodes, {len(m.cells)} {deck.element.name} elements in "
          f"{len(deck.bodies)} element set{'s' if len(deck.bodies) > 1 else ''}, {len(m.lower_nodes)} support nodes"
          + "".join(f", rigid part {p.label!r} ({len(p.triangles)} CPE3/CAX3 elements)" for p in deck.rigid))
    return 0
