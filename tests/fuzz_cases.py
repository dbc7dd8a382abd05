"""Generated cases for the fuzz tests and the fuzz benchmark, and the classification of their outcomes.

:func:`cases` is a hypothesis strategy of case dictionaries: sections of
many sizes and places (box, roof, dome and B-spline uppers over a straight,
wavy or arched lower curve), targets that stretch, shrink, bend, turn over
or collapse, laws and options of both models, and, for part of the
examples, one damage (a coordinate written as a string, an integer too
large for a float, NaN, a key missing or misspelt, an empty curve, a value
of the wrong type).

:func:`outcome_api` and :func:`outcome_cli` run one case and say what
happened: ``ok`` (a result that passes :func:`sectiondeform.verify.check_result`),
``refused:<ErrorClass>`` (one clean line) or ``failure:<what>`` (the
promise is broken: a crash, a multi-line message, a check that fails, a
NaN, a numpy warning, an exit status other than 0 and 2, output left
behind by a refusal, no answer in time).
"""

from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import time
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely
from hypothesis import strategies as st

import sectiondeform as sd
from sectiondeform.pappus import volume as pappus_volume
from sectiondeform.problem import V1
from sectiondeform.verify import (
    AREA_LAW_TOLERANCE,
    ENDS_TOLERANCE,
    INITIAL_AREA_TOLERANCE,
    area_of,
    check_result,
    inverted,
)

__all__ = ["Outcome", "cases", "outcome_api", "outcome_cli", "outcome_cli_file", "TIME_LIMIT_S"]

TIME_LIMIT_S = 20.0
"""CPU seconds one case may take; the stages' size and work bounds keep every case far below it.

CPU time, not wall time: a hang is work without end, and CPU time measures
work whatever the load of the machine (the test suite runs beside others).
"""

WALL_FACTOR = 6.0
"""The command line's process is also killed after this many times the limit in wall time (a process
that waits without working)."""

# -- geometry ----------------------------------------------------------------


def _arc_through(a, b, bulge):
    """An arc case-curve from ``a`` to ``b`` whose midpoint sits ``bulge`` x chord to the left of a->b."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    chord = b - a
    c = float(np.hypot(*chord))
    s = abs(bulge) * c  # sagitta
    r = (c * c / 4 + s * s) / (2 * s)
    left = np.array([-chord[1], chord[0]]) / c
    # Centre on the side away from the bulge.
    side = 1.0 if bulge > 0 else -1.0
    center = (a + b) / 2 - side * left * (r - s)
    a0 = math.degrees(math.atan2(*(a - center)[::-1]))
    a1 = math.degrees(math.atan2(*(b - center)[::-1]))
    if bulge > 0:  # clockwise from a to b: the arc passes to the left of a->b
        while a1 > a0:
            a1 -= 360.0
    else:
        while a1 < a0:
            a1 += 360.0
    arc = {"arc": {"center": center.tolist(), "radius": r, "start_deg": a0, "end_deg": a1}}
    end = center + r * np.array([math.cos(math.radians(a1)), math.sin(math.radians(a1))])
    return arc, end


@st.composite
def _section(draw):
    """Lower curve A->B and upper curve B->A of a closed section, A, B ((2,) arrays) and its size."""
    scale = draw(st.sampled_from([1.0, 10.0, 100.0, 0.1, 1e-3, 1e4])) * draw(st.floats(0.5, 2.0))
    width = scale
    height = scale * draw(st.sampled_from([0.5, 0.2, 1.0, 3.0, 0.02]))
    origin = np.array(draw(st.sampled_from([(0.0, 0.0), (1e3, -50.0), (-1e5, 2e5)]))) * (scale if draw(st.booleans()) else 1.0)
    a = origin
    lower_kind = draw(st.sampled_from(["line", "wavy", "arch", "sag"]))
    if lower_kind == "line":
        b = origin + [width, 0.0]
        lower = {"polyline": [a.tolist(), b.tolist()]}
    elif lower_kind == "wavy":
        n = draw(st.integers(3, 40))
        amp = height * draw(st.sampled_from([0.01, 0.1, 0.4]))
        x = np.linspace(0.0, width, n)
        pts = origin + np.column_stack((x, amp * np.sin(x / width * 2 * math.pi * draw(st.integers(1, 4)))))
        pts[-1, 1] = origin[1]
        lower = {"polyline": pts.tolist()}
        b = pts[-1]
    else:  # an arc bulging up (arch) or down (sag), within the section's height
        bulge = draw(st.sampled_from([0.02, 0.1, 0.3])) * (1 if lower_kind == "arch" else -1)
        lower, b = _arc_through(a, origin + [width, 0.0], bulge)
    upper_kind = draw(st.sampled_from(["box", "roof", "dome", "bspline"]))
    top = max(height, 1e-12)
    if upper_kind == "box":
        upper = {"polyline": [b.tolist(), (b + [0, top]).tolist(), (a + [0, top]).tolist(), a.tolist()]}
    elif upper_kind == "roof":
        k = draw(st.integers(1, 12))
        xs = np.sort(draw(st.lists(st.floats(0.0, 1.0), min_size=k, max_size=k)))[::-1]
        if _rarely(draw):  # wild: the roof's vertices in any order (may cross)
            xs = np.array(draw(st.permutations(list(xs))))
        ys = np.array(draw(st.lists(st.floats(0.05, 1.0), min_size=k, max_size=k)))
        roof = np.column_stack((a[0] + xs * (b[0] - a[0]), a[1] + ys * top + 0.5 * (b[1] - a[1])))
        upper = {"polyline": [b.tolist(), *roof.tolist(), a.tolist()]}
    elif upper_kind == "dome":
        # Negative bulge: to the right of B->A, above the lower curve.
        upper = _arc_through(b, a, -draw(st.sampled_from([0.1, 0.3, 0.5, 0.8])))[0]
    else:
        m = draw(st.integers(2, 8))
        inner = [[b[0] + (a[0] - b[0]) * (i + 0.5) / m, b[1] + top * draw(st.floats(0.1, 1.5))] for i in range(m)]
        upper = {"bspline": {"degree": draw(st.sampled_from([2, 3])), "control_points": [b.tolist(), *inner, a.tolist()]}}
    return lower, upper, a, b, scale


@st.composite
def _target(draw, a, b, scale):
    """A target curve A'->B' of some length and shape."""
    chord = float(np.hypot(*(b - a)))
    length = chord * draw(st.sampled_from([1.0, 0.9, 1.3, 0.6, 0.1, 3.0]))
    turn = math.radians(draw(st.sampled_from([0.0, 0.0, 15.0, -40.0, 90.0, 180.0])))
    start = a + np.array(draw(st.sampled_from([(0.0, 0.0), (0.3, -0.2), (-5.0, 3.0)]))) * scale
    d = np.array([math.cos(turn), math.sin(turn)])
    end = start + length * d
    kind = draw(st.sampled_from(["line", "arc", "wave", "reversed"]))
    if _rarely(draw, 20):
        kind = "point"
    if kind == "line":
        return {"polyline": [start.tolist(), end.tolist()]}
    if kind == "arc":
        return _arc_through(start, end, draw(st.sampled_from([0.05, 0.2, 0.45, -0.1, -0.4])))[0]
    if kind == "wave":
        n = draw(st.integers(3, 30))
        t = np.linspace(0.0, 1.0, n)
        amp = length * draw(st.sampled_from([0.02, 0.1, 0.3]))
        normal = np.array([-d[1], d[0]])
        pts = start + np.outer(t * length, d) + np.outer(amp * np.sin(t * math.pi * draw(st.integers(1, 5))), normal)
        return {"polyline": pts.tolist()}
    if kind == "point":  # collapsed: both ends the same point
        return {"polyline": [start.tolist(), start.tolist()]}
    return {"polyline": [end.tolist(), start.tolist()]}


_BAD_NUMBERS = ["0.8", 0, -1.0, 10**400, float("nan"), float("inf"), True, None, [1.0], 1e300]


def _rarely(draw, one_in: int = 10) -> bool:
    """True for about one example in ``one_in`` (shrinks to False)."""
    # A middle value: hypothesis draws the ends of a range far more often than 1 / one_in.
    return draw(st.integers(0, one_in - 1)) == one_in // 2


@st.composite
def _law_and_options(draw, scale):
    if _rarely(draw):
        ratio = draw(st.sampled_from(_BAD_NUMBERS))
    else:
        ratio = draw(st.one_of(st.sampled_from([0.8, 0.5, 0.95, 1.0, 1.2]), st.floats(0.3, 1.5)))
    law = {"area_ratio": ratio}
    model = draw(st.sampled_from(["paper", "hyperelastic"]))
    if _rarely(draw, 20):
        model = draw(st.sampled_from(["hyperelastc", "Paper", 3, None]))
    options = {"model": model}
    if draw(st.booleans()):
        good = st.sampled_from([1e-3, 1e-4, 1e-2, 0.1]).map(lambda f: f * scale)
        options["chordal_error"] = draw(st.sampled_from(_BAD_NUMBERS) if _rarely(draw) else good)
    if model == "hyperelastic" and draw(st.booleans()):
        bad = _rarely(draw)
        options["elements_through_thickness"] = draw(st.sampled_from([0, -2, 100, "4"] if bad else [2, 3, 4, 6, 8]))
    if model == "hyperelastic" and _rarely(draw, 4):
        bad = _rarely(draw, 3)
        options["bulk_to_shear"] = draw(st.sampled_from([0.0, -5.0, 1e12] if bad else [100.0, 10.0, 1e4]))
    if _rarely(draw, 6):
        options["refine"] = draw(st.sampled_from([2.0, 1.0, 0.5, 65.0]))
    extra = None
    if _rarely(draw, 5):
        extra = draw(st.sampled_from(["x-mine", "extra", "chordal_eror", "through_thickness", "modle"]))
    if extra == "extra":
        options["extra"] = {"anything": [1, 2]}
    elif extra is not None:
        options[extra] = 1.0
    return law, options


_DAMAGES = ["string-coordinate", "huge-int", "nan", "drop-key", "unknown-key", "empty-curve",
            "one-point-curve", "wrong-type", "units", "format"]


def _coordinate_paths(d, path=()):
    """Paths to every number inside a point list of the case dict."""
    if isinstance(d, dict):
        for k, v in d.items():
            yield from _coordinate_paths(v, (*path, k))
    elif isinstance(d, list):
        if len(d) == 2 and all(isinstance(x, float) for x in d):
            yield (*path, 0)
            yield (*path, 1)
        else:
            for i, v in enumerate(d):
                yield from _coordinate_paths(v, (*path, i))


def _set(d, path, value):
    for k in path[:-1]:
        d = d[k]
    d[path[-1]] = value


@st.composite
def _damaged(draw, case):
    kind = draw(st.sampled_from(_DAMAGES))
    case = json.loads(json.dumps(case))  # a deep copy, as JSON gives it
    if kind in ("string-coordinate", "huge-int", "nan"):
        paths = list(_coordinate_paths({k: case[k] for k in ("lower", "upper", "target")}))
        path = draw(st.sampled_from(paths))
        old = case
        for k in path:
            old = old[k]
        value = {"string-coordinate": str(old), "huge-int": 10**400, "nan": float("nan")}[kind]
        _set(case, path, value)
    elif kind == "drop-key":
        del case[draw(st.sampled_from(["lower", "upper", "target", "law"]))]
    elif kind == "unknown-key":
        case[draw(st.sampled_from(["traget", "Law", "option"]))] = {}
    elif kind == "empty-curve":
        case[draw(st.sampled_from(["lower", "upper", "target"]))] = {"polyline": []}
    elif kind == "one-point-curve":
        case[draw(st.sampled_from(["lower", "target"]))] = {"polyline": [[0.0, 0.0]]}
    elif kind == "wrong-type":
        case[draw(st.sampled_from(["lower", "law", "options"]))] = draw(st.sampled_from([[], "x", 3, None]))
    elif kind == "units":
        case["units"] = draw(st.sampled_from(["milimeter", "", 5]))
    else:
        case["format"] = draw(st.sampled_from(["section-case/9", None, "case"]))
    return case


@st.composite
def cases(draw, damage: float = 0.25, models: tuple[str, ...] | None = None):
    """A case dictionary, as a JSON file would give it.

    Parameters
    ----------
    damage : float
        Share of the examples that get one damage (about; drawn per example).
    models : tuple of str, optional
        Force ``options.model`` to one of these (a valid model name).
    """
    lower, upper, a, b, scale = draw(_section())
    target = draw(_target(a, b, scale))
    law, options = draw(_law_and_options(scale))
    if models is not None:
        options["model"] = draw(st.sampled_from(models))
    case = {"format": "section-case/1", "name": "fuzz", "units": "mm", "lower": lower, "upper": upper,
            "target": target, "law": law, "options": options}
    if draw(st.integers(1, 1000)) in range(1 + round(1000 * (1.0 - damage) / 2), 1 + round(1000 * (1.0 + damage) / 2)):
        case = draw(_damaged(case))
    return case


# -- outcomes ------------------------------------------------------------------


@dataclass(frozen=True)
class Outcome:
    """What one case gave: ``kind`` is ``ok``, ``refused:<ErrorClass>`` or ``failure:<what>``; CPU ``seconds``."""

    kind: str
    detail: str = ""
    seconds: float = 0.0

    @property
    def failed(self) -> bool:
        return self.kind.startswith("failure")


class _TimeLimit(BaseException):
    """Raised by the alarm; a BaseException so that no ``except Exception`` of the library eats it."""


def _alarm(signum, frame):
    raise _TimeLimit()


def _children_cpu() -> float:
    """CPU seconds used by this process's finished children (one child at a time here)."""
    import resource

    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _limit_cpu(seconds: float):
    """For ``preexec_fn``: the kernel stops the process (SIGXCPU) after ``seconds`` of CPU time."""
    import resource

    def set_limit():
        soft = max(1, math.ceil(seconds))
        resource.setrlimit(resource.RLIMIT_CPU, (soft, soft + 5))

    return set_limit


def outcome_api(case: dict | Path, limit_s: float = TIME_LIMIT_S) -> Outcome:
    """Run ``case`` (a dict, or a case file) through ``case_from_dict`` (``load_case``) and ``deform``; classify.

    ``ok`` needs a result that passes every check of
    :func:`~sectiondeform.verify.check_result` (a ``section-case/1`` case)
    or of :func:`check_bodies` (``section-case/2``) and no ``RuntimeWarning``
    (numpy's overflow, invalid value...) on the way.

    The time limit is on the process's CPU time (``ITIMER_PROF``, main
    thread only; it repeats every second in case the first signal lands
    where an exception is swallowed): it interrupts Python code between
    bytecodes, so a stage that loops in Python is caught; compiled code
    runs on to its end, which the command-line runs (:func:`outcome_cli`)
    cover: the kernel stops those processes.
    """
    t0 = time.process_time()
    old = signal.signal(signal.SIGPROF, _alarm)
    signal.setitimer(signal.ITIMER_PROF, limit_s, 1.0)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                if isinstance(case, Path):
                    parsed = sd.load_case(case)
                else:  # as a JSON file would give it: a fresh copy, tuples as lists
                    parsed = sd.case_from_dict(json.loads(json.dumps(case)))
                result = sd.deform(parsed)
                fails = check_result(result, parsed) if parsed.dialect == V1 else check_bodies(result)
            except sd.SectionDeformError as exc:
                message = str(exc)
                if not message or "\n" in message:
                    return Outcome("failure:message", repr(message), time.process_time() - t0)
                return Outcome(f"refused:{type(exc).__name__}", message, time.process_time() - t0)
            except _TimeLimit:
                return Outcome("failure:slow", f"no answer within {limit_s} s of CPU time", time.process_time() - t0)
            except Exception as exc:  # the promise is broken: report, do not hide
                return Outcome(f"failure:crash:{type(exc).__name__}", str(exc)[:300], time.process_time() - t0)
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, old)
    seconds = time.process_time() - t0
    numeric = [w for w in caught if issubclass(w.category, RuntimeWarning)]
    if numeric:
        return Outcome("failure:warning", str(numeric[0].message), seconds)
    if fails:
        return Outcome("failure:wrong", "; ".join(fails), seconds)
    return Outcome("ok", "", seconds)


def check_bodies(result) -> list[str]:
    """Every failed check of a result body by body, as one-line strings naming the body; empty when it passes.

    For each body: finite points and figures, its law met by the area (or
    the volume of revolution) recomputed from its deformed contour, its
    reported final area and initial area those of its contours, a simple
    deformed contour whose upper points run from the lower curve's end back
    to its start, and no inverted element in either mesh.
    """
    fails = []
    for body in result.bodies:
        fails += [f"{body.name}: {f}" for f in _body_fails(body, result.axis)]
    return fails


def _body_fails(body, axis) -> list[str]:
    arrays = [body.lower, body.upper, body.contour, body.initial_contour, body.initial_mesh.points,
              body.final_mesh.points]
    if not all(np.isfinite(np.asarray(a, dtype=np.float64)).all() for a in arrays) \
            or not np.isfinite([body.area_initial, body.area_final, body.target, body.final]).all():
        return ["finite: the result holds NaN or infinite values"]
    contour = np.asarray(body.contour, dtype=np.float64)
    final = area_of(contour) if body.measure == "area" else pappus_volume(contour, axis)
    fails = []
    if abs(final - body.target) > AREA_LAW_TOLERANCE * body.target:
        fails.append(f"{body.measure}_law: final {final!r} vs target {body.target!r}")
    # The reported initial area is the curves' exact one, the initial contour their polygon within the
    # chordal error: they agree to the section's area tolerance (INITIAL_AREA_TOLERANCE), not to 1e-8.
    for what, reported, points, tol in (("area_reported", body.area_final, contour, AREA_LAW_TOLERANCE),
                                        ("initial_reported", body.area_initial, body.initial_contour,
                                         INITIAL_AREA_TOLERANCE)):
        recomputed = area_of(np.asarray(points, dtype=np.float64))
        if abs(recomputed - reported) > tol * recomputed:
            fails.append(f"{what}: reported {reported!r} vs recomputed {recomputed!r}")
    if not shapely.is_simple(shapely.linearrings(contour)):
        fails.append("simple: the deformed contour crosses itself")
    lo, up = np.asarray(body.lower), np.asarray(body.upper)
    if max(np.hypot(*(up[0] - lo[-1])), np.hypot(*(up[-1] - lo[0]))) > ENDS_TOLERANCE * np.hypot(*np.ptp(contour, axis=0)):
        fails.append("ends: the upper points do not run from the lower curve's end back to its start")
    for mesh, name in ((body.initial_mesh, "initial_mesh"), (body.final_mesh, "final_mesh")):
        bad = inverted(mesh)
        if bad:
            fails.append(f"{name}: {bad}")
    return fails


def outcome_cli(case: dict, folder: Path, limit_s: float = TIME_LIMIT_S) -> Outcome:
    """Write ``case`` to ``folder`` and run it through the command line (:func:`outcome_cli_file`)."""
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "case.json"
    path.write_text(json.dumps(case), encoding="utf-8")
    return outcome_cli_file(path, folder / "out.json", limit_s)


def outcome_cli_file(path: Path, out: Path, limit_s: float = TIME_LIMIT_S, extra: tuple[str, ...] = ()) -> Outcome:
    """Run ``sectiondeform deform PATH -o OUT [EXTRA...]`` in a new process, killed after ``limit_s``, and classify.

    Exit 0: the result file exists and its contour is finite, meets the law
    and is simple; stderr holds no traceback and no warning of Python's.
    Exit 2: exactly one line on stderr, no result file. Anything else
    (another exit status, a kill at the time limit) is a failure.
    """
    out.unlink(missing_ok=True)
    env = {**os.environ, "PYTHONWARNINGS": "default"}  # show every warning, as a user's shell may
    t0 = _children_cpu()
    try:
        run = subprocess.run([sys.executable, "-m", "sectiondeform", "deform", str(path), "-o", str(out), *extra],
                             capture_output=True, text=True, timeout=WALL_FACTOR * limit_s, env=env,
                             preexec_fn=_limit_cpu(limit_s))
    except subprocess.TimeoutExpired:
        return Outcome("failure:slow", f"killed after {WALL_FACTOR * limit_s:g} s wall time", _children_cpu() - t0)
    seconds = _children_cpu() - t0
    if run.returncode in (-signal.SIGXCPU, -signal.SIGKILL):
        return Outcome("failure:slow", f"stopped after {limit_s:g} s of CPU time", seconds)
    err = run.stderr
    if "Traceback" in err or "Warning:" in err:
        return Outcome("failure:stderr", err[-600:], seconds)
    if run.returncode == 2:
        lines = [line for line in err.splitlines() if line.strip()]
        if len(lines) != 1:
            return Outcome("failure:message", err[-600:], seconds)
        if out.exists():
            return Outcome("failure:output-left", lines[0], seconds)
        return Outcome("refused:exit-2", lines[0], seconds)
    if run.returncode != 0:
        return Outcome(f"failure:exit-{run.returncode}", err[-600:], seconds)
    if not out.exists():
        return Outcome("failure:no-output", run.stdout[-300:], seconds)
    return _checked_output(out, seconds)


def _checked_output(out: Path, seconds: float) -> Outcome:
    """The promise on a written result file: finite contour, law met, simple (recomputed here)."""
    data = json.loads(out.read_text(encoding="utf-8"))
    fails = []
    for body in data.get("bodies", [data]):  # section-result/2: each body's contour
        contour = np.asarray(body["contour"], dtype=np.float64)
        target = body["area"].get("target")
        where = f"{body['name']}: " if "bodies" in data else ""
        if not np.isfinite(contour).all():
            fails.append(f"{where}finite")
        elif target is not None and abs(area_of(contour) - target) > 1e-8 * target:
            fails.append(f"{where}area_law: {area_of(contour)!r} vs {target!r}")
        elif not shapely.is_simple(shapely.linearrings(contour)):
            fails.append(f"{where}simple")
    if fails:
        return Outcome("failure:wrong", "; ".join(fails), seconds)
    return Outcome("ok", "", seconds)


# -- assemblies, bodies of revolution, rigid parts (section-case/2) ------------------


def _rubber(draw, modulus: float) -> dict:
    """A material of one of the rubber models, of shear modulus about ``modulus``."""
    kind = draw(st.sampled_from(["neo-hookean", "neo-hookean", "mooney-rivlin", "yeoh", "none"]))
    if kind == "none":
        return {}
    if kind == "neo-hookean":
        return {"shear_modulus": modulus}
    if kind == "mooney-rivlin":
        share = draw(st.sampled_from([0.0, 0.2, 0.5, 0.9]))
        return {"model": "mooney-rivlin", "c10": modulus / 2 * (1 - share), "c01": modulus / 2 * share,
                "bulk_to_shear": draw(st.sampled_from([100.0, 1000.0]))}
    c20 = draw(st.sampled_from([0.0, 0.05, -0.02, -0.5])) * modulus  # -0.5: unstable from a small stretch
    return {"model": "yeoh", "c10": modulus / 2, "c20": c20, "c30": draw(st.sampled_from([0.0, 0.01])) * modulus}


@st.composite
def assemblies(draw, damage: float = 0.1, models: tuple[str, ...] | None = None):
    """A ``section-case/2`` dictionary: 1-4 bonded bodies, plane or of revolution, maybe a rigid part.

    Bodies are stacked (each on the one below, some of them thin layers) or
    side by side (the second's lower curve runs up the first's side), with
    shear moduli up to 1000 apart and every rubber model; a body of
    revolution may lie close to its axis; the target bends, stretches or
    moves the support (outward from the axis for a body of revolution); a
    rigid plate may press on the top. A share ``damage`` of the examples
    gets one damage (a NaN, a missing key, a body's lower curve off its
    foundation, overlapping bodies, a body across the axis).
    """
    scale = draw(st.sampled_from([1.0, 10.0, 100.0, 0.1]))
    width = scale * draw(st.sampled_from([1.0, 2.0, 5.0, 0.5]))
    n = draw(st.integers(1, 4))
    layout = draw(st.sampled_from(["stacked", "stacked", "side"])) if n > 1 else "stacked"
    revolution = draw(st.booleans())
    x0 = 0.0
    # Distance of the support from the axis (y = -offset): close to the axis, or far.
    offset = scale * draw(st.sampled_from([0.01, 0.1, 1.0, 10.0]))
    base = max(1.0, 1e3 * draw(st.sampled_from([1.0, 1.0, 1e-3])))  # stiffness contrasts up to 1000
    bodies = []
    if layout == "stacked":
        y = 0.0
        for i in range(n):
            t = scale * draw(st.sampled_from([0.2, 0.5, 1.0, 0.02, 0.05]))  # thin layers too
            left, right = 0.0, width
            if i > 0 and draw(st.booleans()):  # a narrower body on top
                inset = width * draw(st.sampled_from([0.1, 0.3]))
                left, right = left + inset, right - inset
            lower = [[x0 + left, y], [x0 + right, y]]
            upper = [[x0 + right, y], [x0 + right, y + t], [x0 + left, y + t], [x0 + left, y]]
            bodies.append((lower, upper))
            y += t
    else:
        h = scale * draw(st.sampled_from([0.2, 0.5, 1.0]))
        cuts = np.linspace(0.0, width, n + 1)
        for i in range(n):
            a, b = cuts[i], cuts[i + 1]
            if i == 0:
                lower = [[x0 + a, 0.0], [x0 + b, 0.0]]
            else:  # up the neighbour's side, then along the support
                lower = [[x0 + a, h], [x0 + a, 0.0], [x0 + b, 0.0]]
            upper = [[x0 + b, 0.0], [x0 + b, h], [x0 + a, h]] + ([[x0 + a, 0.0]] if i == 0 else [])
            bodies.append((lower, upper))
    out = []
    for i, (lower, upper) in enumerate(bodies):
        modulus = base * draw(st.sampled_from([1.0, 0.1, 10.0, 1e-3, 1.0]))
        if revolution:
            law = {"volume_ratio": draw(st.sampled_from([1.0, 1.0, 0.95, 1.05]))}
        else:
            law = {"area_ratio": draw(st.sampled_from([1.0, 0.9, 1.1]))}
            if _rarely(draw, 20):  # growth of an extruded body
                law = {"volume_ratio": 1.05}
        body = {"name": f"b{i}", "lower": {"polyline": lower}, "upper": {"polyline": upper}, "law": law}
        material = _rubber(draw, modulus)
        if material:
            body["material"] = material
        out.append(body)
    support = {"polyline": [[x0, 0.0], [x0 + width, 0.0]]}
    kind = draw(st.sampled_from(["same", "arc", "stretch", "outward", "crown"]))
    if kind == "same":
        target = support
    elif kind == "arc":
        target = _arc_through(np.array([x0, 0.0]), np.array([x0 + width, 0.0]),
                              draw(st.sampled_from([0.05, 0.2, -0.05, -0.2])))[0]
    elif kind == "stretch":
        f = draw(st.sampled_from([0.8, 1.2, 1.5]))
        target = {"polyline": [[x0 + width * (1 - f) / 2, 0.0], [x0 + width * (1 + f) / 2, 0.0]]}
    elif kind == "outward":  # moved away from the axis (grown on a larger drum)
        dy = (offset if revolution else scale) * draw(st.sampled_from([0.1, 0.3, 1.0]))
        target = {"polyline": [[x0, dy], [x0 + width, dy]]}
    else:
        k = 9
        xs = np.linspace(x0, x0 + width, k)
        ys = scale * draw(st.sampled_from([0.05, 0.2])) * np.sin(np.linspace(0, math.pi, k))
        target = {"polyline": np.column_stack((xs, ys)).tolist()}
    model = draw(st.sampled_from(models or ("paper", "hyperelastic")))
    case = {"format": "section-case/2", "name": "fuzz-assembly", "units": "mm", "support": support,
            "target": target, "bodies": out, "options": {"model": model}}
    if revolution:
        case["revolution"] = {"axis": [[0.0, -offset], [1.0, -offset]]}
    if _rarely(draw, 4):  # a rigid plate pressing on the top (contact: hyperelastic model)
        top = max(p[1] for body in out for p in body["upper"]["polyline"])
        press = top * draw(st.sampled_from([0.02, 0.1, 0.3]))
        plate = [[x0 - width, top - press], [x0 + 2 * width, top - press], [x0 + 2 * width, top + scale],
                 [x0 - width, top + scale], [x0 - width, top - press]]
        case["rigid"] = [{"name": "plate", "contour": {"polyline": plate}, "travel": [0.0, -press],
                          "friction": draw(st.sampled_from([0.0, 0.0, 0.3]))}]
    if draw(st.booleans()):
        case["options"]["chordal_error"] = scale * draw(st.sampled_from([1e-3, 1e-2]))
    if draw(st.integers(0, 999)) in range(500 - round(500 * damage), 500 + round(500 * damage)):
        case = draw(_damaged_assembly(case))
    return case


@st.composite
def _damaged_assembly(draw, case):
    case = json.loads(json.dumps(case))
    case["name"] = "fuzz-assembly-damaged"
    kind = draw(st.sampled_from(["nan", "off-foundation", "overlap", "across-axis", "drop-key", "no-bodies",
                                 "material", "law"]))
    body = draw(st.sampled_from(case["bodies"]))
    if kind == "nan":
        body["upper"]["polyline"][1][1] = float("nan")
    elif kind == "off-foundation":
        for p in body["lower"]["polyline"]:
            p[1] += 0.1 * max(1e-3, abs(body["upper"]["polyline"][1][1] - body["upper"]["polyline"][0][1]))
    elif kind == "overlap":
        extra = json.loads(json.dumps(body))
        extra["name"] = "copy"
        case["bodies"].append(extra)
    elif kind == "across-axis":
        case["revolution"] = {"axis": [[0.0, 0.0], [0.0, 1.0]]}
    elif kind == "drop-key":
        del case[draw(st.sampled_from(["support", "target", "bodies"]))]
    elif kind == "no-bodies":
        case["bodies"] = []
    elif kind == "material":
        body["material"] = draw(st.sampled_from([{"model": "yeoh"}, {"shear_modulus": -1.0},
                                                 {"model": "mooney-rivlin", "c10": 0.0, "c01": 0.0},
                                                 {"model": "ogden"}]))
    else:
        body["law"] = draw(st.sampled_from([{"volume_ratio": 0.0}, {"area_ratio": -1.0}, {}]))
    return case


# -- the other commands: fit, sweep, export-fe, convert, damaged drawings ------------

COMMANDS = ("fit", "sweep", "export-fe", "convert", "drawing")
"""The command-line runs :func:`command_runs` generates (``drawing``: ``convert`` of a damaged DXF or SVG)."""


def _fit_csv(draw) -> str:
    """A CSV of rubber test data (neo-Hookean with noise), maybe damaged."""
    mu = draw(st.sampled_from([0.4, 1.0, 5.0]))
    lines = ["mode,stretch,nominal_stress"]
    for mode in draw(st.sampled_from([["uniaxial"], ["uniaxial", "equibiaxial", "planar"], ["planar"]])):
        for lam in np.linspace(1.0, draw(st.sampled_from([1.5, 3.0, 7.0])), draw(st.integers(2, 12))):
            power = {"uniaxial": 2, "equibiaxial": 5, "planar": 3}[mode]
            stress = mu * (lam - lam ** (1 - power)) * (1.0 + 0.02 * draw(st.floats(-1.0, 1.0)))
            lines.append(f"{mode},{float(lam)!r},{float(stress)!r}")
    if _rarely(draw, 3):
        i = draw(st.integers(1, len(lines) - 1))
        lines[i] = draw(st.sampled_from(["uniaxial,nan,1.0", "uniaxial,-2,1", "shear,1.2,0.3", "uniaxial,1.2",
                                         "uniaxial,abc,1", "uniaxial,1e999,1", "", "uniaxial,0.5,-1e308"]))
    if _rarely(draw, 10):
        lines = lines[:1]
    return "\n".join(lines) + "\n"


_DRAWING_DAMAGES = ("cut", "drop", "double", "number", "bytes")


def _damage_text(text: str, damage: dict) -> str:
    """``text`` (a DXF or SVG file) damaged once as ``damage`` says: cut short, a line dropped or doubled,
    a number spoilt, or bytes that are not UTF-8 inserted, at the fraction ``damage["at"]`` of the file.
    """
    import re

    lines = text.splitlines()
    kind, i = damage["kind"], int(damage["at"] * len(lines))
    if kind == "cut":
        return "\n".join(lines[:i])
    if kind == "drop":
        return "\n".join(lines[:i] + lines[i + 1:])
    if kind == "double":
        return "\n".join(lines[:i + 1] + lines[i:])
    if kind == "number":
        numbers = [(k, m) for k, line in enumerate(lines) for m in re.finditer(r"-?\d+\.?\d*(e-?\d+)?", line)]
        if numbers:
            k, m = numbers[int(damage["at"] * len(numbers))]
            bad = ["nan", "1e999", "abc", "-0", "1e308", ""][damage["pick"] % 6]
            lines[k] = lines[k][:m.start()] + bad + lines[k][m.end():]
        return "\n".join(lines)
    j = int(damage["at"] * len(text))
    return text[:j] + "\udcff\udc80" + text[j:]  # two bytes that are not UTF-8 (surrogateescape)


@st.composite
def command_runs(draw, commands: tuple[str, ...] = COMMANDS):
    """A command-line run: ``{"command": ..., "files": {name: text}, "steps": [...], "damage": ...}``.

    ``steps`` hold the argument lists of ``sectiondeform`` and the files
    each writes; ``damage``, for the ``drawing`` runs, says how the file
    written by the first step is damaged (:func:`_damage_text`) before the
    second reads it.
    """
    command = draw(st.sampled_from(commands))
    run = {"command": command, "files": {}, "steps": [], "damage": None}
    if command == "fit":
        run["files"]["data.csv"] = _fit_csv(draw)
        model = draw(st.sampled_from(["neo-hookean", "mooney-rivlin", "yeoh", "all"]))
        args = ["fit", "data.csv", "--model", model]
        if model != "all":
            args += ["-o", "material.json"]
        if _rarely(draw, 4):
            args += ["--max-stretch", draw(st.sampled_from(["2", "0.5", "nan", "1"]))]
        run["steps"].append({"args": args, "outputs": ["material.json"]})
        return run
    case = draw(st.one_of(cases(damage=0.1), assemblies(damage=0.1)))
    run["files"]["case.json"] = json.dumps(case)
    if command == "export-fe":
        args = ["export-fe", "case.json", "-o", "deck.inp"]
        if _rarely(draw, 3):
            args += ["--mesh-size", draw(st.sampled_from(["0.3", "0.05", "0", "-1", "nan"]))]
        if _rarely(draw, 4):
            args += ["--element", draw(st.sampled_from(["CPE8R", "CPE4", "CAX6", "CPE3", "XYZ"]))]
        run["steps"].append({"args": args, "outputs": ["deck.inp"]})
    elif command == "sweep":
        vary = {"area_ratio": draw(st.sampled_from([[0.9, 1.0], [1.1], [0.5, -1.0], [None]]))}
        if draw(st.booleans()):
            vary["bend_radius"] = draw(st.sampled_from([[None, -300.0], [200.0], [0.0]]))
        if draw(st.booleans()):
            vary["crown"] = draw(st.sampled_from([[0.0, 2.0], [1e6]]))
        if draw(st.booleans()):
            vary["stretch"] = draw(st.sampled_from([[0.9, 1.2], [0.0]]))
        if case.get("format") == "section-case/2" or _rarely(draw, 3):
            vary.pop("area_ratio")  # an assembly keeps each body's law
        study = {"format": "section-study/1", "name": "fuzz", "cases": [{"case": "case.json", "vary": vary}]}
        run["files"]["study.json"] = json.dumps(study)
        rows = math.prod(len(v) for v in vary.values())  # each row a deform run, bounded as one
        run["steps"].append({"args": ["sweep", "study.json", "-o", "out", "--workers", "0", "--quiet", "--csv"],
                             "outputs": ["out"], "quiet": True, "rows": rows})
    else:
        ext = draw(st.sampled_from([".dxf", ".svg"]))
        run["steps"].append({"args": ["convert", "case.json", f"case{ext}"], "outputs": [f"case{ext}"]})
        back = ["convert", f"case{ext}", "back.json"]
        if _rarely(draw, 3):
            back += ["--area-ratio", draw(st.sampled_from(["0.9", "0", "x"]))]
        run["steps"].append({"args": back, "outputs": ["back.json"]})
        if command == "drawing":
            run["damage"] = {"file": f"case{ext}", "kind": draw(st.sampled_from(_DRAWING_DAMAGES)),
                             "at": draw(st.floats(0.0, 0.999)), "pick": draw(st.integers(0, 5))}
    return run


def _deck_fails(deck: Path) -> list[str]:
    """Every real of an ``.inp`` deck's data lines longer than CalculiX reads (20 characters), or not finite."""
    from sectiondeform.external.inp_number import FIELD_WIDTH

    fails = []
    for k, line in enumerate(deck.read_text(encoding="utf-8").splitlines()):
        if line.startswith("*") or not line.strip():
            continue
        for field in line.split(","):
            field = field.strip()
            try:
                value = float(field)
            except ValueError:
                continue  # a name (a set, a node list label)
            if len(field) > FIELD_WIDTH or not math.isfinite(value):
                fails.append(f"line {k + 1}: {field!r}")
    return fails[:3]


def outcome_command_run(run: dict, folder: Path, limit_s: float = TIME_LIMIT_S) -> Outcome:
    """Run a :func:`command_runs` run in the empty ``folder``; the outcome of its last step run.

    Each step as a ``sdfuzz-bundle/1`` step (exit 0, or 2 with one line and
    none of its outputs written; no traceback, no warning, nothing
    non-finite on stdout; a sweep gets the time limit once per row, each row
    being a ``deform`` run), and beyond: a deck written by ``export-fe`` holds
    no real longer than CalculiX reads; a ``--quiet`` sweep that succeeds
    prints nothing; the case ``convert`` wrote back (JSON) reads again.
    """
    from fuzz_bundles import _run_step

    folder.mkdir(parents=True, exist_ok=True)
    for name, text in run["files"].items():
        (folder / name).write_text(text, encoding="utf-8")
    outcome = Outcome("ok")
    for i, step in enumerate(run["steps"]):
        if i == 1 and run.get("damage"):
            path = folder / run["damage"]["file"]
            text = path.read_text(encoding="utf-8", errors="surrogateescape")
            path.write_bytes(_damage_text(text, run["damage"]).encode("utf-8", errors="surrogateescape"))
        outcome = _run_step({"cmd": step["args"][0], "args": step["args"][1:], "outputs": step["outputs"]},
                            folder, limit_s * step.get("rows", 1))
        if outcome.kind != "ok":
            return outcome
        if step.get("quiet") and outcome.detail:
            return Outcome("failure:not-quiet", outcome.detail[:300], outcome.seconds)
        if step["args"][0] == "export-fe":
            fails = _deck_fails(folder / "deck.inp")
            if fails:
                return Outcome("failure:deck-real", "; ".join(fails), outcome.seconds)
        if step["args"][0] == "convert" and step["args"][2].endswith(".json"):
            try:
                sd.load_case(folder / step["args"][2])
            except sd.SectionDeformError as exc:
                return Outcome("failure:unreadable", f"convert wrote a case that does not read back: {exc}",
                               outcome.seconds)
    return outcome

