"""Command line: ``python -m paperlib reproduce``, ``seed-study`` and ``explore``.

``reproduce`` runs notebooks and checks their statistics; ``seed-study`` prints each statistic's
spread over seeds (how a ``seed-study`` bound is measured); ``explore`` serves a method's app with
Voila (:mod:`paperlib.apps`). The help texts below are plain text:
they are what a terminal shows.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from . import reproduce as reproduce_module

DESCRIPTION = """\
Re-run the notebooks that reproduce the papers' figures and check the statistics they record
against tests/expected_stats.toml.

commands:
  reproduce    run notebooks (all, or those matching --only), write figures/<notebook>/ and
               figures/INDEX.md, and fail on any statistic out of tolerance
  seed-study   run notebooks over several seeds and print each statistic's range
  explore      serve a method's interactive explorer as a web app (Voila, 127.0.0.1)"""

EXAMPLES = """\
examples:
  python -m paperlib reproduce --quality ci --jobs 2
      every notebook at CI settings, two at a time
  python -m paperlib reproduce --only kim2009_fig07-08_distributions_glcm
      one notebook, at the paper's settings, with a progress bar over its cells
  python -m paperlib reproduce --only "hurtut2009_*" --figures-dir /tmp/figures
      the Hurtut 2009 notebooks, figures written outside the repository
  python -m paperlib reproduce --root ~/src/paperlib --only fig05
      run from another folder: --root names the repository
  python -m paperlib seed-study --only barla2006_fig03-04_matching --seeds 0-9
      the spread of every statistic over ten seeds
  python -m paperlib explore kim2009 --open-browser
      the Kim 2009 explorer at http://127.0.0.1:8866/"""

EXPLORE_EXAMPLES = """\
examples:
  python -m paperlib explore hurtut2009
      serve the Hurtut 2009 explorer at http://127.0.0.1:8866/ (Ctrl-C stops)
  python -m paperlib explore stipple --port 8870 --open-browser
      the Kim 2009 explorer (module names work too) on another port, opened in your browser
  python -m paperlib explore alvarez2015 --file-root ~/textures
      scripts and saved textures read and written only under ~/textures"""

REPRODUCE_EXAMPLES = """\
examples:
  python -m paperlib reproduce --quality ci --jobs 2
  python -m paperlib reproduce --only kim2009_fig07-08_distributions_glcm --seed 3
  python -m paperlib reproduce --root ~/src/paperlib --only "simhon2001_*" --no-progress"""

SEED_STUDY_EXAMPLES = """\
examples:
  python -m paperlib seed-study --only barla2006_fig03-04_matching --seeds 0-9
  python -m paperlib seed-study --only fig07 --seeds 0,3,7 --quality paper"""


def _version() -> str:
    try:
        from importlib.metadata import version

        return version("paperlib")
    except Exception:  # run from a source tree that is not installed
        return "unknown (not installed)"


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text}")
    return value


def _common_options(command: argparse.ArgumentParser, quality: str) -> None:
    command.add_argument("--quality", choices=["ci", "paper"], default=quality, help=f"settings (default: {quality})")
    command.add_argument("--jobs", type=_positive_int, default=1, metavar="N",
                         help="notebooks run in parallel processes (default: 1)")
    command.add_argument("--timeout", type=float, metavar="SECONDS", help="per-cell time limit")
    command.add_argument("--root", type=Path, default=Path("."),
                         help="the paperlib repository (holds notebooks/ and tests/expected_stats.toml; "
                              "default: the current folder)")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``python -m paperlib``: plain-text help with examples, ``--version``.

    Returns
    -------
    argparse.ArgumentParser
    """
    formatter = argparse.RawDescriptionHelpFormatter
    parser = argparse.ArgumentParser(prog="python -m paperlib", description=DESCRIPTION, epilog=EXAMPLES,
                                     formatter_class=formatter)
    parser.add_argument("--version", action="version", version=f"paperlib {_version()}")
    commands = parser.add_subparsers(dest="command", required=True, metavar="{reproduce,seed-study,explore}")
    run = commands.add_parser("reproduce", help="run the notebooks and check their statistics",
                              description="Run notebooks with papermill, publish their figures, check their\n"
                                          "statistics and write figures/INDEX.md.",
                              epilog=REPRODUCE_EXAMPLES, formatter_class=formatter)
    _common_options(run, "paper")
    run.add_argument("--only", metavar="PATTERN",
                     help="glob or substring of the notebook names to run (default: all)")
    run.add_argument("--seed", type=int, help="override every notebook's default seed")
    run.add_argument("--figures-dir", type=Path, help="write figures and INDEX.md here instead of ROOT/figures")
    run.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                     help="progress bars over the notebooks, or over the cells of a single notebook "
                          "(default: only when stderr is a terminal)")
    study = commands.add_parser("seed-study", help="run notebooks over seeds and print each statistic's range",
                                description="Run notebooks over several seeds (figures under build/seed-study/,\n"
                                            "never figures/) and print each statistic's range.",
                                epilog=SEED_STUDY_EXAMPLES, formatter_class=formatter)
    _common_options(study, "ci")
    study.add_argument("--only", metavar="PATTERN", required=True, help="glob or substring of the notebook names")
    study.add_argument("--seeds", type=_seed_range, default=list(range(5)), metavar="A-B",
                       help="seeds to run, as A-B or a comma list (default: 0-4)")
    _explore_parser(commands, formatter)
    return parser


def _explore_parser(commands, formatter) -> None:
    from .apps import ALIASES, APPS

    lines = "\n".join(f"  {key:<12} {description}" for key, (_, description) in APPS.items())
    explore = commands.add_parser(
        "explore", help="serve a method's interactive explorer as a web app",
        description=f"Serve a method's explorer app with Voila on 127.0.0.1 (the panel only, a live kernel\n"
                    f"behind it). Methods (or their module names: {', '.join(ALIASES)}):\n{lines}",
        epilog=EXPLORE_EXAMPLES, formatter_class=formatter)
    explore.add_argument("method", help="paper key or module name of the method")
    explore.add_argument("--port", type=int, default=8866, help="TCP port (default: 8866)")
    explore.add_argument("--file-root", type=Path, metavar="DIR",
                         help="the only folder the app's file boxes may read and write (default: "
                              "$PAPERLIB_FILE_ROOT, else build/explorer_files)")
    explore.add_argument("--open-browser", action="store_true", help="open the page in your browser")


def _is_repository(root: Path) -> bool:
    return (root / "notebooks").is_dir() and (root / "tests" / "expected_stats.toml").is_file()


def _root_hint(root: Path) -> str:
    """Why the error may come from the folder, and the ``--root`` that would work; empty inside a repository."""
    root = Path(root)
    if _is_repository(root):
        return ""
    here = root.resolve()
    candidates = [*here.parents, Path(__file__).resolve().parents[1]]
    found = next((folder for folder in candidates if _is_repository(folder)), None)
    hint = (f"hint: {here} is not the paperlib repository (it lacks notebooks/ or tests/expected_stats.toml); "
            "run from the repository's top folder or pass --root")
    return f"{hint}, e.g. --root {found}" if found else f"{hint} /path/to/paperlib"


def _error(exc: BaseException, root: Path) -> int:
    print(f"error: {exc}", file=sys.stderr)
    hint = _root_hint(root)
    if hint:
        print(hint, file=sys.stderr)
    return 2


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
        return _error(exc, args.root)
    with pd.option_context("display.max_rows", None, "display.width", 250, "display.max_colwidth", 120):
        print(table.to_string(index=False))
    return 0


def _explore(args) -> int:
    from . import apps

    try:
        return apps.serve(args.method, port=args.port, file_root=args.file_root, open_browser=args.open_browser)
    except (TypeError, ValueError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2


def main(argv=None) -> int:
    """Run ``python -m paperlib`` with ``argv`` (default: the command line); the exit status.

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``python -m paperlib``.

    Returns
    -------
    int
        0 when every notebook ran and every statistic is within tolerance, 1 on a failed
        notebook or statistic, 2 on a usage error; for ``explore``, Voila's exit status.
    """
    args = build_parser().parse_args(argv)
    if args.command == "seed-study":
        return _seed_study(args)
    if args.command == "explore":
        return _explore(args)
    try:
        runs, table = reproduce_module.reproduce(
            args.root, quality=args.quality, only=args.only, jobs=args.jobs, seed=args.seed, timeout=args.timeout,
            figures_dir=args.figures_dir, progress=args.progress,
        )
    except ValueError as exc:
        return _error(exc, args.root)
    print(reproduce_module.format_summary(runs, table))
    problems = reproduce_module.failures(runs, table)
    for problem in problems:
        print(f"FAILED {problem}", file=sys.stderr)
    if not problems:
        print(f"\nall {len(runs)} notebook(s) ran and all {len(table)} statistic(s) are within tolerance")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
