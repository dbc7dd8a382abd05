"""Fit rubber constants to homogeneous test data (CSV), and draw the fit.

Data: a CSV file with a header row naming the columns ``mode``,
``stretch`` and ``nominal_stress`` (MPa, force over initial area); rows
starting with ``#`` are comments, other columns are ignored. A file of one
mode may leave out the ``mode`` column and have its mode given by the
caller (``uniaxial=ut.csv`` on the command line).

Fit: the nominal stress of the three models is linear in their constants
(:func:`~sectiondeform.materials.homogeneous.stress_basis`), so the fit is
a bounded linear least-squares problem (:func:`scipy.optimize.lsq_linear`),
solved exactly. Each mode weighs the same: the cost is the sum over modes
of the squared relative RMS error

    e_m = RMS(P_fit − P_data) / RMS(P_data)   over the points of mode m.

Bounds: μ > 0 (neo-Hookean); c₁₀, c₀₁ ≥ 0 (Mooney–Rivlin, stable for all
deformations); c₁₀, c₃₀ ≥ 0 and c₂₀ free (Yeoh: a negative c₂₀ gives the
initial softening of filled rubber). The fitted rubber is checked for
stability over the data's stretch range (and its inverse, compression).
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import CaseError
from .homogeneous import MODES, mode_name, nominal_stress, stress_basis, unstable_modes
from .models import MATERIAL_MODELS

__all__ = ["TestCurve", "FitResult", "read_test_data", "fit_material", "draw_fit", "BOUNDS"]

BOUNDS = {
    "neo-hookean": ([0.0], [np.inf]),
    "mooney-rivlin": ([0.0, 0.0], [np.inf, np.inf]),
    "yeoh": ([0.0, -np.inf, 0.0], [np.inf, np.inf, np.inf]),
}
STRETCH_LIMIT = 1e3
"""Largest stretch, and largest inverse stretch (so λ ≥ 1e-3), of a test point: beyond, no rubber test, and the
stress basis (powers of λ up to 6 and down to -6 for Yeoh's c30) leaves the floats."""
STRESS_LIMIT = 1e6
"""Largest nominal stress of a test point, MPa (rubber breaks below 100): its squares stay finite."""


@dataclass(frozen=True, eq=False)
class TestCurve:
    """One mode's test points.

    Attributes
    ----------
    mode : str
        ``uniaxial``, ``equibiaxial`` or ``planar``.
    stretch : (N,) float64 ndarray
        Stretch in the loading direction.
    stress : (N,) float64 ndarray
        Nominal stress (force over initial area), MPa.
    source : str
        The file it came from.
    """

    __test__ = False  # not a pytest class

    mode: str
    stretch: np.ndarray
    stress: np.ndarray
    source: str = ""


@dataclass(frozen=True, eq=False)
class FitResult:
    """A fitted rubber and how well it fits.

    Attributes
    ----------
    material : NeoHookean or MooneyRivlin or Yeoh
    errors : dict of str to float
        Relative RMS error per mode, RMS(P_fit − P_data) / RMS(P_data).
    warnings : tuple of str
        Stability losses within the data's stretch range, one line each.
    max_stretch : float
        Largest stretch (or inverse stretch) of the data.
    """

    material: object
    errors: dict
    warnings: tuple
    max_stretch: float


def read_test_data(path, mode: str | None = None) -> list[TestCurve]:
    """Read test data from a CSV file, one :class:`TestCurve` per mode, in the order of ``MODES``.

    Parameters
    ----------
    path : str or Path
    mode : str, optional
        The mode of every row, for a file without a ``mode`` column.

    Returns
    -------
    list of TestCurve

    Raises
    ------
    CaseError
        One line naming the file, line and column: a missing column, a value
        that is not a finite number, a stretch not > 0, an unknown mode, no
        point off λ = 1.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as exc:
        raise CaseError(str(path), f"not a UTF-8 text file ({exc.reason} at byte {exc.start})") from None
    rows = [(n, row) for n, row in enumerate(csv.reader(text.splitlines()), start=1)
            if row and any(c.strip() for c in row) and not row[0].lstrip().startswith("#")]
    if not rows:
        raise CaseError(str(path), "no data: expected a header row 'mode,stretch,nominal_stress' and rows of numbers")
    header_line, header = rows[0]
    names = [c.strip().lower() for c in header]
    need = ["stretch", "nominal_stress"] + ([] if mode is not None else ["mode"])
    for name in need:
        if name not in names:
            hint = " (or give the file's mode, e.g. uniaxial=FILE)" if name == "mode" else ""
            raise CaseError(f"{path}, line {header_line}", f"no column {name!r} in the header {','.join(header)!r}{hint}")
    if mode is not None and "mode" in names:
        raise CaseError(f"{path}, line {header_line}", "the file has a mode column; give the mode there or with the file, not both")
    col = {name: names.index(name) for name in ("mode", "stretch", "nominal_stress") if name in names}
    fixed = None if mode is None else mode_name(mode, f"{path}: mode")
    points: dict[str, list[tuple[float, float]]] = {m: [] for m in MODES}
    for n, row in rows[1:]:
        def cell(name, n=n, row=row):
            i = col[name]
            if i >= len(row) or not row[i].strip():
                raise CaseError(f"{path}, line {n}, column {name}", "empty")
            return row[i].strip()

        def value(name, cell=cell, n=n):
            raw = cell(name)
            try:
                v = float(raw)
            except ValueError:
                raise CaseError(f"{path}, line {n}, column {name}", f"expected a number, got {raw[:40]!r}") from None
            if not math.isfinite(v):
                raise CaseError(f"{path}, line {n}, column {name}", f"expected a finite number, got {raw[:40]!r}")
            return v

        m = fixed if fixed is not None else mode_name(cell("mode"), f"{path}, line {n}, column mode")
        lam = value("stretch")
        if not 1.0 / STRETCH_LIMIT <= lam <= STRETCH_LIMIT:
            raise CaseError(f"{path}, line {n}, column stretch",
                            f"must be within [{1.0 / STRETCH_LIMIT:g}, {STRETCH_LIMIT:g}], got {lam:g}")
        stress = value("nominal_stress")
        if not abs(stress) <= STRESS_LIMIT:
            raise CaseError(f"{path}, line {n}, column nominal_stress",
                            f"must be within +-{STRESS_LIMIT:g} MPa, got {stress:g}; give the stress in MPa")
        points[m].append((lam, stress))
    curves = []
    for m in MODES:
        if not points[m]:
            continue
        arr = np.array(points[m], dtype=np.float64)
        if not np.any(arr[:, 0] != 1.0):
            raise CaseError(f"{path}: {m}", "every point is at stretch 1; nothing to fit")
        curves.append(TestCurve(m, arr[:, 0], arr[:, 1], str(path)))
    if not curves:
        raise CaseError(str(path), "no data rows after the header")
    return curves


def merge_curves(curves) -> list[TestCurve]:
    """Curves of the same mode joined into one, in the order of ``MODES``."""
    out = []
    for m in MODES:
        same = [c for c in curves if c.mode == m]
        if same:
            out.append(TestCurve(m, np.concatenate([c.stretch for c in same]), np.concatenate([c.stress for c in same]),
                                 ", ".join(dict.fromkeys(c.source for c in same))))
    return out


def _check_points(curve: TestCurve) -> None:
    """Refuse a curve (read, or built in Python) whose stretches or stresses leave the range a fit can take."""
    lam, stress = np.asarray(curve.stretch, dtype=np.float64), np.asarray(curve.stress, dtype=np.float64)
    if lam.shape != stress.shape or lam.ndim != 1:
        raise CaseError(f"data: {curve.mode}", f"{lam.size} stretches for {stress.size} stresses; give one of each per point")
    bad = ~((lam >= 1.0 / STRETCH_LIMIT) & (lam <= STRETCH_LIMIT))
    if bad.any():
        raise CaseError(f"data: {curve.mode}", f"stretch {lam[bad][0]:g} (point {int(np.argmax(bad))}): a stretch must "
                                                f"be within [{1.0 / STRETCH_LIMIT:g}, {STRETCH_LIMIT:g}]")
    bad = ~(np.abs(stress) <= STRESS_LIMIT)
    if bad.any():
        raise CaseError(f"data: {curve.mode}", f"nominal stress {stress[bad][0]:g} (point {int(np.argmax(bad))}): a "
                                                f"stress must be a finite number within +-{STRESS_LIMIT:g} MPa")


def fit_material(model: str, curves, bulk_to_shear: float | None = None, bulk_modulus: float | None = None) -> FitResult:
    """Least-squares fit of a rubber model's constants to test curves.

    Parameters
    ----------
    model : {"neo-hookean", "mooney-rivlin", "yeoh"}
    curves : sequence of TestCurve
        Any of the three modes; several curves of one mode are joined.
    bulk_to_shear, bulk_modulus : float, optional
        The volumetric constant of the fitted rubber (incompressible tests
        say nothing about it); at most one, default ``bulk_to_shear`` 1000.

    Returns
    -------
    FitResult

    Raises
    ------
    CaseError
        Unknown model, fewer points than constants, or data giving no
        positive shear modulus.

    Examples
    --------
    >>> from sectiondeform.materials import MooneyRivlin
    >>> lam = np.linspace(1.1, 3.0, 8)
    >>> data = [TestCurve("uniaxial", lam, nominal_stress(MooneyRivlin(0.2, 0.05), "uniaxial", lam))]
    >>> fit = fit_material("mooney-rivlin", data)
    >>> round(fit.material.c10, 9), round(fit.material.c01, 9), fit.errors["uniaxial"] < 1e-12
    (0.2, 0.05, True)
    """
    from scipy.optimize import lsq_linear

    if model not in MATERIAL_MODELS:
        raise CaseError("model", f"unknown material model {model!r}; use one of {', '.join(MATERIAL_MODELS)}")
    cls = MATERIAL_MODELS[model]
    curves = merge_curves(curves)
    for c in curves:
        _check_points(c)
    n_points = sum(c.stretch.size for c in curves)
    if n_points < len(cls.constants):
        raise CaseError("data", f"{n_points} point(s) for {len(cls.constants)} constants of {model}; give more points")
    rows, rhs = [], []
    for c in curves:
        scale = math.sqrt(float(np.mean(c.stress**2)) * c.stress.size)
        if scale == 0.0:
            raise CaseError(f"data: {c.mode}", "every nominal stress is 0; nothing to fit")
        rows.append(stress_basis(model, c.mode, c.stretch) / scale)
        rhs.append(c.stress / scale)
    A, b = np.vstack(rows), np.concatenate(rhs)
    col_scale = np.maximum(np.abs(A).max(axis=0), 1e-300)  # columns of very different sizes (Yeoh's c30)
    if np.linalg.matrix_rank(A / col_scale, tol=1e-10 * np.sqrt(A.shape[0])) < A.shape[1]:
        raise CaseError("data", f"these data do not set the {len(cls.constants)} constants of {model} apart "
                                "(planar data alone give only c10 + c01); add another mode or fit a model with fewer constants")
    lo, hi = BOUNDS[model]
    sol = lsq_linear(A / col_scale, b, bounds=(np.array(lo) * col_scale, np.array(hi) * col_scale), method="bvls")
    x = sol.x / col_scale
    if not x[0] > 0:
        raise CaseError("data", f"the {model} fit gives no positive shear modulus (the data do not rise with stretch)")
    material = cls(*x, bulk_to_shear=bulk_to_shear, bulk_modulus=bulk_modulus)
    errors = {}
    for c in curves:
        fitted = nominal_stress(material, c.mode, c.stretch)
        errors[c.mode] = math.sqrt(float(np.mean((fitted - c.stress) ** 2)) / float(np.mean(c.stress**2)))
    lam_all = np.concatenate([c.stretch for c in curves])
    max_stretch = float(np.max(np.maximum(lam_all, 1.0 / lam_all)))
    if not (np.isfinite(x).all() and all(math.isfinite(e) for e in errors.values())):
        raise CaseError("data", f"the {model} fit of these data gives no finite constants or errors; check the units "
                                "(MPa) and the stretches of the data")
    warnings = tuple(unstable_modes(material, max_stretch)) if max_stretch > 1.0 else ()
    return FitResult(material, errors, warnings, max_stretch)


_MODE_COLOURS = {"uniaxial": "tab:blue", "equibiaxial": "tab:orange", "planar": "tab:green"}
_MODEL_STYLES = {"neo-hookean": ":", "mooney-rivlin": "--", "yeoh": "-"}


def draw_fit(fits, curves, fig=None, zoom_stretch: float = 2.0):
    """Draw test data against fitted curves: the whole range, and a zoom on small stretch.

    Parameters
    ----------
    fits : sequence of FitResult
    curves : sequence of TestCurve
    fig : matplotlib.figure.Figure, optional
        Drawn into; a new figure of its own (not pyplot's) by default.
    zoom_stretch : float
        Right end of the zoom panel (only drawn when the data go beyond it).

    Returns
    -------
    matplotlib.figure.Figure
    """
    from ..plot import new_figure

    curves = merge_curves(curves)
    lam_max = max(float(c.stretch.max()) for c in curves)
    zoom = lam_max > zoom_stretch * 1.05
    if fig is None:
        fig = new_figure(figsize=(11 if zoom else 6.5, 4.8), layout="constrained")
    axes = fig.subplots(1, 2 if zoom else 1, squeeze=False)[0]
    for k, ax in enumerate(axes):
        right = zoom_stretch if k == 1 else None
        for c in curves:
            colour = _MODE_COLOURS[c.mode]
            keep = c.stretch <= right if right else np.ones(c.stretch.size, bool)
            ax.plot(c.stretch[keep], c.stress[keep], "o", color=colour, ms=4, mfc="none", label=f"{c.mode} data")
            lo = min(1.0, float(c.stretch.min()))
            lam = np.linspace(lo, right or float(c.stretch.max()), 200)
            for f in fits:
                m = f.material
                ax.plot(lam, nominal_stress(m, c.mode, lam), _MODEL_STYLES[m.model], color=colour, lw=1.3,
                        label=f"{m.model} ({100 * f.errors[c.mode]:.1f} %)")
        ax.set_xlabel("stretch λ")
        ax.set_ylabel("nominal stress [MPa]")
        ax.grid(True, lw=0.3, alpha=0.5)
        ax.set_title("test data and fits" if k == 0 else f"zoom: λ ≤ {zoom_stretch:g}")
    axes[0].legend(fontsize=7, ncols=len(curves), loc="upper left", title="model (relative RMS error)", title_fontsize=7)
    return fig
