"""Run the notebooks with papermill, check their statistics, write ``figures/INDEX.md``.

This is what ``python -m paperlib reproduce`` and ``make reproduce`` do:

1. find ``notebooks/*.ipynb`` (optionally those matching ``--only``);
2. execute each with papermill on a ``python3`` kernel that is *this* interpreter
   (a kernelspec written under ``build/jupyter``, never a kernel named in the
   notebook's metadata), passing ``seed``, ``quality`` and ``out_dir``; the executed
   copy goes to ``build/notebooks/``, the source stays output-free. The kernel talks over
   Unix-domain sockets in a folder of its own, not TCP ports: jupyter_client picks TCP ports by
   binding and releasing them, and a kernel started alongside another may find one taken and die
   before replying (jupyter/jupyter_client#154, nteract/papermill#511);
3. each notebook writes into a staging folder ``build/staging/<stem>/`` that replaces
   ``figures/<stem>/`` only when the notebook finished, so ``figures/`` never holds a
   half-run notebook;
4. check the recorded statistics against ``tests/expected_stats.toml`` and write
   ``figures/INDEX.md``.

Like :mod:`paperlib.repro`, this module knows no method.
"""

from __future__ import annotations

import fnmatch
import json
import os
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from . import repro
from ._atomic import publish_folder, recover_folder
from ._checks import instance_of
from .claims import VERDICTS, ledger_table, load_claims, write_ledger
from .parallel import progress_enabled, run_many

__all__ = [
    "NotebookRun",
    "find_notebooks",
    "kernel_manager_on_sockets_in",
    "paper_and_figure",
    "reproduce",
    "run_notebook",
    "seed_study",
    "write_index",
]

PAPERS = {
    "hurtut2009": "Hurtut, Landes, Thollot, Gousseau, Drouilhet & Coeurjolly 2009, "
    "Appearance-guided synthesis of element arrangements by example",
    "barla2006": "Barla, Breslav, Thollot, Sillion & Markosian 2006, Stroke pattern analysis and synthesis",
    "kim2009": "Kim, Maciejewski, Isenberg, Andrews, Chen, Sousa & Ebert 2009, Stippling by example",
    "alvarez2015": "Alvarez, Gousseau, Morel & Salgado 2015, "
    "Exploring the space of abstract textures by principles and random sampling",
    "simhon2001": "Simhon & Dudek 2001, On the elaboration of hand-drawn sketches",
}
KERNEL_NAME = "python3"


@dataclass(frozen=True)
class Layout:
    """Where the notebooks, figures, build products and expected statistics live."""

    root: Path
    notebooks: Path
    figures: Path
    build: Path
    expected: Path
    claims: Path

    @classmethod
    def of(cls, root=".", *, figures_dir=None, build_dir=None) -> "Layout":
        """The project's standard layout under ``root``; figures and build may move elsewhere."""
        root = Path(root).resolve()
        return cls(
            root=root,
            notebooks=root / "notebooks",
            figures=Path(figures_dir).resolve() if figures_dir else root / "figures",
            build=Path(build_dir).resolve() if build_dir else root / "build",
            expected=root / "tests" / "expected_stats.toml",
            claims=root / "tests" / "claims",
        )


@dataclass(frozen=True)
class NotebookRun:
    """Outcome of one notebook execution.

    Parameters
    ----------
    notebook : str
        The notebook's stem.
    ok : bool
        Whether it ran to the end and wrote its ``stats.json``.
    seconds : float
        Wall time of the execution, in seconds.
    error : str, default ""
        Why it failed (the first line of the error), empty on success.
    """

    notebook: str
    ok: bool
    seconds: float
    error: str = ""


def find_notebooks(notebooks_dir, pattern=None) -> list[Path]:
    """The notebooks in ``notebooks_dir`` whose stem matches ``pattern``, sorted.

    ``pattern`` is a shell glob on the stem (``"kim2009_*"``); without wildcards it
    matches as a substring (``"fig07"``).

    Parameters
    ----------
    notebooks_dir : str or os.PathLike
        The folder holding the ``.ipynb`` files.
    pattern : str or sequence of str, optional
        Shell glob on the stem, or a substring when it has no wildcard; all notebooks when
        None or empty. A sequence selects the notebooks any of its patterns matches.

    Returns
    -------
    list of pathlib.Path
        The matching notebooks, sorted by path.

    Raises
    ------
    ValueError
        When no notebook matches, naming the pattern and the available notebooks.
    """
    instance_of(notebooks_dir, (str, os.PathLike), "notebooks_dir")
    patterns = [] if pattern is None else [pattern] if isinstance(pattern, str) else pattern
    instance_of(patterns, (list, tuple), "pattern")
    for each in patterns:
        instance_of(each, str, "pattern")
    notebooks = sorted(Path(notebooks_dir).glob("*.ipynb"))
    globs = [each if any(char in each for char in "*?[") else f"*{each}*" for each in patterns if each]
    if globs:
        notebooks = [path for path in notebooks if any(fnmatch.fnmatchcase(path.stem, glob) for glob in globs)]
    if not notebooks:
        available = ", ".join(path.stem for path in sorted(Path(notebooks_dir).glob("*.ipynb"))) or "none"
        raise ValueError(f"no notebook in notebooks_dir={str(notebooks_dir)!r:.120} matches pattern={pattern!r:.80} "
                         f"(available: {available})")
    return notebooks


def paper_and_figure(stem: str) -> tuple[str, str]:
    """``("kim2009", "fig07")`` for ``kim2009_fig07_examples``; ``("", "")`` otherwise.

    Parameters
    ----------
    stem : str
        A notebook's stem, ``<paper><year>_figNN_<topic>``.

    Returns
    -------
    paper : str
        The paper's key (one of ``PAPERS``), or ``""`` when the stem names no known paper.
    figure : str
        The ``figNN`` part, or ``""`` when there is none.
    """
    parts = instance_of(stem, str, "stem").split("_")
    if parts[0] in PAPERS:
        figure = parts[1] if len(parts) > 2 and parts[1].startswith("fig") else ""
        return parts[0], figure
    return "", ""


def _install_kernelspec(build_dir: Path) -> None:
    """Make the kernel named ``python3`` run this interpreter, whatever else is installed.

    Jupyter searches ``JUPYTER_PATH`` before the user's and the system's kernel folders,
    so a kernelspec written there wins over a ``python3`` spec pointing elsewhere.
    """
    jupyter_dir = (build_dir / "jupyter").resolve()
    spec_path = jupyter_dir / "kernels" / KERNEL_NAME / "kernel.json"
    spec = {
        # ipykernel minus the false alarms it logs on every orderly shutdown (paperlib._kernel)
        "argv": [sys.executable, "-m", "paperlib._kernel", "-f", "{connection_file}"],
        "display_name": f"Python 3 ({sys.executable})",
        "language": "python",
    }
    if not spec_path.exists() or json.loads(spec_path.read_text()) != spec:
        with repro.atomic_path(spec_path) as temporary:
            temporary.write_text(json.dumps(spec, indent=1))
    paths = os.environ.get("JUPYTER_PATH", "").split(os.pathsep)
    if str(jupyter_dir) not in paths:
        os.environ["JUPYTER_PATH"] = os.pathsep.join([str(jupyter_dir), *filter(None, paths)])


def _first_line_of_error(exc: BaseException) -> str:
    """One readable line: for a cell error, its exception name and message."""
    ename, evalue = getattr(exc, "ename", None), getattr(exc, "evalue", None)
    text = f"{ename}: {evalue}" if ename else f"{type(exc).__name__}: {exc}"
    lines = [line for line in text.strip().splitlines() if line.strip()]
    return lines[0] if lines else type(exc).__name__


def _publish(staging: Path, target: Path) -> None:
    """Replace ``target`` by the finished ``staging`` folder, crash-safe (:func:`paperlib._atomic.publish_folder`)."""
    publish_folder(staging, target)


def recover_figures(figures: Path) -> list[str]:
    """Restore every ``figures/<notebook>`` a crash left set aside mid-publish; the names restored."""
    figures = Path(figures)
    if not figures.is_dir():
        return []
    leftovers = [path for path in figures.glob(".*.old") if path.is_dir()]
    return [path.name[1:-4] for path in leftovers if recover_folder(figures / path.name[1:-4])]


def run_notebook(path, *, layout: Layout, quality: str = "ci", seed: int | None = None, timeout=None,
                 progress=False) -> NotebookRun:
    """Execute one notebook with papermill and publish its figures on success.

    Parameters
    ----------
    path : str or Path
        The notebook.
    layout : Layout
        Where figures and build products go.
    quality : {"ci", "paper"}
    seed : int, optional
        Overrides the notebook's own default seed.
    timeout : float, optional
        Per-cell time limit in seconds.
    progress : bool or None
        Show a tqdm bar over the notebook's cells (None: only when stderr is a terminal).

    Returns
    -------
    NotebookRun
        Whether it ran, how long it took, and the first line of its error.
    """
    import papermill

    if quality not in repro.QUALITIES:
        raise ValueError(f"quality must be one of {repro.QUALITIES}, got {quality!r}")
    path = Path(path).resolve()
    _install_kernelspec(layout.build)
    staging = layout.build / "staging" / path.stem
    shutil.rmtree(staging, ignore_errors=True)
    parameters = {"quality": quality, "out_dir": str(staging)}
    if seed is not None:
        parameters["seed"] = int(seed)
    executed = layout.build / "notebooks" / path.name
    executed.parent.mkdir(parents=True, exist_ok=True)
    began = time.perf_counter()
    sockets = Path(tempfile.mkdtemp(prefix="paperlib-kernel-"))  # short: a socket path holds <= 107 bytes
    try:
        papermill.execute_notebook(
            str(path),
            str(executed),
            parameters=parameters,
            kernel_name=KERNEL_NAME,
            language="python",
            cwd=str(path.parent),
            progress_bar={"desc": path.stem, "unit": "cell"} if progress_enabled(progress) else False,
            execution_timeout=timeout,
            kernel_manager_class=kernel_manager_on_sockets_in(sockets),
        )
    except Exception as exc:  # a failing cell, a dead kernel, a timeout: report, don't crash the batch
        return NotebookRun(path.stem, False, time.perf_counter() - began, _first_line_of_error(exc))
    finally:
        shutil.rmtree(sockets, ignore_errors=True)
    seconds = time.perf_counter() - began
    if not (staging / repro.STATS_FILE).exists():
        return NotebookRun(path.stem, False, seconds, "finished without writing stats.json (no repro.start call)")
    _publish(staging, layout.figures / path.stem)
    return NotebookRun(path.stem, True, seconds)


def kernel_manager_on_sockets_in(folder):
    """A jupyter_client kernel manager class whose kernels listen on Unix-domain sockets in ``folder``.

    Parameters
    ----------
    folder : str or Path
        An existing folder of this kernel's own (the socket files are ``folder/kernel-<n>``).

    Returns
    -------
    type
        A subclass of ``jupyter_client.AsyncKernelManager`` (nbclient's default) with the ``ipc``
        transport: no TCP port is chosen, so no other process can take it first.
    """
    from jupyter_client import AsyncKernelManager

    folder = Path(instance_of(folder, (str, Path), "folder"))
    if not folder.is_dir():
        raise ValueError(f"folder must be an existing folder, got {str(folder)!r}")

    class KernelManagerOnSockets(AsyncKernelManager):
        def __init__(self, **kwargs):
            super().__init__(**kwargs)
            self.transport = "ipc"
            self.ip = str(folder / "kernel")

    return KernelManagerOnSockets


def _run_task(task):
    path, layout, quality, seed, timeout = task
    return run_notebook(path, layout=layout, quality=quality, seed=seed, timeout=timeout)


def reproduce(root=".", *, quality="paper", only=None, jobs=1, seed=None, timeout=None, progress=None,
              figures_dir=None, build_dir=None, client=None):
    """Run notebooks, check statistics, write the index.

    Parameters
    ----------
    root : str or Path
        Project root (``notebooks/``, ``tests/expected_stats.toml``).
    quality : {"ci", "paper"}
    only : str or sequence of str, optional
        Glob or substring selecting notebooks, or several (see :func:`find_notebooks`).
    jobs : int
        Notebooks run in parallel processes (through :func:`paperlib.parallel.run_many`).
    seed : int, optional
        Overrides every notebook's default seed.
    timeout : float, optional
        Per-cell time limit in seconds.
    progress : bool or None
        Show tqdm progress: one bar over the notebooks, or over the cells when a single notebook
        runs here. None (default): only when stderr is a terminal.
    figures_dir, build_dir : str or Path, optional
        Put figures and build products elsewhere than ``root/figures`` and ``root/build``.
    client : dask.distributed.Client, optional
        Run the notebooks on this Dask cluster instead of local processes; ``jobs`` is then
        ignored. Every worker needs paperlib, its dependencies and the project folder at the
        same path (a shared file system): the executed notebooks and figures are written there.

    Returns
    -------
    runs : list of NotebookRun
    table : pandas.DataFrame
        The statistics check of :func:`paperlib.repro.check_stats` for the notebooks
        that ran successfully.
    """
    layout = Layout.of(root, figures_dir=figures_dir, build_dir=build_dir)
    recover_figures(layout.figures)  # a run killed mid-publish left a notebook's figures set aside
    notebooks = find_notebooks(layout.notebooks, only)
    # fail before any work when a selected notebook's expected statistics are missing or malformed
    expected = repro.load_expected(layout.expected, notebooks=[path.stem for path in notebooks])
    progress_enabled(progress)  # a wrong value fails before any work
    tasks = [(path, layout, quality, seed, timeout) for path in notebooks]
    if len(tasks) == 1 and client is None:  # one notebook, run here: show its cells
        runs = [run_notebook(notebooks[0], layout=layout, quality=quality, seed=seed, timeout=timeout,
                             progress=progress)]
    else:
        runs = run_many(_run_task, tasks, seeded=False, workers=jobs, progress=progress, desc="notebooks",
                        client=client)
    finished = [run.notebook for run in runs if run.ok]
    table = repro.check_stats(layout.figures, expected, notebooks=finished)
    all_stems = [path.stem for path in find_notebooks(layout.notebooks)]
    write_index(layout, all_stems, _expected_for_index(layout, all_stems))
    return runs, table


def _expected_for_index(layout: Layout, stems) -> dict:
    """Every notebook's expected statistics; a notebook whose file is malformed is left out (its index
    section then says it has no valid entry) so that running one notebook never depends on another's file."""
    expected = {}
    for stem in stems:
        try:
            expected.update(repro.load_expected(layout.expected, notebooks=[stem]))
        except ValueError:
            continue
    return expected


def seed_study(root=".", *, only, seeds, quality="ci", jobs=1, timeout=None, build_dir=None,
               client=None) -> pd.DataFrame:
    """Run notebooks over several seeds and tabulate each statistic's spread.

    This is how a ``seed-study`` bound of ``tests/expected_stats.toml`` is measured: the range a
    statistic takes over seeds, on this library. Figures go under
    ``build/seed-study/<quality>/seed-<seed>/``, never into ``figures/``.

    Parameters
    ----------
    root : str or Path
        Project root.
    only : str
        Glob or substring selecting notebooks (see :func:`find_notebooks`).
    seeds : iterable of int
        The seeds to run, at least two.
    quality : {"ci", "paper"}
    jobs : int
        Notebooks run in parallel processes.
    timeout : float, optional
        Per-cell time limit in seconds.
    build_dir : str or Path, optional
        Instead of ``root/build``.
    client : dask.distributed.Client, optional
        Run on this Dask cluster (workers sharing the project folder), as :func:`reproduce`.

    Returns
    -------
    pandas.DataFrame
        One row per notebook and numeric statistic (wall times excluded): ``min``,
        ``max``, ``n_seeds`` and ``values`` (the value at each seed, in seed order);
        non-numeric statistics show ``n_distinct`` instead. Failed runs raise.
    """
    seeds = [int(seed) for seed in seeds]
    if len(seeds) < 2 or len(set(seeds)) != len(seeds):
        raise ValueError(f"seeds must be at least two distinct integers, got {seeds!r}")
    layout = Layout.of(root, build_dir=build_dir)
    notebooks = find_notebooks(layout.notebooks, only)
    tasks = []
    for seed in seeds:
        folder = layout.build / "seed-study" / quality / f"seed-{seed}"
        seeded_layout = Layout.of(root, figures_dir=folder / "figures", build_dir=folder / "build")
        tasks += [(path, seeded_layout, quality, seed, timeout) for path in notebooks]
    runs = run_many(_run_task, tasks, seeded=False, workers=jobs, progress=False, client=client)
    failed = [f"{run.notebook}: {run.error}" for run in runs if not run.ok]
    if failed:
        raise RuntimeError("seed study: notebooks failed: " + "; ".join(failed))
    values: dict[tuple[str, str], list] = {}
    for (_path, seeded_layout, *_), run in zip(tasks, runs):
        statistics = repro.load_stats(seeded_layout.figures / run.notebook / repro.STATS_FILE)
        for name, value in repro.statistics_without_times(statistics).items():
            values.setdefault((run.notebook, name), []).append(value)
    return pd.DataFrame([_spread(notebook, name, items) for (notebook, name), items in values.items()])


def _spread(notebook: str, statistic: str, items: list) -> dict:
    numeric = all(isinstance(item, (int, float)) and not isinstance(item, bool) for item in items)
    row = {"notebook": notebook, "statistic": statistic, "n_seeds": len(items)}
    if numeric:
        row.update(min=min(items), max=max(items), n_distinct=len(set(items)))
    else:
        row.update(min=None, max=None, n_distinct=len({json.dumps(item, sort_keys=True) for item in items}))
    row["values"] = json.dumps(items)[:200]
    return row


def write_index(layout: Layout, stems, expected: dict) -> Path:
    """Write ``figures/INDEX.md`` and a claims ledger per paper (``figures/ledger_<paper>.md``).

    The index opens with the provenance of the statistics (how many of each kind per
    paper and per notebook), the run quality of each notebook, the expected failures
    (paper claims we miss) in one list, and links to the ledgers; then each notebook's
    files and statistics.

    Parameters
    ----------
    layout : Layout
        The project's folders (:meth:`Layout.of`); the index and ledgers go in
        ``layout.figures``.
    stems : list or tuple of str
        The notebook stems to index, in the order of their sections.
    expected : dict
        The expected statistics, ``{notebook: {statistic: spec}}``
        (:func:`paperlib.repro.load_expected`).

    Returns
    -------
    pathlib.Path
        The index written, ``layout.figures / "INDEX.md"``.
    """
    instance_of(layout, Layout, "layout")
    instance_of(expected, dict, "expected")
    for stem in instance_of(stems, (list, tuple), "stems"):
        instance_of(stem, str, "each of stems")
    table = repro.check_stats(layout.figures, expected, notebooks=stems)
    ledgers = _write_ledgers(layout, table)
    lines = [
        "# Figures",
        "",
        "Written by `python -m paperlib reproduce`; do not edit. Each statistic is shown with the value recorded",
        "by the last run, what `tests/expected_stats.toml` expects, its kind (where the bound comes from:",
        "`paper`, `oracle`, `truth`, `seed-study`, `budget`; see DESIGN.md) and its source. Wall times (`time_*`)",
        "are shown, never asserted.",
        "",
        *_provenance_section(layout, table, stems),
        *_ledger_section(ledgers),
        *_expected_failures_section(table),
    ]
    for stem in stems:
        lines += _notebook_section(layout, stem, table[table.notebook == stem])
    index = layout.figures / "INDEX.md"
    with repro.atomic_path(index) as temporary:
        temporary.write_text("\n".join(lines))
    return index


def _stored_quality(folder: Path) -> str:
    """The quality (``ci``/``paper``) of the run whose ``stats.json`` is in ``folder``."""
    try:
        return repro.load_stats(folder / repro.STATS_FILE).get("quality", "?")
    except ValueError:
        return "not run"


def _provenance_section(layout: Layout, table: pd.DataFrame, stems) -> list[str]:
    asserted = table[table.status != "shown"]
    counts = pd.crosstab(asserted.notebook, asserted.kind).reindex(index=stems, columns=list(repro.KINDS),
                                                                    fill_value=0)
    papers = counts.groupby([paper_and_figure(stem)[0] or "project data" for stem in counts.index]).sum()
    papers.loc["all"] = counts.sum()
    kinds = " | ".join(repro.KINDS)

    def numbers(row) -> str:
        return " | ".join(str(int(n)) for n in row) + f" | {int(row.sum())} |"

    return [
        "## Provenance of the statistics",
        "",
        "Asserted statistics by kind:",
        "",
        f"| notebooks of | {kinds} | total |",
        "|---" * (len(repro.KINDS) + 2) + "|",
        *[f"| {paper} | {numbers(row)}" for paper, row in papers.iterrows()],
        "",
        f"| notebook | quality of the recorded run | {kinds} | total |",
        "|---" * (len(repro.KINDS) + 3) + "|",
        *[f"| {stem} | {_stored_quality(layout.figures / stem)} | {numbers(row)}" for stem, row in counts.iterrows()],
        "",
    ]


def _write_ledgers(layout: Layout, table: pd.DataFrame) -> dict[str, tuple[Path, pd.Series]]:
    """Write ``ledger_<paper>.md`` for every claims file; return paper -> (path, verdict counts)."""
    written = {}
    for path in sorted(layout.claims.glob("*.toml")) if layout.claims.is_dir() else []:
        try:
            claims = load_claims(path)
        except ValueError:
            continue  # tests/test_claims.py names the problem; the index must still be written
        notebooks = table[table.notebook.str.startswith(f"{claims.paper}_")]
        ledger = ledger_table(claims, notebooks)
        target = write_ledger(layout.figures / f"ledger_{claims.paper}.md", PAPERS.get(claims.paper, claims.paper),
                              ledger)
        written[claims.paper] = (target, ledger.verdict.value_counts())
    return written


def _ledger_section(ledgers) -> list[str]:
    if not ledgers:
        return []
    lines = ["## Claims ledgers", "", "| paper | ledger | " + " | ".join(VERDICTS) + " |",
             "|---|---|" + "---|" * len(VERDICTS)]
    for paper, (path, counts) in ledgers.items():
        lines.append(f"| {PAPERS.get(paper, paper)} | [{path.name}]({path.name}) | "
                     + " | ".join(str(int(counts.get(verdict, 0))) for verdict in VERDICTS) + " |")
    return lines + [""]


def _expected_failures_section(table: pd.DataFrame) -> list[str]:
    missed = table[table.status == "xfail"]
    lines = ["## Paper claims we miss (expected failures)", ""]
    if missed.empty:
        return lines + ["None.", ""]
    lines += ["| notebook | statistic | value | paper's bound | measured and why |", "|---|---|---|---|---|"]
    for row in missed.itertuples():
        lines.append(f"| {row.notebook} | {row.statistic} | {_value_text(row.value)} | {row.expected} | "
                     f"{row.reason.removeprefix('expected failure: ')} |")
    return lines + [""]


def _value_text(value) -> str:
    text = "" if value is None else json.dumps(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _notebook_section(layout: Layout, stem: str, rows: pd.DataFrame) -> list[str]:
    paper, figure = paper_and_figure(stem)
    folder = layout.figures / stem
    files = sorted(p.name for p in folder.iterdir() if p.is_file()) if folder.is_dir() else []
    lines = [
        f"## {stem}",
        "",
        f"- paper: {PAPERS.get(paper, 'none (project data)')}",
        f"- figure: {figure or 'none'}",
        f"- quality of the recorded run: {_stored_quality(folder)}",
        f"- notebook: [`notebooks/{stem}.ipynb`](../notebooks/{stem}.ipynb)",
        "- files: " + (", ".join(f"[{name}]({stem}/{name})" for name in files) or "none yet"),
        "",
        *statistics_table(rows),
    ]
    return lines + [""]


def statistics_table(rows: pd.DataFrame) -> list[str]:
    """A Markdown table of checked statistics: value, expected bound, tolerance, kind, status and source.

    The table of each notebook's section of ``figures/INDEX.md``, also shown on the notebook's page of the
    documentation site (``docs/generate.py``). A status other than pass, xfail, shown or skipped is followed
    by its reason; a ``|`` inside a cell is escaped so that the table keeps its columns.

    Parameters
    ----------
    rows : pandas.DataFrame
        Rows of :func:`paperlib.repro.check_stats` (columns ``statistic``, ``value``, ``expected``,
        ``tolerance``, ``kind``, ``status``, ``reason``, ``source``), usually one notebook's.

    Returns
    -------
    list of str
        The header, the separator and one line per row.
    """
    instance_of(rows, pd.DataFrame, "rows")
    lines = ["| statistic | value | expected | tolerance | kind | status | source |", "|---|---|---|---|---|---|---|"]
    for row in rows.itertuples():
        status = row.status if row.status in repro.OK_STATUSES else f"{row.status}: {row.reason}"
        cells = [row.statistic, _value_text(row.value), row.expected, row.tolerance, row.kind, status, row.source]
        lines.append("| " + " | ".join(str(cell).replace("|", "\\|").replace("\n", " ") for cell in cells) + " |")
    return lines


def format_summary(runs, table: pd.DataFrame) -> str:
    """The text printed at the end of a reproduce run."""
    lines = ["", "notebook runs:"]
    lines += [f"  {'ok  ' if run.ok else 'FAIL'} {run.seconds:8.1f} s  {run.notebook}" for run in runs]
    if len(table):
        shown = table[["notebook", "statistic", "value", "expected", "tolerance", "ok"]].copy()
        shown["value"] = shown["value"].map(lambda v: (json.dumps(v)[:40]) if v is not None else "")
        lines += ["", "statistics:", shown.to_string(index=False)]
    return "\n".join(lines)


def failures(runs, table: pd.DataFrame) -> list[str]:
    """One line per problem, naming the notebook."""
    problems = [f"{run.notebook}: notebook failed: {run.error}" for run in runs if not run.ok]
    for row in table[~table.ok].itertuples():
        what = f"statistic {row.statistic!r}: " if row.statistic else ""
        problems.append(f"{row.notebook}: {what}{row.reason}")
    return problems
