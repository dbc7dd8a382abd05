"""The fuzz tests' generator at scale: count the outcomes, keep every input that breaks the promise.

Draws ``--count`` cases from the generators of ``tests/fuzz_cases.py``
with hypothesis under ``--seed``: a share ``--v2`` of them assemblies and
bodies of revolution (``assemblies``: 1-4 bodies stacked or side by side,
stiffness contrasts to 1000, thin layers, every rubber model, rigid parts),
the rest one-body cases (``cases``, both models, a quarter damaged). Runs
each through the library (``load_case``-equivalent and ``deform``, then the
independent checks: :func:`sectiondeform.verify.check_result`, or
``check_bodies`` body by body), every ``--cli-every``-th one also through
``sectiondeform deform`` in a new process, and every ``--commands-every``-th
draws a run of another command (``fit``, ``sweep``, ``export-fe``,
``convert``, ``convert`` of a damaged DXF or SVG: ``command_runs``).
Prints progress on stderr and, at the end, the outcomes: ``ok`` (a result
that passes the checks), ``refused:<ErrorClass>`` (one clean line) and
``failure:<what>`` (crash, multi-line message, failed check, numpy warning,
over the time limit). Each failing input is saved under ``--failures`` as
JSON with a text file saying what happened, to be replayed with
``sectiondeform deform FILE -o out.json``.

    .venv/bin/python benchmarks/fuzz.py --count 10000 --seed 1 --failures fuzz-failures

With ``--max-minutes`` it stops drawing inputs when the time is up and
reports how many ran. Exit status 1 when any input failed. Needs the test extras (hypothesis).
"""

from __future__ import annotations

import argparse
import collections
import json
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from fuzz_cases import (  # noqa: E402
    TIME_LIMIT_S,
    assemblies,
    cases,
    command_runs,
    outcome_api,
    outcome_cli,
    outcome_command_run,
)
from hypothesis import HealthCheck, Phase, given, seed, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


class _Stop(Exception):
    """The time given (``--max-minutes``) is up."""


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=1000, help="inputs to generate (default 1000)")
    parser.add_argument("--seed", type=int, default=0, help="hypothesis seed (default 0)")
    parser.add_argument("--damage", type=float, default=0.25, help="share of damaged inputs (default 0.25)")
    parser.add_argument("--cli-every", type=int, default=50, metavar="N",
                        help="also run every N-th input through the command line (0: never; default 50)")
    parser.add_argument("--v2", type=float, default=0.5,
                        help="share of assemblies and bodies of revolution among the inputs (default 0.5)")
    parser.add_argument("--commands-every", type=int, default=20, metavar="N",
                        help="also run a generated fit, sweep, export-fe or convert every N-th input (0: never; default 20)")
    parser.add_argument("--only-commands", action="store_true",
                        help="draw only command runs (fit, sweep, export-fe, convert): --count of them")
    parser.add_argument("--refusals", action="store_true",
                        help="draw only undamaged assemblies for the hyperelastic model (--count of them) and count "
                             "how each ends: answered, or refused, and whether the refusal names a physical reason")
    parser.add_argument("--limit", type=float, default=TIME_LIMIT_S, help=f"seconds per input (default {TIME_LIMIT_S:g})")
    parser.add_argument("--max-minutes", type=float, default=None,
                        help="stop drawing new inputs after this many minutes (the summary says how many ran)")
    parser.add_argument("--failures", type=Path, default=Path("fuzz-failures"),
                        help="folder for the failing inputs (default ./fuzz-failures)")
    args = parser.parse_args(argv)

    if args.refusals:
        return refusals(args.count, args.seed, args.limit, args.failures)
    counts: collections.Counter[str] = collections.Counter()
    by_model: dict[str, collections.Counter[str]] = collections.defaultdict(collections.Counter)
    newton = collections.Counter()  # hyperelastic assemblies without damage: answered, Newton refusals
    seconds: list[float] = []
    failures: list[str] = []
    start = time.perf_counter()
    n = [0]

    def record(case, outcome, via):
        counts[f"{via} {outcome.kind}"] += 1
        if via.startswith("api"):
            options = case.get("options")
            model = options.get("model") if isinstance(options, dict) else None
            by_model[str(model)][outcome.kind.split(":")[0]] += 1
        if outcome.failed:
            args.failures.mkdir(parents=True, exist_ok=True)
            stem = f"{via}-{outcome.kind.replace(':', '-')}-{args.seed}-{n[0]}"
            stem = stem.replace(" ", "-")
            (args.failures / f"{stem}.json").write_text(json.dumps(case), encoding="utf-8")
            (args.failures / f"{stem}.txt").write_text(f"{via} {outcome.kind} after {outcome.seconds:.2f} s: {outcome.detail}\n",
                                                      encoding="utf-8")
            failures.append(f"{stem}: {outcome.detail[:200]}")
            print(f"FAILURE {stem}: {outcome.detail[:200]}", file=sys.stderr)

    share = round(1000 * args.v2)

    @seed(args.seed)
    @settings(max_examples=args.count, database=None, deadline=None, phases=[Phase.generate],
              suppress_health_check=list(HealthCheck))
    @given(pick=st.integers(0, 999), one=cases(damage=args.damage), many=assemblies(),
           command=command_runs())
    def run(pick, one, many, command):
        case = many if pick < share else one
        if args.max_minutes is not None and time.perf_counter() - start > 60.0 * args.max_minutes:
            raise _Stop
        n[0] += 1
        if args.only_commands:
            with tempfile.TemporaryDirectory() as folder:
                record(command, outcome_command_run(command, Path(folder), args.limit), f"cmd {command['command']}")
            return
        outcome = outcome_api(case, args.limit)
        seconds.append(outcome.seconds)
        record(case, outcome, "api v2" if pick < share else "api")
        if pick < share and case.get("options", {}).get("model") == "hyperelastic" and case.get("name") == "fuzz-assembly":
            newton[refusal_class(outcome)] += 1
        if args.commands_every and n[0] % args.commands_every == 0:
            with tempfile.TemporaryDirectory() as folder:
                record(command, outcome_command_run(command, Path(folder), args.limit), f"cmd {command['command']}")
        if args.cli_every and n[0] % args.cli_every == 0:
            with tempfile.TemporaryDirectory() as folder:
                record(case, outcome_cli(case, Path(folder), args.limit), "cli")
        if n[0] % 100 == 0:
            ok = sum(v for k, v in counts.items() if k.endswith(" ok"))
            print(f"{n[0]}/{args.count} inputs, {ok} ok, {len(failures)} failures, "
                  f"{time.perf_counter() - start:.0f} s", file=sys.stderr, flush=True)

    try:
        run()
    except _Stop:
        print(f"stopped after {args.max_minutes:g} minutes", file=sys.stderr)
    wall = time.perf_counter() - start
    print(f"fuzz: {n[0]} inputs (seed {args.seed}, damage {args.damage:g}), {wall:.0f} s wall, "
          f"slowest input {max(seconds, default=0):.2f} s, per-input limit {args.limit:g} s")
    for key, value in sorted(counts.items(), key=lambda kv: (kv[0].split()[0], -kv[1])):
        print(f"  {value:6d}  {key}")
    print("by model (api):")
    for model, c in sorted(by_model.items()):
        print(f"  {model}: " + ", ".join(f"{k} {v}" for k, v in sorted(c.items())))
    total = sum(newton.values())
    print(f"hyperelastic model on undamaged generated assemblies and bodies of revolution: {total}")
    for key, value in sorted(newton.items(), key=lambda kv: -kv[1]):
        print(f"  {value:6d}  ({100 * value / total:.1f} %)  {key}")
    print(f"failures: {len(failures)}" + (f", saved in {args.failures}" if failures else ""))
    return 1 if failures else 0


def refusal_class(outcome) -> str:
    """How a hyperelastic solve ended: answered, a refusal naming a physical reason, a convergence refusal without one,
    or the kind of another refusal (geometry, mesh: the input itself).
    """
    detail = outcome.detail
    if outcome.kind == "ok":
        return "answered"
    if "is unstable" in detail:
        return "no equilibrium: an unstable rubber named"
    if "at the last equilibrium reached, " in detail:
        return "no equilibrium: the physical state named (fem/diagnosis.py)"
    if "Newton stopped" in detail or "did not converge" in detail or "the loading took" in detail:
        return "convergence refusal, no physical reason named"
    return outcome.kind


def refusals(count: int, seed_: int, limit: float, folder: Path | None = None) -> int:
    """Issue 25's count: undamaged generated assemblies and bodies of revolution, hyperelastic, by how they end.

    Each input refused without a physical reason, and each failure, is saved in ``folder``: the case as
    ``refusal-<seed>-<n>.json`` (replayed with ``sectiondeform deform``), its one line as ``.txt``.
    """
    classes: collections.Counter[str] = collections.Counter()
    slowest = [0.0]
    saved = [0]

    @seed(seed_)
    @settings(max_examples=count, database=None, deadline=None, phases=[Phase.generate],
              suppress_health_check=list(HealthCheck))
    @given(case=assemblies(damage=0.0, models=("hyperelastic",)))
    def run(case):
        outcome = outcome_api(case, limit)
        slowest[0] = max(slowest[0], outcome.seconds)
        kind = refusal_class(outcome)
        classes[kind] += 1
        if folder is not None and (kind.startswith("convergence refusal") or outcome.failed):
            folder.mkdir(parents=True, exist_ok=True)
            saved[0] += 1
            stem = folder / f"refusal-{seed_}-{saved[0]}"
            stem.with_suffix(".json").write_text(json.dumps(case, indent=1))
            stem.with_suffix(".txt").write_text(f"{outcome.kind}: {outcome.detail}\n")

    run()
    total = sum(classes.values())
    print(f"hyperelastic model, {total} undamaged generated assemblies and bodies of revolution (seed {seed_}), "
          f"slowest {slowest[0]:.1f} s of CPU:")
    for key, value in classes.most_common():
        print(f"  {value:6d}  ({100 * value / total:5.1f} %)  {key}")
    return 1 if any(k.startswith("failure") for k in classes) else 0


if __name__ == "__main__":
    sys.exit(main())
