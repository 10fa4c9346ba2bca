"""Command line: ``python -m paperlib reproduce [--quality ci|paper] [--only PATTERN] [--jobs N]``."""

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
    return parser


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        runs, table = reproduce_module.reproduce(
            args.root, quality=args.quality, only=args.only, jobs=args.jobs, seed=args.seed, timeout=args.timeout
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
