"""The fast models against the finite-element reference, and the reference's refinement study.

Writes the tables of ``docs/validation.md`` (between its ``<!-- validation:... -->``
markers) from scratch:

    .venv/bin/python benchmarks/validation.py tests/data/cases/*.json --write docs/validation.md

and, given version-2 cases too (``tests/data/cases/v2/*.json``), the tables
of its sections "Bodies of revolution: fast models against the reference"
and "Several bonded bodies" (blocks ``validation:revolution`` and
``validation:assemblies``); the version-1 tables are the same either way.
Every comparison is ``sectiondeform.reference.validation.validate`` of a
problem, one body or several:

1. Validation of the version-1 cases with each fast model (``paper``, and
   ``hyperelastic`` if given with ``--models``): shape distance (Hausdorff
   and largest pointwise, absolute, over the mean thickness T and over the
   section's height), areas, times, speed ratio.
2. Refinement study of the reference: mesh sizes 0.4 T ... 0.025 T; per
   body, the largest move of an upper point between successive meshes and
   against the finest, over T; the law's error; time.
3. Version-2 cases, one reference solve of all their bodies per case, each
   fast model against it, one row per body (Hausdorff over the body's mean
   thickness and over the problem's height, each body's law's measure and
   error, the times of the whole): the cases of one body (bodies of
   revolution first, then plane ones for comparison) in one block, those of
   several bodies in another. What a model refuses, or a reference that
   does not converge, is a row with the one-line refusal.
   ``--assembly-mesh-size`` sets the reference's element size (default 0.1
   of each body's mesh scale); ``--assembly-study`` adds the study of the
   cases of several bodies (twice that size against it: block
   ``validation:assemblies-study``).

Needs the extra ``[fem]``; takes a few minutes on 2 cores (the finest
meshes of the study dominate). ``--quick`` skips the two finest meshes.
"""

from __future__ import annotations

import argparse
import re
import sys
import time
from pathlib import Path

import numpy as np

import sectiondeform as sd
from sectiondeform.errors import SectionDeformError
from sectiondeform.io.json import atomic_write
from sectiondeform.models import MODEL_NAMES
from sectiondeform.problem import V1
from sectiondeform.reference import DEFAULT_MESH_SIZE, solve_reference
from sectiondeform.reference.validation import save_validation_figure, validate

STUDY = (0.4, 0.2, 0.1, 0.05, 0.025)


def eprint(*args):
    print(*args, file=sys.stderr, flush=True)


def validation_table(problems, models, figures: Path | None) -> str:
    """The version-1 table: per case and model, the one body's figures."""
    rows = [
        "| case | fast model | T (mm) | height (mm) | r | Hausdorff (mm) | Hausdorff / T | Hausdorff / height "
        "| max pointwise / T | max pointwise / height "
        "| area fast (rel. err.) | area reference (rel. err.) | time fast | time reference | speed ratio |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for problem in problems:
        for model in models:
            eprint(f"== {problem.name}, {model} model")
            v = validate(problem, model=model, progress=eprint)
            if figures is not None:
                save_validation_figure(v, figures / f"validation-{problem.name}-{model}.png")
            for bv, f in zip(v.bodies, v.fast.bodies):
                s = bv.shape
                ref_err = (bv.reference_final - bv.target) / bv.target  # against the fast model's target, as the fast error
                rows.append(
                    f"| {problem.name} | {model} | {bv.thickness:.2f} | {v.height:.2f} | {bv.target / f.area_initial:.2f} "
                    f"| {s.hausdorff:.3f} | {s.hausdorff_relative:.1%} | {s.hausdorff / v.height:.1%} "
                    f"| {s.max_pointwise_relative:.1%} | {s.max_pointwise / v.height:.1%} "
                    f"| {bv.fast_final:.1f} ({bv.fast_error:+.0e}) | {bv.reference_final:.1f} ({ref_err:+.1e}) "
                    f"| {1e3 * v.fast_seconds:.1f} ms | {v.reference_seconds:.2f} s | {v.speed_ratio:,.0f} |"
                )
    return "\n".join(rows)


def _law(body) -> str:
    law = body.law
    return f"{law.key} {law.ratio:g}" if hasattr(law, "ratio") else law.key


BODIES_HEADER = [
    "| case | kinematics | body | rubber | law | fast model | T (mm) | Hausdorff (mm) | Hausdorff / T "
    "| Hausdorff / height | max pointwise (mm) | law's measure fast (rel. err.) | reference (rel. err.) "
    "| time fast | time reference | speed ratio |",
    "|---|---|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
]


def body_rows(problem, models, figures: Path | None, mesh_size: float, solved: dict | None = None) -> list[str]:
    """Rows of a problem: one reference solve, then each model against it, one row per body.

    ``solved``, if given, receives the reference under ``(problem.name, mesh_size)``.
    """
    kinematics = "revolution" if problem.revolution is not None else "plane"
    head = f"| {problem.name} | {kinematics} "
    names = ", ".join(b.name for b in problem.bodies)
    try:
        ref = solve_reference(problem, mesh_size=mesh_size, progress=eprint)
    except SectionDeformError as exc:
        eprint(f"   reference failed: {exc}")
        return [head + f"| {names} | | | {model} | reference failed: {exc} |" + " |" * 9 for model in models]
    if solved is not None:
        solved[(problem.name, mesh_size)] = ref
    eprint(f"   reference: {ref.elements} triangles, {ref.dofs} unknowns, {ref.iterations} Newton iterations, "
           f"{ref.seconds:.2f} s")
    rows = []
    for model in models:
        eprint(f"== {problem.name}, {model} model")
        try:
            v = validate(problem, model=model, mesh_size=mesh_size, reference=ref, progress=eprint)
        except SectionDeformError as exc:
            eprint(f"   refused: {exc}")
            rows.append(head + f"| {names} | | | {model} | refused: {exc} |" + " |" * 9)
            continue
        if figures is not None:
            save_validation_figure(v, figures / f"validation-{problem.name}-{model}.png")
        for body, bv, rubber in zip(problem.bodies, v.bodies, ref.materials):
            s = bv.shape
            unit = "mm³" if bv.measure == "volume" else "mm²"
            rows.append(
                head + f"| {body.name} | {rubber.model}, μ {rubber.shear_modulus:g} MPa | {_law(body)} | {model} "
                f"| {bv.thickness:.2f} | {s.hausdorff:.3f} | {s.hausdorff / bv.thickness:.1%} | {s.hausdorff / v.height:.1%} "
                f"| {s.max_pointwise:.3f} | {bv.measure} {bv.fast_final:.6g} {unit} ({bv.fast_error:+.0e}) "
                f"| {bv.reference_final:.6g} {unit} ({bv.reference_error:+.1e}) | {1e3 * v.fast_seconds:.1f} ms "
                f"| {v.reference_seconds:.2f} s | {v.speed_ratio:,.0f} |"
            )
    return rows


def bodies_table(problems, models, figures: Path | None, mesh_size: float = DEFAULT_MESH_SIZE,
                 solved: dict | None = None) -> str:
    """The table of problems (already loaded): per body, each model against the problem's reference."""
    rows = list(BODIES_HEADER)
    for problem in problems:
        eprint(f"== {problem.name}: one reference of its bodies ({len(problem.bodies)})")
        rows += body_rows(problem, models, figures, mesh_size, solved)
    return "\n".join(rows)


def study_table(problems, sizes, solved: dict | None = None) -> str:
    """Refinement of the reference: per body, the largest move of an upper point against the next and the finest size."""
    solved = {} if solved is None else solved
    rows = [
        "| case | body | h / mesh scale | triangles | unknowns | Newton its | max move vs previous / T "
        "| max move vs finest / T | law's rel. err. | strain energy (μ mm²) | time |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for problem in problems:
        refs = []
        for h in sizes:
            if (problem.name, h) not in solved:
                eprint(f"== study {problem.name}, h = {h}")
                t0 = time.perf_counter()
                ref = solve_reference(problem, mesh_size=h)
                solved[(problem.name, h)] = ref
                eprint(f"   {time.perf_counter() - t0:.2f} s")
            refs.append(solved[(problem.name, h)])
        T = [sd.build_section(problem.body_case(b)).thickness for b in range(len(problem.bodies))]
        for k, (h, ref) in enumerate(zip(sizes, refs)):
            for b, body in enumerate(ref.bodies):
                prev = "" if k == 0 else f"{np.hypot(*(body.upper - refs[k - 1].bodies[b].upper).T).max() / T[b]:.3%}"
                fine = np.hypot(*(body.upper - refs[-1].bodies[b].upper).T).max() / T[b]
                rows.append(
                    f"| {problem.name} | {body.name} | {h:g}{' (default)' if h == DEFAULT_MESH_SIZE else ''} "
                    f"| {ref.elements} | {ref.dofs} | {ref.iterations} | {prev} | {fine:.3%} "
                    f"| {body.relative_error:+.2e} | {ref.strain_energy:.4g} | {ref.seconds:.2f} s |"
                )
    return "\n".join(rows)


def replace_block(text: str, name: str, body: str) -> str:
    pattern = re.compile(rf"(<!-- validation:{name} -->\n).*?(<!-- /validation:{name} -->)", re.S)
    if not pattern.search(text):
        raise SystemExit(f"the document has no <!-- validation:{name} --> ... <!-- /validation:{name} --> block")
    return pattern.sub(lambda m: m.group(1) + body + "\n" + m.group(2), text)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="+", type=Path, help="case files (.json)")
    parser.add_argument("--models", nargs="+", default=["paper", "hyperelastic"], choices=MODEL_NAMES)
    parser.add_argument("--write", type=Path, metavar="DOC", help="markdown file whose validation blocks to replace")
    parser.add_argument("--figures", type=Path, metavar="DIR", help="also write one overlay figure per case and model")
    parser.add_argument("--quick", action="store_true", help="study down to 0.1 T only")
    parser.add_argument("--assembly-mesh-size", type=float, default=DEFAULT_MESH_SIZE, metavar="H",
                        help=f"reference element size of the version-2 cases, fraction of each body's mesh scale "
                             f"(default {DEFAULT_MESH_SIZE})")
    parser.add_argument("--assembly-study", action="store_true",
                        help="also the refinement of the reference of the cases of several bodies: twice that size "
                             "against it (block validation:assemblies-study)")
    args = parser.parse_args(argv)
    loaded = [sd.load_case(path) for path in sorted(args.cases)]
    v1 = [p for p in loaded if p.dialect == V1]
    # Bodies of revolution first, then the plane one-body cases for comparison.
    one_body = sorted((p for p in loaded if p.dialect != V1 and len(p.bodies) == 1),
                      key=lambda p: (p.revolution is None, p.name))
    several = [p for p in loaded if len(p.bodies) > 1]
    sizes = STUDY[:3] if args.quick else STUDY
    blocks = {}
    if v1:
        blocks["table"] = validation_table(v1, args.models, args.figures)
        blocks["study"] = study_table(v1, sizes)
    if one_body:
        blocks["revolution"] = bodies_table(one_body, args.models, args.figures, args.assembly_mesh_size)
    if several:
        solved: dict = {}
        blocks["assemblies"] = bodies_table(several, args.models, args.figures, args.assembly_mesh_size, solved)
        if args.assembly_study:
            blocks["assemblies-study"] = study_table(several, (2 * args.assembly_mesh_size, args.assembly_mesh_size),
                                                     solved)
    print(*blocks.values(), sep="\n\n")
    if args.write:
        text = args.write.read_text(encoding="utf-8")
        for name, body in blocks.items():
            text = replace_block(text, name, body)
        atomic_write(args.write, lambda tmp: tmp.write_text(text, encoding="utf-8"))
        eprint(f"wrote {args.write}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
