"""`python -m paperlib reproduce` on a throwaway project: success and every bad input."""

import json
import sys
import textwrap

import nbformat
import pytest

from paperlib import repro
from paperlib.__main__ import main
from paperlib.reproduce import find_notebooks, paper_and_figure

pytestmark = pytest.mark.notebooks

PARAMETERS = 'seed = 0\nquality = "ci"\nout_dir = "../figures/{stem}"'
START = "from paperlib import repro\nrepro.start(out_dir, seed=seed, quality=quality)"
#: How the kernel talks to papermill, recorded by the demo notebook (``ipc``: Unix-domain sockets).
RECORD_TRANSPORT = ('from ipykernel import get_connection_info\n'
                    'repro.record("transport", get_connection_info(unpack=True)["transport"])')


def write_notebook(root, stem, body):
    cells = [nbformat.v4.new_code_cell(PARAMETERS.format(stem=stem)), nbformat.v4.new_code_cell(START)]
    cells[0].metadata["tags"] = ["parameters"]
    cells.append(nbformat.v4.new_code_cell(textwrap.dedent(body)))
    path = root / "notebooks" / f"{stem}.ipynb"
    path.parent.mkdir(parents=True, exist_ok=True)
    nbformat.write(nbformat.v4.new_notebook(cells=cells), path)
    return path


@pytest.fixture
def project(tmp_path):
    write_notebook(
        tmp_path,
        "kim2009_fig01_demo",
        textwrap.dedent("""
        import sys
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots()
        ax.plot([0, 1])
        repro.save_figure(fig, "line")
        repro.record("answer", 6 * 7)
        repro.record("executable", sys.executable)
        repro.record("quality_seen", quality)
        """) + RECORD_TRANSPORT,
    )
    (tmp_path / "tests").mkdir()
    (tmp_path / "tests" / "expected_stats.toml").write_text(
        textwrap.dedent(
            f"""
            [kim2009_fig01_demo.answer]
            kind = "truth"
            value = 42
            source = "ground truth"

            [kim2009_fig01_demo.executable]
            kind = "truth"
            value = {json.dumps(sys.executable)}
            source = "by construction: the kernel must be this interpreter"

            [kim2009_fig01_demo.quality_seen]
            kind = "truth"
            value = "ci"
            source = "by construction: the --quality flag reaches the notebook"

            [kim2009_fig01_demo.transport]
            kind = "truth"
            value = "ipc"
            source = "by construction: kernels listen on Unix-domain sockets, no TCP port to lose to a race"
            """
        )
    )
    return tmp_path


def run_cli(project, *args):
    return main(["reproduce", "--root", str(project), "--quality", "ci", *args])


def test_success_publishes_figures_index_and_executed_copy(project, capsys):
    source = (project / "notebooks" / "kim2009_fig01_demo.ipynb").read_text()
    assert run_cli(project) == 0
    out = capsys.readouterr().out
    assert "all 1 notebook(s) ran and all 4 statistic(s)" in out
    figures = project / "figures" / "kim2009_fig01_demo"
    assert sorted(p.name for p in figures.iterdir()) == ["line.png", "stats.json"]
    assert repro.load_stats(figures / "stats.json")["statistics"]["executable"] == sys.executable
    assert (project / "notebooks" / "kim2009_fig01_demo.ipynb").read_text() == source  # still output-free
    executed = nbformat.read(project / "build" / "notebooks" / "kim2009_fig01_demo.ipynb", as_version=4)
    assert any(cell.get("outputs") is not None for cell in executed.cells)
    index = (project / "figures" / "INDEX.md").read_text()
    assert "Kim" in index and "fig01" in index and "| answer | 42 | 42 | exact | truth | pass |" in index
    assert "| kim2009_fig01_demo | ci | 0 | 0 | 4 | 0 | 0 | 4 |" in index  # provenance: four truths


def test_unknown_pattern_is_one_clear_line(project, capsys):
    assert run_cli(project, "--only", "nosuchfigure") == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "nosuchfigure" in err[0] and "kim2009_fig01_demo" in err[0]


def test_missing_expected_file(project, capsys):
    (project / "tests" / "expected_stats.toml").unlink()
    assert run_cli(project) == 2
    assert "expected statistics file not found" in capsys.readouterr().err


def test_failing_notebook_is_named_and_old_figures_survive(project, capsys):
    assert run_cli(project) == 0
    figures = project / "figures" / "kim2009_fig01_demo"
    before = {p.name: p.read_bytes() for p in figures.iterdir()}
    write_notebook(project, "kim2009_fig01_demo", 'repro.record("answer", 1)\nraise RuntimeError("boom")')
    capsys.readouterr()
    assert run_cli(project) == 1
    err = capsys.readouterr().err
    assert "FAILED kim2009_fig01_demo: notebook failed: RuntimeError: boom" in err
    assert {p.name: p.read_bytes() for p in figures.iterdir()} == before


def test_wrong_and_missing_statistics_fail(project, capsys):
    write_notebook(project, "kim2009_fig01_demo", 'repro.record("answer", "42")\nrepro.record("stray", 1)')
    assert run_cli(project) == 1
    err = capsys.readouterr().err
    assert "statistic 'answer': expected a number, got str" in err
    assert "statistic 'executable': expected but not recorded" in err
    assert "statistic 'stray': recorded but not in tests/expected_stats.toml" in err


def test_parallel_jobs_run_every_selected_notebook(project, capsys):
    write_notebook(project, "simhon2001_fig02_other", 'repro.record("answer", 1)')
    with (project / "tests" / "expected_stats.toml").open("a") as handle:
        handle.write('\n[simhon2001_fig02_other.answer]\nkind = "truth"\nvalue = 1\nsource = "ground truth"\n')
    assert run_cli(project, "--jobs", "2") == 0
    assert (project / "figures" / "simhon2001_fig02_other" / "stats.json").exists()
    assert run_cli(project, "--only", "simhon*") == 0
    assert "all 1 notebook(s)" in capsys.readouterr().out


def test_find_notebooks_patterns(project):
    write_notebook(project, "simhon2001_fig02_other", "pass")
    folder = project / "notebooks"
    assert [p.stem for p in find_notebooks(folder, "fig02")] == ["simhon2001_fig02_other"]
    assert [p.stem for p in find_notebooks(folder, "*demo")] == ["kim2009_fig01_demo"]
    assert len(find_notebooks(folder)) == 2


def test_paper_and_figure():
    assert paper_and_figure("alvarez2015_fig01-03_gallery") == ("alvarez2015", "fig01-03")
    assert paper_and_figure("hurtut2009_ripley_L") == ("hurtut2009", "")
    assert paper_and_figure("datasets_overview") == ("", "")


def test_bad_jobs_rejected_by_argparse(project):
    with pytest.raises(SystemExit):
        run_cli(project, "--jobs", "0")


def test_missed_paper_claim_is_listed_once_and_the_ledger_written(project, capsys):
    with (project / "tests" / "expected_stats.toml").open("a") as handle:
        handle.write(
            '\n[kim2009_fig01_demo.answer_paper]\nkind = "paper"\nmin = 50\nsource = "paper, section 3: at least 50"\n'
            'xfail = "measured 42 at seed 0; cause: the demo computes 6 * 7"\n'
        )
    write_notebook(project, "kim2009_fig01_demo", 'repro.record("answer", 42)\nrepro.record("answer_paper", 42)\n'
                   'import sys\nrepro.record("executable", sys.executable)\nrepro.record("quality_seen", quality)\n'
                   + RECORD_TRANSPORT)
    (project / "tests" / "claims").mkdir()
    (project / "tests" / "claims" / "kim2009.toml").write_text(
        'paper = "kim2009"\nfigures = 1\n\n[[claim]]\nwhere = "Fig. 1"\nclaim = "at least 50"\n'
        'statistics = ["kim2009_fig01_demo.answer_paper"]\nwhy = "the demo computes 6 * 7"\n'
    )
    assert run_cli(project) == 0  # an expected failure does not fail the run
    index = (project / "figures" / "INDEX.md").read_text()
    assert "| kim2009_fig01_demo | answer_paper | 42 | >= 50 | measured 42 at seed 0; cause: the demo" in index
    assert "[ledger_kim2009.md](ledger_kim2009.md) | 0 | 0 | 1 | 0 |" in index
    ledger = (project / "figures" / "ledger_kim2009.md").read_text()
    assert "| Fig. 1 | at least 50 | `kim2009_fig01_demo.answer_paper` (paper: 42, xfail) | not |" in ledger


def test_seed_study_prints_each_statistics_spread(project, capsys):
    write_notebook(project, "kim2009_fig01_demo", 'repro.record("answer", seed * 2)\nrepro.record("time_x", 1.0)')
    assert main(["seed-study", "--root", str(project), "--only", "demo", "--seeds", "3-5"]) == 0
    out = capsys.readouterr().out
    assert "answer" in out and "[6, 8, 10]" in out and "time_x" not in out
    assert not (project / "figures").exists()  # a seed study never writes the committed figures
    assert main(["seed-study", "--root", str(project), "--only", "demo", "--seeds", "3"]) == 2


def test_version(capsys):
    from importlib.metadata import version

    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    assert capsys.readouterr().out.strip() == f"paperlib {version('paperlib')}"


@pytest.mark.parametrize("command", [[], ["reproduce"], ["seed-study"]])
def test_help_is_plain_text_with_examples(command, capsys):
    with pytest.raises(SystemExit) as stop:
        main([*command, "--help"])
    assert stop.value.code == 0
    out = capsys.readouterr().out
    assert "``" not in out and ":func:" not in out  # no raw reStructuredText
    assert "examples:\n  python -m paperlib " in out
    assert "--root" in out


def test_outside_the_repository_the_error_hints_root(tmp_path, capsys, monkeypatch):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    assert main(["reproduce", "--quality", "ci"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and err[0].startswith("error: ")
    assert err[1].startswith("hint: ") and "is not the paperlib repository" in err[1] and "--root" in err[1]
    assert main(["seed-study", "--only", "x", "--root", str(elsewhere)]) == 2
    assert "--root" in capsys.readouterr().err


def test_a_subfolder_of_the_repository_hints_its_root(project, capsys):
    inside = project / "notebooks" / "sub"
    inside.mkdir()
    assert main(["reproduce", "--root", str(inside), "--quality", "ci"]) == 2
    assert f"--root {project.resolve()}" in capsys.readouterr().err


def test_success_logs_no_kernel_false_alarms(project, capfd):
    """The kernel's own log reaches the terminal (fd 2): on success it must not cry wolf (issue 22)."""
    assert run_cli(project) == 0
    err = capfd.readouterr().err
    assert "KeyboardInterrupt caught in kernel" not in err
    assert "without encryption" not in err and "WARNING" not in err
    spec = json.loads((project / "build" / "jupyter" / "kernels" / "python3" / "kernel.json").read_text())
    assert spec["argv"][1:3] == ["-m", "paperlib._kernel"]


def test_kernel_filter_drops_only_the_false_alarms():
    import logging

    from paperlib._kernel import FalseAlarmFilter

    def record(message):
        return logging.LogRecord("IPKernelApp", logging.ERROR, __file__, 1, message, None, None)

    quiet = FalseAlarmFilter()
    assert not quiet.filter(record("KeyboardInterrupt caught in kernel."))
    assert not quiet.filter(record("Kernel is running over TCP without encryption. All communication ..."))
    assert quiet.filter(record("Exception in message handler:"))


def test_one_notebook_shows_its_cells_several_show_notebooks(project, capfd):
    assert run_cli(project, "--progress") == 0
    err = capfd.readouterr().err
    assert "kim2009_fig01_demo" in err and "4/4 [" in err and "cell" in err  # its three cells + injected parameters
    write_notebook(project, "simhon2001_fig02_other", 'repro.record("answer", 1)')
    with (project / "tests" / "expected_stats.toml").open("a") as handle:
        handle.write('\n[simhon2001_fig02_other.answer]\nkind = "truth"\nvalue = 1\nsource = "ground truth"\n')
    assert run_cli(project, "--progress") == 0
    err = capfd.readouterr().err
    assert "notebooks" in err and "2/2 [" in err and "cell" not in err
    assert run_cli(project) == 0  # default: stderr is no terminal here, so no bar
    assert "%|" not in capfd.readouterr().err


@pytest.mark.dask
def test_reproduce_on_a_dask_cluster_publishes_like_a_local_run(project):
    """`reproduce(client=...)` (docs/scale_out.md, "Scale out with Dask"): workers sharing the folder run the notebooks."""
    from paperlib.reproduce import reproduce

    distributed = pytest.importorskip("distributed", reason="dask.distributed is not installed (pip install -e .[dask])")
    write_notebook(project, "simhon2001_fig02_other", 'repro.record("answer", 1)')
    with (project / "tests" / "expected_stats.toml").open("a") as handle:
        handle.write('\n[simhon2001_fig02_other.answer]\nkind = "truth"\nvalue = 1\nsource = "ground truth"\n')
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  memory_limit="1GiB") as cluster, distributed.Client(cluster) as client:
        runs, table = reproduce(project, quality="ci", client=client)
    assert [run.notebook for run in runs] == ["kim2009_fig01_demo", "simhon2001_fig02_other"]
    assert all(run.ok for run in runs) and table.ok.all() and len(table) == 5
    stats = repro.load_stats(project / "figures" / "kim2009_fig01_demo" / "stats.json")["statistics"]
    assert stats["answer"] == 42 and stats["quality_seen"] == "ci"
    assert (project / "figures" / "simhon2001_fig02_other" / "stats.json").exists()
