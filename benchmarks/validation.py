"""The fast models against the finite-element reference, and the reference's refinement study.

Writes the tables of ``docs/validation.md`` (between its ``<!-- validation:... -->``
markers) from scratch:

    .venv/bin/python benchmarks/validation.py tests/data/cases/*.json --write docs/validation.md

and, given version-2 cases too (``tests/data/cases/v2/*.json``), the tables
of its sections "Bodies of revolution: fast models against the reference"
and "Assemblies" (blocks ``validation:revolution`` and
``validation:assemblies``); the version-1 tables are the same either way:

1. Validation: for every case, ``sectiondeform.reference.validation.validate_case``
   with each fast model (``paper``, and ``hyperelastic`` if given with
   ``--models``): shape distance (Hausdorff and largest pointwise, absolute,
   over the mean thickness T and over the section's height), areas, times,
   speed ratio.
2. Refinement study of the reference: mesh sizes 0.4 T ... 0.025 T; largest
   move of an upper point between successive meshes and against the finest,
   over T; area error; time.
3. Version-2 cases of one body (a body of revolution, or a plane one for
   comparison), through the fast models' assembly path, with the body's law
   (volume for revolution, area in plane) and its errors; what a model or
   the reference refuses is a row with the one-line refusal.
4. Version-2 cases of several bodies: one reference solve of all bodies
   (``sectiondeform.reference.assembly``) per case, each fast model against
   it, one row per body (Hausdorff over the body's mean thickness and over
   the assembly's height, each body's law's measure and error, the times of
   the whole); a reference that does not converge is a row saying so.
   ``--assembly-mesh-size`` sets its element size (default 0.1 of each
   body's mesh scale); ``--assembly-study`` adds its refinement (twice
   that size against it, per body: block ``validation:assemblies-study``).

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
from sectiondeform.assembly import Assembly
from sectiondeform.errors import SectionDeformError
from sectiondeform.io.json import atomic_write
from sectiondeform.reference import DEFAULT_MESH_SIZE, solve_reference
from sectiondeform.reference.validation import save_validation_figure, validate_case

STUDY = (0.4, 0.2, 0.1, 0.05, 0.025)


def eprint(*args):
    print(*args, file=sys.stderr, flush=True)


def validation_table(cases, models, figures: Path | None) -> str:
    rows = [
        "| case | fast model | T (mm) | height (mm) | r | Hausdorff (mm) | Hausdorff / T | Hausdorff / height "
        "| max pointwise / T | max pointwise / height "
        "| area fast (rel. err.) | area reference (rel. err.) | time fast | time reference | speed ratio |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for path in cases:
        case = sd.load_case(path)
        for model in models:
            eprint(f"== {case.name}, {model} model")
            v = validate_case(case, model=model, progress=eprint)
            if figures is not None:
                save_validation_figure(v, figures / f"validation-{case.name}-{model}.png")
            f, s = v.fast, v.shape
            ref_err = (v.area_reference - f.area_target) / f.area_target
            rows.append(
                f"| {case.name} | {model} | {v.thickness:.2f} | {v.height:.2f} | {f.area_target / f.area_initial:.2f} "
                f"| {s.hausdorff:.3f} | {s.hausdorff_relative:.1%} | {s.hausdorff / v.height:.1%} "
                f"| {s.max_pointwise_relative:.1%} | {s.max_pointwise / v.height:.1%} "
                f"| {f.area_final:.1f} ({f.relative_error:+.0e}) | {v.area_reference:.1f} ({ref_err:+.1e}) "
                f"| {1e3 * v.fast_seconds:.1f} ms | {v.reference_seconds:.2f} s | {v.speed_ratio:,.0f} |"
            )
    return "\n".join(rows)


V2_HEADER = [
    "| case | body | fast model | kinematics | law | T (mm) | height (mm) | Hausdorff (mm) | Hausdorff / T "
    "| Hausdorff / height | max pointwise (mm) | max pointwise / T | max pointwise / height "
    "| law's measure fast (rel. err.) | reference (rel. err.) | time fast | time reference | speed ratio |",
    "|---|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
]


def _law(body) -> str:
    law = body.law
    return f"{law.key} {law.ratio:g}" if hasattr(law, "ratio") else law.key


def v2_row(case: Assembly, model: str, figures: Path | None) -> str:
    """One row of a version-2 table: the body's figures, or the one-line refusal."""
    names = ", ".join(b.name for b in case.bodies)
    kinematics = "revolution" if case.revolution is not None else "plane"
    laws = ", ".join(_law(b) for b in case.bodies)
    try:
        v = validate_case(case, model=model, progress=eprint)
    except SectionDeformError as exc:
        eprint(f"   refused: {exc}")
        return f"| {case.name} | {names} | {model} | {kinematics} | {laws} | refused: {exc} |" + " |" * 12
    if figures is not None:
        save_validation_figure(v, figures / f"validation-{case.name}-{model}.png")
    f, s, r = v.fast, v.shape, v.reference
    if v.revolution:
        fast_err, ref_err = v.volume_relative_errors
        measure = (f"volume {f.volume_final:.6g} mm³ ({fast_err:+.0e}) | {r.volume_final:.6g} mm³ ({ref_err:+.1e})")
    else:
        ref_err = (v.area_reference - f.area_target) / f.area_target
        measure = f"area {f.area_final:.1f} mm² ({f.relative_error:+.0e}) | {v.area_reference:.1f} mm² ({ref_err:+.1e})"
    return (
        f"| {case.name} | {names} | {model} | {kinematics} | {laws} | {v.thickness:.2f} | {v.height:.2f} "
        f"| {s.hausdorff:.3f} | {s.hausdorff / v.thickness:.1%} | {s.hausdorff / v.height:.1%} "
        f"| {s.max_pointwise:.3f} | {s.max_pointwise / v.thickness:.1%} | {s.max_pointwise / v.height:.1%} "
        f"| {measure} | {1e3 * v.fast_seconds:.1f} ms | {v.reference_seconds:.2f} s | {v.speed_ratio:,.0f} |"
    )


def v2_table(cases, models, figures: Path | None) -> str:
    """The table of version-2 cases (already loaded), each with each model."""
    rows = list(V2_HEADER)
    for case in cases:
        for model in models:
            eprint(f"== {case.name}, {model} model")
            rows.append(v2_row(case, model, figures))
    return "\n".join(rows)


ASSEMBLY_HEADER = [
    "| case | kinematics | body | rubber | law | fast model | T (mm) | Hausdorff (mm) | Hausdorff / T "
    "| Hausdorff / height | max pointwise (mm) | law's measure fast (rel. err.) | reference (rel. err.) "
    "| time fast | time reference | speed ratio |",
    "|---|---|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
]


def assembly_rows(case: Assembly, models, figures: Path | None, mesh_size: float, solved: dict | None = None) -> list[str]:
    """Rows of the assemblies table: one reference solve, then each model against it, one row per body.

    ``solved``, if given, receives the reference under ``(case.name, mesh_size)``.
    """
    from sectiondeform.reference.assembly import solve_assembly_reference
    from sectiondeform.reference.validation import validate_assembly

    kinematics = "revolution" if case.revolution is not None else "plane"
    head = f"| {case.name} | {kinematics} "
    try:
        ref = solve_assembly_reference(case, mesh_size=mesh_size, progress=eprint)
        if solved is not None:
            solved[(case.name, mesh_size)] = ref
    except SectionDeformError as exc:
        eprint(f"   reference failed: {exc}")
        return [head + f"| {', '.join(b.name for b in case.bodies)} | | | {model} | reference failed: {exc} |" + " |" * 9
                for model in models]
    eprint(f"   reference: {ref.elements} triangles, {ref.dofs} unknowns, {ref.iterations} Newton iterations, "
           f"{ref.seconds:.2f} s")
    rows = []
    for model in models:
        eprint(f"== {case.name}, {model} model")
        try:
            v = validate_assembly(case, model=model, mesh_size=mesh_size, reference=ref, progress=eprint)
        except SectionDeformError as exc:
            eprint(f"   refused: {exc}")
            rows.append(head + f"| {', '.join(b.name for b in case.bodies)} | | | {model} | refused: {exc} |" + " |" * 9)
            continue
        if figures is not None:
            save_validation_figure(v, figures / f"validation-{case.name}-{model}.png")
        for body, bv, rubber in zip(case.bodies, v.bodies, ref.materials):
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


def assembly_table(cases, models, figures: Path | None, mesh_size: float = DEFAULT_MESH_SIZE,
                   solved: dict | None = None) -> str:
    """The table of assemblies of several bodies (already loaded): per body, each model against the reference."""
    rows = list(ASSEMBLY_HEADER)
    for case in cases:
        eprint(f"== {case.name}: the reference of its {len(case.bodies)} bodies")
        rows += assembly_rows(case, models, figures, mesh_size, solved)
    return "\n".join(rows)


def assembly_study(cases, sizes, solved: dict | None = None) -> str:
    """Refinement of the assembly reference: per body, the largest move of an upper point between sizes."""
    from sectiondeform.reference.assembly import solve_assembly_reference

    solved = {} if solved is None else solved
    rows = [
        "| case | body | h / mesh scale | triangles (all bodies) | max move vs finer / T | law's rel. err. | time |",
        "|---|---|---:|---:|---:|---:|---:|",
    ]
    for case in cases:
        refs = []
        for h in sizes:
            if (case.name, h) not in solved:
                eprint(f"== study {case.name}, h = {h}")
                solved[(case.name, h)] = solve_assembly_reference(case, mesh_size=h)
            refs.append(solved[(case.name, h)])
        T = [sd.build_section(case.body_case(b)).thickness for b in range(len(case.bodies))]
        for k, (h, ref) in enumerate(zip(sizes, refs)):
            for b, body in enumerate(ref.bodies):
                move = ""
                if k + 1 < len(refs):
                    move = f"{np.hypot(*(body.upper - refs[k + 1].bodies[b].upper).T).max() / T[b]:.3%}"
                rows.append(f"| {case.name} | {body.name} | {h:g} | {ref.elements} | {move} "
                            f"| {body.relative_error:+.1e} | {ref.seconds:.1f} s |")
    return "\n".join(rows)


def study_table(cases, sizes) -> str:
    rows = [
        "| case | h / T | triangles | unknowns | Newton its | max move vs previous / T "
        "| max move vs finest / T | area rel. err. | strain energy (μ mm²) | time |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for path in cases:
        case = sd.load_case(path)
        T = sd.build_section(case).thickness
        sols = []
        for h in sizes:
            eprint(f"== study {case.name}, h = {h} T")
            t0 = time.perf_counter()
            ref = solve_reference(case, mesh_size=h)
            sols.append((h, ref, time.perf_counter() - t0))
        finest = sols[-1][1].upper
        prev = None
        for h, ref, secs in sols:
            move_prev = "" if prev is None else f"{np.linalg.norm(ref.upper - prev, axis=1).max() / T:.3%}"
            move_fine = np.linalg.norm(ref.upper - finest, axis=1).max() / T
            rows.append(
                f"| {case.name} | {h:g}{' (default)' if h == DEFAULT_MESH_SIZE else ''} | {ref.elements} | {ref.dofs} "
                f"| {ref.iterations} | {move_prev} | {move_fine:.3%} | {ref.relative_area_error:+.2e} "
                f"| {ref.strain_energy:.4g} | {secs:.2f} s |"
            )
            prev = ref.upper
    return "\n".join(rows)


def replace_block(text: str, name: str, body: str) -> str:
    pattern = re.compile(rf"(<!-- validation:{name} -->\n).*?(<!-- /validation:{name} -->)", re.S)
    if not pattern.search(text):
        raise SystemExit(f"the document has no <!-- validation:{name} --> ... <!-- /validation:{name} --> block")
    return pattern.sub(lambda m: m.group(1) + body + "\n" + m.group(2), text)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="+", type=Path, help="case files (.json)")
    parser.add_argument("--models", nargs="+", default=["paper", "hyperelastic"], choices=sd.case.MODELS)
    parser.add_argument("--write", type=Path, metavar="DOC", help="markdown file whose validation blocks to replace")
    parser.add_argument("--figures", type=Path, metavar="DIR", help="also write one overlay figure per case and model")
    parser.add_argument("--quick", action="store_true", help="study down to 0.1 T only")
    parser.add_argument("--assembly-mesh-size", type=float, default=DEFAULT_MESH_SIZE, metavar="H",
                        help=f"reference element size of the assemblies, fraction of each body's mesh scale "
                             f"(default {DEFAULT_MESH_SIZE})")
    parser.add_argument("--assembly-study", action="store_true",
                        help="also the refinement of the assembly reference: twice that size against it "
                             "(block validation:assemblies-study)")
    args = parser.parse_args(argv)
    loaded = {path: sd.load_case(path) for path in sorted(args.cases)}
    cases = [path for path, case in loaded.items() if not isinstance(case, Assembly)]
    v2 = [case for case in loaded.values() if isinstance(case, Assembly)]
    one_body = [case for case in v2 if len(case.bodies) == 1]
    # Bodies of revolution first, then the plane one-body cases for comparison.
    one_body.sort(key=lambda case: (case.revolution is None, case.name))
    several = [case for case in v2 if len(case.bodies) > 1]
    sizes = STUDY[:3] if args.quick else STUDY
    blocks = {}
    if cases:
        blocks["table"] = validation_table(cases, args.models, args.figures)
        blocks["study"] = study_table(cases, sizes)
    if one_body:
        blocks["revolution"] = v2_table(one_body, args.models, args.figures)
    if several:
        solved: dict = {}
        blocks["assemblies"] = assembly_table(several, args.models, args.figures, args.assembly_mesh_size, solved)
        if args.assembly_study:
            blocks["assemblies-study"] = assembly_study(several, (2 * args.assembly_mesh_size, args.assembly_mesh_size),
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
