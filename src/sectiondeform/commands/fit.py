"""Fit rubber constants (neo-Hookean, Mooney-Rivlin, Yeoh) to uniaxial, equibiaxial or planar test data.

DATA is a CSV file with the columns mode (uniaxial, equibiaxial, planar),
stretch and nominal_stress (MPa, force over initial area); lines starting
with # are comments. A file of one mode may leave out the mode column and
be given as MODE=FILE. Prints the constants and the relative RMS error per
mode; writes the case format's material object (-o) and a figure (--plot).
The output files are written whole or not at all.

Examples
--------
  sectiondeform fit treloar.csv
  sectiondeform fit treloar.csv --model yeoh -o rubber.json --plot fit.png
  sectiondeform fit uniaxial=ut.csv planar=ps.csv --max-stretch 3
"""

from __future__ import annotations

import json
from pathlib import Path

from ..errors import CaseError
from ..materials import MATERIAL_MODELS


def add_args(parser) -> None:
    parser.add_argument("data", nargs="+", metavar="DATA", help="CSV file, or MODE=FILE for a file without a mode column")
    parser.add_argument("--model", choices=(*MATERIAL_MODELS, "all"), default="all", help="rubber model to fit (default: all)")
    parser.add_argument("--max-stretch", type=float, metavar="L", help="fit only the points with stretch <= L")
    parser.add_argument("--bulk-to-shear", type=float, metavar="K", help="bulk-to-shear ratio written with the constants (default 1000)")
    parser.add_argument("--plot", type=Path, metavar="FIG", help="figure of data against fit (.png, .svg, .pdf)")
    parser.add_argument("-o", "--output", type=Path, metavar="MATERIAL.json", help="write the fitted material object (needs one --model)")


def _read(args):
    from ..materials.fit import TestCurve, read_test_data

    curves = []
    for item in args.data:
        mode, sep, name = item.partition("=")
        path, mode = (Path(name), mode) if sep and not Path(item).exists() else (Path(item), None)
        curves += read_test_data(path, mode)
    if args.max_stretch is not None:
        if not args.max_stretch > 1.0:
            raise CaseError("--max-stretch", f"must be > 1, got {args.max_stretch:g}")
        kept = []
        for c in curves:
            keep = c.stretch <= args.max_stretch
            if keep.any():
                kept.append(TestCurve(c.mode, c.stretch[keep], c.stress[keep], c.source))
        if not kept:
            raise CaseError("--max-stretch", f"no point with stretch <= {args.max_stretch:g}")
        curves = kept
    return curves


def run(args) -> int:
    from ..io import check_figure_path, check_output_path
    from ..io.json import atomic_write
    from ..materials.fit import draw_fit, fit_material

    models = list(MATERIAL_MODELS) if args.model == "all" else [args.model]
    if args.output is not None:
        if len(models) != 1:
            raise CaseError("-o", f"choose the model to write with --model ({', '.join(MATERIAL_MODELS)})")
        check_output_path(args.output, "-o", (".json",), "material")
    if args.plot is not None:
        check_figure_path(args.plot, "--plot")
    curves = _read(args)
    fits = [fit_material(m, curves, bulk_to_shear=args.bulk_to_shear) for m in models]
    modes = [c.mode for c in curves]
    print("  " + " ".join(f"{c.mode}: {c.stretch.size} points, stretch {c.stretch.min():.3g}..{c.stretch.max():.3g};" for c in curves))
    print(f"  {'model':14s} {'constants (MPa)':58s} " + " ".join(f"{m:>12s}" for m in modes))
    for f in fits:
        m = f.material
        constants = ", ".join(f"{name} {getattr(m, name):.5g}" for name in m.constants)
        if m.model != "neo-hookean":
            constants += f" (mu0 {m.shear_modulus:.4g})"
        print(f"  {m.model:14s} {constants:58s} " + " ".join(f"{100 * f.errors[mode]:11.2f}%" for mode in modes))
        for w in f.warnings:
            print(f"  warning: {m.model} {w}; do not use it beyond")
    print("  errors: relative RMS, RMS(fit - data) / RMS(data), per mode")
    if args.plot is not None:
        from ..plot import write_figure

        write_figure(draw_fit(fits, curves), args.plot)
        print(f"  wrote {args.plot}")
    if args.output is not None:
        text = json.dumps(fits[0].material.to_json(), indent=1) + "\n"
        atomic_write(args.output, lambda tmp: tmp.write_text(text, encoding="utf-8"))
        print(f"  wrote {args.output}")
    return 0
