"""Parametric studies: many targets, laws, models and sections, on local cores or a Dask cluster.

A study (``section-study/1`` JSON, or a CSV of rows) expands into rows
(:mod:`.study`); rows are grouped by section and cut into chunks
(:mod:`.engines`); a worker prepares each section once and re-deforms it per
row (:mod:`.runner`); finished rows stream into a Parquet table
(:mod:`.table`). :func:`sweep` does it all and returns the table.
"""

from __future__ import annotations

from .api import run_study, sweep
from .study import Row, Study, StudyError, load_study, study_from_dict

__all__ = ["Row", "Study", "StudyError", "load_study", "run_study", "study_from_dict", "sweep"]
