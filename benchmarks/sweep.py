"""Benchmark of parametric studies on the paper example: engine overhead, speed-up, a large study.

Run: python benchmarks/sweep.py [--big N]   (prints a Markdown table)
"""

from __future__ import annotations

import argparse
import json
import resource
import shutil
import tempfile
import time
from pathlib import Path

import sectiondeform as sd
from sectiondeform.studies.api import run_study
from sectiondeform.studies.study import study_from_dict


def _study(folder: Path, model: str, n: int):
    shutil.copy(sd.example_case_path(), folder / "paper-example.json")
    vary = {"model": [model], "area_ratio": {"start": 0.7, "stop": 0.95, "num": n}}
    return study_from_dict({"format": "section-study/1", "cases": [{"case": "paper-example.json", "vary": vary}]}, folder)


def _in_process(model: str, n: int) -> float:
    """Seconds per re-deformation in this process (section prepared once)."""
    d = sd.Deformer(sd.load_case(sd.example_case_path()), model=model)
    d.deform()
    t = time.perf_counter()
    for i in range(n):
        d.deform(None, sd.AreaRatio(0.7 + 0.25 * i / max(1, n - 1)))
    return (time.perf_counter() - t) / n


def _timed(study, **kw) -> float:
    out = tempfile.mkdtemp()
    try:
        t = time.perf_counter()
        run_study(study, out, **kw)
        return time.perf_counter() - t
    finally:
        shutil.rmtree(out)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--big", type=int, default=100_000)
    args = ap.parse_args()
    tmp = Path(tempfile.mkdtemp())
    rows = {"paper": 4000, "hyperelastic": 200}
    print("| model | rows | in-process ms/row | 1 worker ms/row | ratio | 2 workers s | speed-up | Dask 2 workers s |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for model, n in rows.items():
        study = _study(tmp, model, n)
        inproc = _in_process(model, n)
        one = _timed(study, workers=1)
        two = _timed(study, workers=2)
        dask = _timed(study, workers=2, scheduler="local")
        print(f"| {model} | {n} | {1e3 * inproc:.3f} | {1e3 * one / n:.3f} | {one / n / inproc:.2f} | "
              f"{two:.2f} | {one / two:.2f} | {dask:.2f} |")
    big = _study(tmp, "paper", args.big)
    out = tempfile.mkdtemp()
    t = time.perf_counter()
    run_study(big, out, workers=2)
    wall = time.perf_counter() - t
    size = (Path(out) / "rows.parquet").stat().st_size
    me = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    kids = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    print(f"\n{args.big} paper rows on 2 workers: {wall:.1f} s wall ({args.big / wall:.0f} rows/s), "
          f"peak RSS {me:.0f} MB main process, {kids:.0f} MB largest worker, table {size / 1e6:.1f} MB")
    print(json.dumps({"big_rows": args.big, "wall_s": wall, "rss_main_mb": me, "rss_worker_mb": kids}))
    shutil.rmtree(out)
    shutil.rmtree(tmp)


if __name__ == "__main__":
    main()
