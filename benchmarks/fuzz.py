"""The fuzz tests' generator at scale: count the outcomes, keep every input that breaks the promise.

Draws ``--count`` cases from the generator of ``tests/fuzz_cases.py`` (both
models, a quarter damaged) with hypothesis under ``--seed``, runs each
through the library (``load_case``-equivalent and ``deform``, then the
independent checks of :mod:`sectiondeform.verify`), and every
``--cli-every``-th one also through the command line in a new process.
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

from fuzz_cases import TIME_LIMIT_S, cases, outcome_api, outcome_cli  # noqa: E402
from hypothesis import HealthCheck, Phase, given, seed, settings  # noqa: E402


class _Stop(Exception):
    """The time given (``--max-minutes``) is up."""


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=1000, help="inputs to generate (default 1000)")
    parser.add_argument("--seed", type=int, default=0, help="hypothesis seed (default 0)")
    parser.add_argument("--damage", type=float, default=0.25, help="share of damaged inputs (default 0.25)")
    parser.add_argument("--cli-every", type=int, default=50, metavar="N",
                        help="also run every N-th input through the command line (0: never; default 50)")
    parser.add_argument("--limit", type=float, default=TIME_LIMIT_S, help=f"seconds per input (default {TIME_LIMIT_S:g})")
    parser.add_argument("--max-minutes", type=float, default=None,
                        help="stop drawing new inputs after this many minutes (the summary says how many ran)")
    parser.add_argument("--failures", type=Path, default=Path("fuzz-failures"),
                        help="folder for the failing inputs (default ./fuzz-failures)")
    args = parser.parse_args(argv)

    counts: collections.Counter[str] = collections.Counter()
    by_model: dict[str, collections.Counter[str]] = collections.defaultdict(collections.Counter)
    seconds: list[float] = []
    failures: list[str] = []
    start = time.perf_counter()
    n = [0]

    def record(case, outcome, via):
        counts[f"{via} {outcome.kind}"] += 1
        if via == "api":
            options = case.get("options")
            model = options.get("model") if isinstance(options, dict) else None
            by_model[str(model)][outcome.kind.split(":")[0]] += 1
        if outcome.failed:
            args.failures.mkdir(parents=True, exist_ok=True)
            stem = f"{via}-{outcome.kind.replace(':', '-')}-{args.seed}-{n[0]}"
            (args.failures / f"{stem}.json").write_text(json.dumps(case), encoding="utf-8")
            (args.failures / f"{stem}.txt").write_text(f"{via} {outcome.kind} after {outcome.seconds:.2f} s: {outcome.detail}\n",
                                                      encoding="utf-8")
            failures.append(f"{stem}: {outcome.detail[:200]}")
            print(f"FAILURE {stem}: {outcome.detail[:200]}", file=sys.stderr)

    @seed(args.seed)
    @settings(max_examples=args.count, database=None, deadline=None, phases=[Phase.generate],
              suppress_health_check=list(HealthCheck))
    @given(case=cases(damage=args.damage))
    def run(case):
        if args.max_minutes is not None and time.perf_counter() - start > 60.0 * args.max_minutes:
            raise _Stop
        n[0] += 1
        outcome = outcome_api(case, args.limit)
        seconds.append(outcome.seconds)
        record(case, outcome, "api")
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
    print(f"failures: {len(failures)}" + (f", saved in {args.failures}" if failures else ""))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
