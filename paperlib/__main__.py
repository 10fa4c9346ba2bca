"""Command line.

``python -m paperlib reproduce [--quality ci|paper] [--only PATTERN] [--jobs N]`` runs notebooks
and checks their statistics; ``python -m paperlib seed-study --only PATTERN --seeds 0-9`` prints
each statistic's spread over seeds (how a ``seed-study`` bound is measured).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from . import reproduce as reproduce_module


def _positive_int(text: str) -> int:
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text}")
    return value


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="python -m paperlib", description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser("reproduce", help="run the notebooks and check their statistics")
    run.add_argument("--quality", choices=["ci", "paper"], default="paper", help="settings (default: paper)")
    run.add_argument("--only", metavar="PATTERN", help="glob or substring of the notebook names to run")
    run.add_argument("--jobs", type=_positive_int, default=1, metavar="N", help="notebooks run in parallel")
    run.add_argument("--seed", type=int, help="override every notebook's default seed")
    run.add_argument("--timeout", type=float, help="per-cell time limit in seconds")
    run.add_argument("--root", type=Path, default=Path("."), help="project root (default: current folder)")
    run.add_argument("--figures-dir", type=Path, help="write figures and INDEX.md here instead of ROOT/figures")
    study = commands.add_parser("seed-study", help="run notebooks over seeds and print each statistic's range")
    study.add_argument("--only", metavar="PATTERN", required=True, help="glob or substring of the notebook names")
    study.add_argument("--seeds", type=_seed_range, default=list(range(5)), metavar="A-B",
                       help="seeds to run, as A-B or a comma list (default: 0-4)")
    study.add_argument("--quality", choices=["ci", "paper"], default="ci", help="settings (default: ci)")
    study.add_argument("--jobs", type=_positive_int, default=1, metavar="N", help="runs in parallel")
    study.add_argument("--timeout", type=float, help="per-cell time limit in seconds")
    study.add_argument("--root", type=Path, default=Path("."), help="project root (default: current folder)")
    return parser


def _seed_range(text: str) -> list[int]:
    """``"0-9"`` or ``"0,3,7"`` as a list of seeds."""
    try:
        if "-" in text:
            first, last = (int(part) for part in text.split("-", 1))
            return list(range(first, last + 1))
        return [int(part) for part in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"seeds must be A-B or a comma list of integers, got {text!r}") from None


def _seed_study(args) -> int:
    import pandas as pd

    try:
        table = reproduce_module.seed_study(
            args.root, only=args.only, seeds=args.seeds, quality=args.quality, jobs=args.jobs, timeout=args.timeout
        )
    except (ValueError, RuntimeError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    with pd.option_context("display.max_rows", None, "display.width", 250, "display.max_colwidth", 120):
        print(table.to_string(index=False))
    return 0


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    if args.command == "seed-study":
        return _seed_study(args)
    try:
        runs, table = reproduce_module.reproduce(
            args.root, quality=args.quality, only=args.only, jobs=args.jobs, seed=args.seed, timeout=args.timeout,
            figures_dir=args.figures_dir,
        )
    except ValueError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    print(reproduce_module.format_summary(runs, table))
    problems = reproduce_module.failures(runs, table)
    for problem in problems:
        print(f"FAILED {problem}", file=sys.stderr)
    if not problems:
        print(f"\nall {len(runs)} notebook(s) ran and all {len(table)} statistic(s) are within tolerance")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
