"""Run a parametric study: every row of STUDY, its table streamed to OUTDIR/rows.parquet.

STUDY is a section-study/1 JSON file (cases and the axes to vary: area_ratio,
model, element_size, bend_radius, crown, stretch, scale, rotate_deg,
translate_x, translate_y, targets) or a CSV with one row per line. Rows
already in OUTDIR's table are not redone, so an interrupted study run again
continues where it stopped. A failed row is recorded, never stops the study.

Example: sectiondeform sweep study.json -o out/ --workers 4 --csv
         sectiondeform sweep study.json -o out/ --scheduler tcp://10.0.0.5:8786
"""

from __future__ import annotations

from pathlib import Path

from ..errors import require


def add_args(parser) -> None:
    parser.add_argument("study", type=Path, help="study file (.json section-study/1, or .csv of rows)")
    parser.add_argument("-o", "--output", type=Path, required=True, metavar="OUTDIR", help="folder of the table and per-row files")
    parser.add_argument("--workers", type=int, metavar="N", help="worker processes (default: every core; 0: this process)")
    parser.add_argument("--scheduler", metavar="ADDRESS", help="run on Dask: 'local' (a LocalCluster) or tcp://HOST:PORT")
    parser.add_argument("--save", choices=("results", "figures", "none"), default="none",
                        help="per-row files in OUTDIR/results/: result JSON, or result JSON and PNG figure")
    parser.add_argument("--csv", action="store_true", help="also write OUTDIR/rows.csv")
    parser.add_argument("--reference", type=Path, metavar="RESULT", help="result JSON (one body, or as many as the cases): add each row's Hausdorff distance to it")
    parser.add_argument("--quiet", action="store_true", help="print nothing on success (no progress, no summary)")


def run(args) -> int:
    require("pyarrow", "sweep", "sectiondeform sweep")
    if args.scheduler is not None:
        require("distributed", "dask", "sectiondeform sweep --scheduler")
    from ..studies.api import _as_study, run_study

    study = _as_study(args.study, args.reference)
    info = run_study(study, args.output, workers=args.workers, scheduler=args.scheduler,
                     save=args.save, csv=args.csv, quiet=args.quiet)
    if args.quiet:
        return 0
    print(f"{study.name}: {info['rows']} rows, {info['skipped']} already done, {info['run']} run, {info['failed']} failed")
    print(f"  wrote {info['table']}" + (f", {info['csv']}" if info["csv"] else ""))
    return 0
