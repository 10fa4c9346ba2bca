"""Write the generated pages of the documentation site into ``docs/_generated/`` (git-ignored).

Called by ``docs/conf.py`` when Sphinx starts (``builder-inited``), before it reads any source; it can also be
run by hand (``python docs/generate.py``) to look at what it writes. Nothing here executes a notebook:

- one page per notebook of ``notebooks/``, ``_generated/notebooks/<stem>.ipynb``. When the executed copy that
  ``make reproduce`` left in ``build/notebooks/<stem>.ipynb`` is of the same quality as the committed figures
  (``figures/<stem>/stats.json``), the page is that copy (code, printed outputs, tables); otherwise (a fresh
  clone, CI, or an executed copy of another quality) it is the source notebook's markdown cells only. Either
  way the page says which, and shows the quality and seed of the figures, the committed figures of
  ``figures/<stem>/`` inline, and the recorded statistics beside their expected bound, kind, source and status
  (:func:`paperlib.reproduce.statistics_table`, the table of ``figures/INDEX.md``). myst-nb renders the pages
  with ``nb_execution_mode = "off"``;
- per paper, ``_generated/papers/<paper>.md``: its notebooks (quality, seed, status counts) and its claims
  ledger (``figures/ledger_<paper>.md``, written by ``make reproduce``), included by ``docs/papers/<paper>.md``;
- the API reference, one page per public module (``tests/fuzz_registry.py``'s ``MODULES``).
"""

from __future__ import annotations

import ast
import copy
import os
import shutil
from pathlib import Path

import nbformat

ROOT = Path(__file__).resolve().parents[1]
GENERATED = "_generated"
#: Where ``make reproduce`` leaves its executed copies; ``PAPERLIB_DOCS_EXECUTED`` overrides it (a folder
#: without notebooks, e.g. ``/nonexistent``, renders every page from its source notebook).
EXECUTED_ENV = "PAPERLIB_DOCS_EXECUTED"
WIDGET_MIME = "application/vnd.jupyter.widget-view+json"
#: Output types that need a live kernel or fetch scripts; such an output is replaced by a line saying so.
DROPPED_MIMES = (WIDGET_MIME, "application/javascript", "application/vnd.jupyter.widget-state+json")
PAPER_ORDER = ("hurtut2009", "barla2006", "kim2009", "alvarez2015", "simhon2001")


def public_modules(root: Path = ROOT) -> list[str]:
    """The public modules of the API reference: ``MODULES`` of ``tests/fuzz_registry.py`` (read, not imported).

    Parameters
    ----------
    root : pathlib.Path
        The repository.

    Returns
    -------
    list of str
        Module names, ``paperlib.apps`` included.
    """
    tree = ast.parse((root / "tests" / "fuzz_registry.py").read_text(encoding="utf-8"))
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == "MODULES" for t in node.targets):
            modules = list(ast.literal_eval(node.value))
            break
    else:
        raise ValueError("tests/fuzz_registry.py defines no MODULES")
    return modules + [name for name in ("paperlib.apps",) if name not in modules]


def _write(path: Path, text: str) -> None:
    """Write ``text`` unless the file already holds it (Sphinx then keeps its cached page)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def _copy(source: Path, target: Path) -> None:
    target.parent.mkdir(parents=True, exist_ok=True)
    if not target.exists() or target.stat().st_size != source.stat().st_size or \
            target.stat().st_mtime < source.stat().st_mtime:
        shutil.copy2(source, target)


def _parameters(notebook) -> dict:
    """The values papermill injected (``quality``, ``seed``) into an executed copy, as far as they are literals."""
    values = {}
    for cell in notebook.cells:
        if cell.cell_type == "code" and "injected-parameters" in cell.get("metadata", {}).get("tags", []):
            for node in ast.parse(cell.source).body:
                if isinstance(node, ast.Assign) and len(node.targets) == 1 and hasattr(node.targets[0], "id"):
                    try:
                        values[node.targets[0].id] = ast.literal_eval(node.value)
                    except ValueError:
                        pass
    return values


def _clean_outputs(notebook) -> None:
    """Replace widget views and scripts (they need a kernel and fetch JavaScript from CDNs) by a line saying so."""
    notebook.metadata.pop("widgets", None)
    for cell in notebook.cells:
        for output in cell.get("outputs", []):
            data = output.get("data")
            if data and any(mime in data for mime in DROPPED_MIMES):
                output["data"] = {"text/plain": "(a Jupyter widget was shown here: it needs a live kernel; "
                                                "the explorers are on the page Explore interactively)"}


def _figures(folder: Path) -> list[Path]:
    """The committed figures of a notebook: each PNG, or the SVG where a figure has no PNG."""
    if not folder.is_dir():
        return []
    files = sorted(p for p in folder.iterdir() if p.suffix in (".png", ".svg"))
    pngs = {p.stem for p in files if p.suffix == ".png"}
    return [p for p in files if p.suffix == ".png" or p.stem not in pngs]


def _status_counts(rows) -> str:
    counts = rows.status.value_counts()
    return ", ".join(f"{int(n)} {status}" for status, n in counts.items()) or "none recorded"


class Generator:
    """Writes every generated page for one build.

    Parameters
    ----------
    out : pathlib.Path
        ``docs/_generated``.
    root : pathlib.Path
        The repository.
    executed : pathlib.Path, optional
        The folder of executed notebooks, by default ``build/notebooks`` (or ``$PAPERLIB_DOCS_EXECUTED``).
    """

    def __init__(self, out: Path, root: Path = ROOT, executed: Path | None = None):
        from paperlib import repro, reproduce

        self.repro, self.reproduce = repro, reproduce
        self.out, self.root = Path(out), Path(root)
        self.layout = reproduce.Layout.of(self.root)
        default = os.environ.get(EXECUTED_ENV) or self.layout.build / "notebooks"
        self.executed = Path(executed) if executed is not None else Path(default)
        self.stems = [path.stem for path in reproduce.find_notebooks(self.layout.notebooks)]
        expected = reproduce._expected_for_index(self.layout, self.stems)
        self.table = repro.check_stats(self.layout.figures, expected, notebooks=self.stems)
        self.runs = {stem: self._stored_run(stem) for stem in self.stems}

    def _stored_run(self, stem: str) -> dict:
        try:
            return self.repro.load_stats(self.layout.figures / stem / self.repro.STATS_FILE)
        except (ValueError, OSError):
            return {}

    def run(self) -> list[Path]:
        """Write all pages; return the notebook pages written.

        Returns
        -------
        list of pathlib.Path
            One ``.ipynb`` per notebook of ``notebooks/``.
        """
        self.out.mkdir(parents=True, exist_ok=True)
        pages = [self.notebook_page(stem) for stem in self.stems]
        for stale in (self.out / "notebooks").glob("*.ipynb"):
            if stale not in pages:
                stale.unlink()
        self.notebook_index()
        for paper in PAPER_ORDER:
            self.paper_extra(paper)
        self.api_pages()
        self.index_extra()
        return pages

    # --- notebooks -------------------------------------------------------------------------------------
    def _provenance(self, stem: str, executed_used: bool, why: str) -> str:
        run = self.runs[stem]
        quality, seed = run.get("quality", "not run"), run.get("seed", "not run")
        paper, _figure = self.reproduce.paper_and_figure(stem)
        rows = self.table[self.table.notebook == stem]
        paper_link = f"{{doc}}`/papers/{paper}`" if paper in PAPER_ORDER else "none (a project-wide notebook)"
        if executed_used:
            source = (f"Rendered from the **executed copy** `build/notebooks/{stem}.ipynb` that `make reproduce` "
                      "left (code, printed outputs and tables as that run produced them; nothing was executed to "
                      "build this page).")
        else:
            source = (f"Rendered from the **notebook source** `notebooks/{stem}.ipynb`: its markdown cells only, "
                      f"{why}. Run `make reproduce`, then `make docs`, to see the code and its outputs.")
        return "\n".join([
            ":::{admonition} How this page was made",
            ":class: note",
            "",
            f"**Figures of quality `{quality}`, seed `{seed}`** (recorded in `figures/{stem}/stats.json`, "
            "written by `make reproduce`).",
            "",
            source,
            "",
            f"Paper: {paper_link}. Statistics: {_status_counts(rows)} "
            f"(see {{ref}}`Recorded statistics <stats-{stem}>`).",
            ":::",
        ])

    def _figure_cell(self, stem: str) -> str:
        run = self.runs[stem]
        figures = _figures(self.layout.figures / stem)
        lines = ["## Figures", "",
                 f"The committed figures of `figures/{stem}/` (quality `{run.get('quality', 'not run')}`, "
                 f"seed `{run.get('seed', 'not run')}`).", ""]
        if not figures:
            lines.append("This notebook saves no figure.")
        for path in figures:
            target = self.out / "figures" / stem / path.name
            _copy(path, target)
            lines += [f"![{path.stem}](../figures/{stem}/{path.name})", "", f"*{path.name}*", ""]
        return "\n".join(lines)

    def _statistics_cell(self, stem: str) -> str:
        rows = self.table[self.table.notebook == stem]
        lines = [f"(stats-{stem})=", "## Recorded statistics", "",
                 "Each statistic the run recorded, the bound `tests/expected_stats.toml` sets, its kind (where the "
                 "bound comes from: paper, oracle, truth, seed-study, budget; see {doc}`/statistics`), its status "
                 "(pass; xfail: a paper claim we miss, with the measured value; shown: wall times, never "
                 "asserted; skipped: needs an optional package) and its source.", ""]
        if rows.empty:
            lines.append("No statistic recorded.")
        else:
            lines += self.reproduce.statistics_table(rows)
        return "\n".join(lines)

    def notebook_page(self, stem: str) -> Path:
        """Write the page of one notebook.

        Parameters
        ----------
        stem : str
            The notebook's name without ``.ipynb``.

        Returns
        -------
        pathlib.Path
            The page written, ``_generated/notebooks/<stem>.ipynb``.
        """
        source = nbformat.read(self.layout.notebooks / f"{stem}.ipynb", as_version=4)
        executed_path = self.executed / f"{stem}.ipynb"
        quality = self.runs[stem].get("quality")
        executed_used, why = False, "because there is no executed copy in `build/notebooks/` (a fresh clone, CI)"
        if executed_path.is_file():
            executed = nbformat.read(executed_path, as_version=4)
            ran = _parameters(executed)
            if ran.get("quality") != quality:
                why = (f"because the executed copy in `build/notebooks/` is of quality `{ran.get('quality')}` "
                       f"and the committed figures of quality `{quality}`")
            elif "seed" in ran and ran["seed"] != self.runs[stem].get("seed"):
                why = "because the executed copy in `build/notebooks/` ran another seed than the committed figures"
            else:
                notebook, executed_used = copy.deepcopy(executed), True
        if not executed_used:
            notebook = nbformat.v4.new_notebook(metadata=copy.deepcopy(source.metadata))
            notebook.cells = [nbformat.v4.new_markdown_cell(cell.source) for cell in source.cells
                              if cell.cell_type == "markdown"]
        _clean_outputs(notebook)
        cells = notebook.cells
        has_title = bool(cells) and cells[0].cell_type == "markdown" and cells[0].source.lstrip().startswith("# ")
        title, intro = (cells[0].source.lstrip().split("\n", 1) + [""])[:2] if has_title else (f"# {stem}", "")
        rest = cells[1:] if has_title else cells
        # the title, how the page was made, the notebook's introduction (the paper's claim), the figures beside it
        head = [nbformat.v4.new_markdown_cell(title),
                nbformat.v4.new_markdown_cell(self._provenance(stem, executed_used, why))]
        inserted = [*([nbformat.v4.new_markdown_cell(intro)] if intro.strip() else []),
                    nbformat.v4.new_markdown_cell(self._figure_cell(stem)),
                    nbformat.v4.new_markdown_cell(self._statistics_cell(stem)),
                    nbformat.v4.new_markdown_cell("## The notebook" + (
                        "" if executed_used else " (markdown cells of the source)"))]
        notebook.cells = head + inserted + rest
        for number, cell in enumerate(notebook.cells):
            cell["id"] = f"cell-{number}"
        target = self.out / "notebooks" / f"{stem}.ipynb"
        _write(target, nbformat.writes(notebook))
        return target

    def notebook_index(self) -> None:
        """Write ``_generated/notebooks/index.md``: every notebook page, grouped by paper."""
        lines = ["# Notebooks", "",
                 "One page per notebook of `notebooks/`: its figures inline, the quality and seed that made them, "
                 "and its statistics against their bounds.", "",
                 "| notebook | paper | quality | seed | statistics |", "|---|---|---|---|---|"]
        for stem in self.stems:
            paper, _ = self.reproduce.paper_and_figure(stem)
            run = self.runs[stem]
            rows = self.table[self.table.notebook == stem]
            paper_link = f"{{doc}}`{paper} </papers/{paper}>`" if paper in PAPER_ORDER else "-"
            lines.append(f"| {{doc}}`{stem}` | {paper_link} | {run.get('quality', 'not run')} | "
                         f"{run.get('seed', 'not run')} | {_status_counts(rows)} |")
        lines += ["", "```{toctree}", ":hidden:", "", *self.stems, "```", ""]
        _write(self.out / "notebooks" / "index.md", "\n".join(lines))

    # --- papers ------------------------------------------------------------------------------------------
    def paper_extra(self, paper: str) -> None:
        """Write ``_generated/papers/<paper>.md``: the paper's notebooks and its claims ledger.

        Parameters
        ----------
        paper : str
            ``hurtut2009``, ``barla2006``, ...
        """
        stems = [stem for stem in self.stems if self.reproduce.paper_and_figure(stem)[0] == paper]
        qualities = sorted({str(self.runs[s].get("quality", "not run")) for s in stems})
        seeds = sorted({str(self.runs[s].get("seed", "not run")) for s in stems})
        lines = ["## Notebooks", "",
                 f"Figures of quality `{', '.join(qualities)}`, seed `{', '.join(seeds)}` "
                 "(each notebook's `figures/<notebook>/stats.json`).", "",
                 "| notebook | figure | quality | seed | statistics |", "|---|---|---|---|---|"]
        for stem in stems:
            run = self.runs[stem]
            figure = self.reproduce.paper_and_figure(stem)[1] or "-"
            rows = self.table[self.table.notebook == stem]
            lines.append(f"| {{doc}}`/{GENERATED}/notebooks/{stem}` | {figure} | {run.get('quality', 'not run')} | "
                         f"{run.get('seed', 'not run')} | {_status_counts(rows)} |")
        lines += ["", "## Claims ledger", ""]
        ledger = self.layout.figures / f"ledger_{paper}.md"
        if ledger.is_file():
            body = ledger.read_text(encoding="utf-8").split("\n")
            body = [line for line in body if not line.startswith("# ")]
            lines += [f"From `figures/ledger_{paper}.md` (written by `make reproduce` from `tests/claims/{paper}.toml` "
                      "and the recorded statistics).", "", *body]
        else:
            lines.append(f"No ledger yet: `make reproduce` writes `figures/ledger_{paper}.md`.")
        _write(self.out / "papers" / f"{paper}.md", "\n".join(lines) + "\n")

    # --- API ---------------------------------------------------------------------------------------------
    def api_pages(self) -> None:
        """Write ``_generated/api/``: an index and one autodoc page per public module."""
        modules = public_modules(self.root)
        for module in modules:
            title = module
            _write(self.out / "api" / f"{module}.rst", "\n".join([
                title, "=" * len(title), "", f".. automodule:: {module}", "   :members:", ""]))
        lines = ["# API reference", "",
                 "Generated from the numpydoc docstrings of the public modules (the `__all__` of each).", "",
                 "```{toctree}", ":maxdepth: 1", "", *modules, "```", ""]
        _write(self.out / "api" / "index.md", "\n".join(lines))

    def index_extra(self) -> None:
        """Write ``_generated/index_extra.md``: the headline notebook's link, if it exists."""
        lines = []
        if "scorecard" in self.stems:
            lines = ["The headline **fidelity scorecard** (the same measures, with controls, for every paper): "
                     f"{{doc}}`/{GENERATED}/notebooks/scorecard`.", ""]
        _write(self.out / "index_extra.md", "\n".join(lines) + "\n")


def generate(out: Path | None = None) -> list[Path]:
    """Write every generated page under ``out`` (``docs/_generated`` by default).

    Parameters
    ----------
    out : pathlib.Path, optional
        The folder of generated pages.

    Returns
    -------
    list of pathlib.Path
        The notebook pages.
    """
    return Generator(out or Path(__file__).resolve().parent / GENERATED).run()


if __name__ == "__main__":
    for page in generate():
        print(page)
