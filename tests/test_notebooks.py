"""The notebook contract (DESIGN.md) and every notebook run through papermill.

Every notebook runs twice at CI quality with the same seeds, into temporary folders
(the committed figures/ are left alone): the first run's statistics must satisfy
tests/expected_stats.toml, and both runs must record identical statistics apart from
wall times (``time_*``).
"""

import ast
from pathlib import Path

import nbformat
import pytest

from paperlib import repro
from paperlib.reproduce import reproduce

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
EXPECTED = repro.load_expected(ROOT / "tests" / "expected_stats.toml")
CELL_TIMEOUT = 1800  # seconds; a hung cell fails the run instead of eating CI's budget
ids = [path.stem for path in NOTEBOOKS]


def test_there_are_notebooks():
    assert NOTEBOOKS, "notebooks/ holds no notebook"


def test_every_expected_entry_has_a_notebook():
    assert set(EXPECTED) <= {path.stem for path in NOTEBOOKS}, "expected_stats.toml names a notebook that is gone"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=ids)
def test_first_code_cell_is_tagged_parameters_with_seed_quality_out_dir(path):
    notebook = nbformat.read(path, as_version=4)
    code_cells = [cell for cell in notebook.cells if cell.cell_type == "code"]
    assert code_cells and "parameters" in code_cells[0].metadata.get("tags", [])
    assigned = {
        target.id
        for node in ast.parse(code_cells[0].source).body
        if isinstance(node, ast.Assign)
        for target in node.targets
        if isinstance(target, ast.Name)
    }
    assert {"seed", "quality", "out_dir"} <= assigned


@pytest.mark.parametrize("path", NOTEBOOKS, ids=ids)
def test_opens_with_a_markdown_cell(path):
    notebook = nbformat.read(path, as_version=4)
    assert notebook.cells[0].cell_type == "markdown" and len(notebook.cells[0].source) > 100


@pytest.mark.parametrize("path", NOTEBOOKS, ids=ids)
def test_stored_without_outputs(path):
    notebook = nbformat.read(path, as_version=4)
    for cell in notebook.cells:
        if cell.cell_type == "code":
            assert not cell.outputs and cell.execution_count is None, "run `make strip`"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=ids)
def test_has_expected_statistics(path):
    assert EXPECTED.get(path.stem), f"{path.stem} has no entry in tests/expected_stats.toml"


def run_all(tmp_path_factory, name):
    folder = tmp_path_factory.mktemp(name)
    runs, _table = reproduce(
        ROOT, quality="ci", jobs=2, timeout=CELL_TIMEOUT, progress=False,
        figures_dir=folder / "figures", build_dir=folder / "build",
    )
    return {run.notebook: run for run in runs}, folder / "figures"


@pytest.fixture(scope="session")
def first_run(tmp_path_factory):
    return run_all(tmp_path_factory, "first")


@pytest.fixture(scope="session")
def second_run(tmp_path_factory):
    return run_all(tmp_path_factory, "second")


@pytest.mark.notebooks
@pytest.mark.parametrize("stem", ids)
def test_notebook_runs_and_statistics_are_within_tolerance(first_run, stem):
    runs, figures = first_run
    assert runs[stem].ok, runs[stem].error
    table = repro.check_stats(figures, EXPECTED, notebooks=[stem])
    failing = table[~table.ok]
    assert failing.empty, "\n" + failing[["statistic", "value", "expected", "reason"]].to_string()


@pytest.mark.notebooks
@pytest.mark.parametrize("stem", ids)
def test_same_seed_same_statistics(first_run, second_run, stem):
    (runs_a, figures_a), (runs_b, figures_b) = first_run, second_run
    assert runs_a[stem].ok and runs_b[stem].ok
    a = repro.load_stats(figures_a / stem / repro.STATS_FILE)
    b = repro.load_stats(figures_b / stem / repro.STATS_FILE)
    assert repro.statistics_without_times(a) == repro.statistics_without_times(b)
    assert a["seed"] == b["seed"] and a["quality"] == b["quality"] == "ci"
