"""A one-line progress bar on stderr: rows done, failures, rows per second, time left."""

from __future__ import annotations

import math
import sys
import time

__all__ = ["Progress"]


class Progress:
    """Progress of a study, redrawn at most every ``interval`` seconds.

    Parameters
    ----------
    total : int
        Rows to run.
    quiet : bool
        Draw nothing.
    """

    def __init__(self, total: int, quiet: bool = False, stream=None, interval: float = 0.2):
        self.total, self.quiet, self.stream, self.interval = total, quiet, stream or sys.stderr, interval
        self.done = self.failed = 0
        self.start = self._drawn = time.monotonic()

    def update(self, records: list[dict]) -> None:
        """Count finished rows and redraw."""
        self.done += len(records)
        self.failed += sum(not r["ok"] for r in records)
        if time.monotonic() - self._drawn >= self.interval:
            self.draw()

    def line(self) -> str:
        """The progress line."""
        elapsed = max(time.monotonic() - self.start, 1e-9)
        rate = self.done / elapsed
        left = (self.total - self.done) / rate if rate > 0 else float("nan")
        width = 24
        fill = int(width * self.done / self.total) if self.total else width
        eta = "--:--" if math.isnan(left) else f"{int(left) // 60:02d}:{int(left) % 60:02d}"
        return (f"[{'#' * fill}{'.' * (width - fill)}] {self.done}/{self.total} rows, "
                f"{self.failed} failed, {rate:.1f} rows/s, {eta} left")

    def draw(self, end: str = "") -> None:
        """Redraw the line in place."""
        self._drawn = time.monotonic()
        if not self.quiet:
            print(f"\r{self.line()}", end=end, file=self.stream, flush=True)

    def close(self) -> None:
        """Draw the final line and end it."""
        self.draw(end="\n")
