"""paperlib.repro: recording statistics and figures, checking tolerances."""

import importlib.util
import json
import math
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pytest

from paperlib import repro


@pytest.fixture
def run_dir(tmp_path):
    out = repro.start(tmp_path / "figures" / "demo_nb", seed=3, quality="ci")
    yield out


def write_expected(path, text):
    path.write_text(text)
    return path


def test_start_writes_fresh_stats(run_dir):
    repro.record("a", 1)
    repro.start(run_dir, seed=4, quality="paper")
    data = repro.load_stats(run_dir / "stats.json")
    assert data == {"notebook": "demo_nb", "seed": 4, "quality": "paper", "statistics": {},
                    repro.OPTIONAL_PACKAGES_KEY: {name: importlib.util.find_spec(name) is not None
                                                  for name in repro.OPTIONAL_PACKAGES}}


def test_record_converts_numpy_and_keeps_order(run_dir):
    repro.record("count", np.int64(7))
    repro.record("mean", np.float32(0.5))
    repro.record("curve", np.array([1.0, 2.0]))
    repro.record("flag", np.bool_(True))
    repro.record("table", {"x": [1, 2], "y": "label"})
    stats = repro.load_stats(run_dir / "stats.json")["statistics"]
    assert list(stats) == ["count", "mean", "curve", "flag", "table"]
    assert stats["count"] == 7 and isinstance(stats["count"], int)
    assert stats["mean"] == 0.5 and stats["curve"] == [1.0, 2.0] and stats["flag"] is True


def test_record_same_name_replaces(run_dir):
    repro.record("a", 1)
    repro.record("a", 2)
    assert repro.load_stats(run_dir / "stats.json")["statistics"] == {"a": 2}


@pytest.mark.parametrize(
    "name, value, message",
    [
        ("nan", math.nan, "finite"),
        ("inf", np.inf, "finite"),
        ("obj", object(), "type object"),
        ("bad name", 1, "must start with a letter"),
        ("_x", 1, "must start with a letter"),
        ("big", list(range(20_000)), "at most"),
        ("keys", {1: 2}, "keys must be strings"),
    ],
)
def test_record_rejects_bad_statistics(run_dir, name, value, message):
    with pytest.raises(ValueError, match=message):
        repro.record(name, value)
    assert repro.load_stats(run_dir / "stats.json")["statistics"] == {}


def test_start_validates(tmp_path):
    with pytest.raises(ValueError, match="quality"):
        repro.start(tmp_path, seed=0, quality="draft")
    with pytest.raises(ValueError, match="seed"):
        repro.start(tmp_path, seed=1.5, quality="ci")


def test_save_figure_is_reproducible_and_leaves_no_temporaries(run_dir):
    fig, ax = plt.subplots()
    ax.plot([0, 1], [1, 0])
    first = [path.read_bytes() for path in repro.save_figure(fig, "line", svg=True)]
    second = [path.read_bytes() for path in repro.save_figure(fig, "line", svg=True)]
    plt.close(fig)
    assert first == second
    assert sorted(p.name for p in run_dir.iterdir()) == ["line.png", "line.svg", "stats.json"]


def test_atomic_path_keeps_old_file_on_error(tmp_path):
    target = tmp_path / "f.txt"
    target.write_text("old")
    with pytest.raises(RuntimeError):
        with repro.atomic_path(target) as temporary:
            temporary.write_text("half")
            raise RuntimeError("interrupted")
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["f.txt"]


EXPECTED = """
[count]
kind = "truth"
value = 7
source = "ground truth: the generator draws 7"

[mean]
kind = "paper"
value = 0.5
rtol = 0.1
source = "paper, section 2: a mean of 0.5"

[curve]
kind = "oracle"
value = [1.0, 2.0]
atol = 1e-9
source = "spatstat's Kest on the same points"

[ratio]
kind = "seed-study"
min = 0.9
max = 1.1
source = "ci seeds 0-9: 0.93-1.07"
paper = { min = 0.99 }

[label]
kind = "truth"
value = "ok"
source = "ground truth: the label the code was written to give"

[missed]
kind = "paper"
min = 0.99
source = "paper, Fig. 8: coefficients greater than 0.99"
xfail = "measured 0.93 at seeds 0-4; cause: fewer offsets"
"""


def expected_file(tmp_path, text=EXPECTED, notebook="demo_nb"):
    """Write ``text``, whose tables are one notebook's statistics, as an expected_stats.toml."""
    path = tmp_path / "expected_stats.toml"
    path.write_text(re.sub(r"^\[(\w+)", rf"[{notebook}.\1", text, flags=re.MULTILINE))
    return path


GOOD = [("count", 7), ("mean", 0.54), ("curve", [1.0, 2.0]), ("ratio", 0.95), ("label", "ok"), ("missed", 0.93)]


def test_check_stats_all_ok_with_an_expected_failure_and_a_wall_time(tmp_path, run_dir):
    for name, value in GOOD + [("time_total", 3.0)]:
        repro.record(name, value)
    table = repro.check_stats(run_dir.parent, expected_file(tmp_path))
    assert list(table.columns) == repro.CHECK_COLUMNS
    assert table.ok.all(), table[~table.ok]
    status = table.set_index("statistic").status.to_dict()
    assert status == {"count": "pass", "mean": "pass", "curve": "pass", "ratio": "pass", "label": "pass",
                      "missed": "xfail", "time_total": "shown"}
    assert table.set_index("statistic").kind["curve"] == "oracle"


def test_an_expected_failure_that_passes_fails_the_run(tmp_path, run_dir):
    for name, value in GOOD:
        repro.record(name, 0.995 if name == "missed" else value)
    table = repro.check_stats(run_dir.parent, expected_file(tmp_path)).set_index("statistic")
    assert table.status["missed"] == "XPASS" and not table.ok["missed"]
    assert "remove 'xfail'" in table.reason["missed"]


def test_check_stats_reports_each_problem(tmp_path, run_dir):
    repro.record("count", 8)  # off by one, exact expected
    repro.record("mean", "0.5")  # wrong type
    repro.record("curve", [1.0])  # wrong length
    repro.record("ratio", 1.2)  # above max
    repro.record("extra", 1)  # not expected
    repro.record("missed", 0.5)
    repro.record("time_total", 300.0)  # never a failure
    table = repro.check_stats(run_dir.parent, expected_file(tmp_path)).set_index("statistic")
    reasons = table.reason.to_dict()
    assert "differs" in reasons["count"]
    assert "expected a number" in reasons["mean"]
    assert "list of 2" in reasons["curve"]
    assert "above the maximum" in reasons["ratio"]
    assert reasons["label"] == "expected but not recorded"
    assert reasons["extra"] == "recorded but not in tests/expected_stats.toml"
    assert table.ok.to_dict() == {"count": False, "mean": False, "curve": False, "ratio": False, "label": False,
                                  "missed": True, "extra": False, "time_total": True}


def test_quality_override_applies(tmp_path):
    out = repro.start(tmp_path / "figs" / "demo_nb", seed=0, quality="paper")
    repro.record("ratio", 0.95)
    spec = '[ratio]\nkind = "seed-study"\nmin = 0.9\nmax = 1.1\nsource = "seeds 0-9"\npaper = { min = 0.99 }\n'
    table = repro.check_stats(out.parent, expected_file(tmp_path, spec))
    assert not table.ok.iloc[0] and "below the minimum 0.99" in table.reason.iloc[0]


def test_check_stats_missing_notebook_outputs(tmp_path):
    table = repro.check_stats(tmp_path, expected_file(tmp_path), notebooks=["demo_nb", "other"])
    assert "no stats.json" in table.reason.iloc[0]
    assert table.reason.iloc[1] == "notebook has no entry in tests/expected_stats.toml"


SOURCE = 'kind = "truth"\nsource = "ground truth: known"\n'


@pytest.mark.parametrize(
    "text, message",
    [
        ('[x]\nkind = "truth"\nvalue = 1\n', "source"),
        (f"[x]\n{SOURCE}", "give 'value'"),
        (f"[x]\nvalue = 1\nrtol = -1\n{SOURCE}", "non-negative"),
        (f"[x]\nvalue = 1\ntolerance = 1\n{SOURCE}", "unknown keys"),
        (f"[time_x]\nmax = 1\n{SOURCE}", "never asserted"),
        (f'[x]\nvalue = 1\n{SOURCE}ci = {{ source = "t" }}\n', "override"),
        ('[x]\nvalue = 1\nsource = "ground truth"\n', "'kind' must be one of"),
        ('[x]\nvalue = 1\nkind = "guess"\nsource = "ground truth"\n', "'kind' must be one of"),
        ('[x]\nvalue = 1\nkind = "paper"\nsource = "our run at seed 0"\n', "must name the paper and where"),
        ('[x]\nvalue = 1\nkind = "oracle"\nsource = "our own code"\n', "independent implementation"),
        ('[x]\nvalue = 1\nkind = "truth"\nsource = "measured at seed 0"\n', "known answer"),
        ('[x]\nmin = 1\nkind = "seed-study"\nsource = "a few runs"\n', "seeds the range"),
        ('[x]\nmax = 1\nkind = "budget"\nsource = "seemed enough"\n', "budget, cap"),
        ('[x]\nvalue = 0.3568\natol = 0.001\nkind = "seed-study"\nsource = "seeds 0-4"\n', "spread over seeds"),
        ('[x]\nmin = 1\nkind = "truth"\nsource = "ground truth"\nxfail = "measured 0.5 at seed 0, cause x"\n',
         "only a paper's claim"),
        ('[x]\nmin = 1\nkind = "paper"\nsource = "paper, Fig. 2"\nxfail = "we miss it"\n', "measured value"),
        ("[x\n", "invalid TOML"),
    ],
)
def test_load_expected_rejects_malformed_specs(tmp_path, text, message):
    with pytest.raises(ValueError, match=message):
        repro.load_expected(expected_file(tmp_path, text))


def test_load_expected_validates_only_the_selected_notebooks(tmp_path):
    path = expected_file(tmp_path)
    with path.open("a") as handle:
        handle.write(f"\n[other.y]\nvalue = 2\n{SOURCE}\n[broken.z]\nvalue = 1\nsource = \"no kind\"\n")
    assert set(repro.load_expected(path, notebooks=["demo_nb", "other", "absent"])) == {"demo_nb", "other"}
    with pytest.raises(ValueError, match="broken.z"):
        repro.load_expected(path)


def test_load_expected_missing_file(tmp_path):
    with pytest.raises(ValueError, match="not found"):
        repro.load_expected(tmp_path / "nope.toml")


def test_statistics_without_times():
    data = {"statistics": {"a": 1, "time_b": 2.0}}
    assert repro.statistics_without_times(data) == {"a": 1}


def test_record_without_start_is_an_error(monkeypatch):
    monkeypatch.setattr(repro, "_current_run", None)
    with pytest.raises(RuntimeError, match="start"):
        repro.record("a", 1)


def test_stats_file_is_plain_json(run_dir):
    repro.record("a", 1.25)
    assert json.loads((run_dir / "stats.json").read_text())["statistics"]["a"] == 1.25


def test_tables_compare_key_by_key_with_tolerance(tmp_path):
    out = repro.start(tmp_path / "figs" / "demo_nb", seed=0, quality="ci")
    spec = expected_file(tmp_path, f"[t]\nvalue = {{ a = 1.0, b = 2.0 }}\natol = 0.1\n{SOURCE}")
    repro.record("t", {"a": 1.05, "b": 2.0})
    assert repro.check_stats(out.parent, spec).ok.all()
    repro.record("t", {"a": 1.05, "b": 2.5})
    assert "key 'b'" in repro.check_stats(out.parent, spec).reason.iloc[0]
    repro.record("t", {"a": 1.0})
    assert "keys" in repro.check_stats(out.parent, spec).reason.iloc[0]


def test_outputs_are_world_readable(run_dir):
    repro.record("a", 1)
    assert (run_dir / "stats.json").stat().st_mode & 0o777 == 0o644


def test_requires_checks_an_optional_comparison_where_the_run_had_its_package(tmp_path):
    """An entry with ``requires = "<package>"`` is checked when the run that recorded it could import the package,
    whatever the machine that reads the run has (a rebuilt INDEX.md must not depend on the reader's packages)."""
    folder = tmp_path / "figures" / "nb"
    folder.mkdir(parents=True)
    expected = tmp_path / "expected.toml"
    expected.write_text(
        '[nb.a]\nkind = "truth"\nvalue = 1.0\nsource = "by construction"\n\n'
        '[nb.b]\nkind = "truth"\nvalue = 2.0\nrequires = "no_such_package_here"\nsource = "by construction"\n'
    )

    def status(statistics, packages=None):
        data = {"quality": "ci", "statistics": statistics}
        if packages is not None:
            data[repro.OPTIONAL_PACKAGES_KEY] = packages
        (folder / "stats.json").write_text(json.dumps(data))
        table = repro.check_stats(tmp_path / "figures", expected).set_index("statistic")
        assert table.loc["a", "status"] == "pass" and table.loc["b", "ok"] == (table.loc["b", "status"] in ("pass", "skipped"))
        return table.loc["b", "status"]

    without, with_it = {"no_such_package_here": False}, {"no_such_package_here": True}
    # a run without the package records what it could not do (kim2009_fig06's ps_available = false): skipped
    assert status({"a": 1.0, "b": 5.0}, without) == "skipped"
    assert status({"a": 1.0}, without) == "skipped"
    # a run with it is checked, here where the package is absent
    assert status({"a": 1.0, "b": 2.0}, with_it) == "pass"
    assert status({"a": 1.0, "b": 5.0}, with_it) == "FAIL"
    assert status({"a": 1.0}, with_it) == "FAIL"
    # a run from before the record: it had the package if it recorded the statistic
    assert status({"a": 1.0, "b": 2.0}) == "pass"
    assert status({"a": 1.0}) == "skipped"
    expected.write_text('[nb.a]\nkind = "truth"\nvalue = 1.0\nrequires = "not a package"\nsource = "by construction"\n')
    with pytest.raises(ValueError, match="requires"):
        repro.load_expected(expected)


def test_a_run_records_which_optional_packages_it_can_import(run_dir):
    data = json.loads((run_dir / "stats.json").read_text())
    assert set(data[repro.OPTIONAL_PACKAGES_KEY]) == set(repro.OPTIONAL_PACKAGES)
    assert all(isinstance(v, bool) for v in data[repro.OPTIONAL_PACKAGES_KEY].values())


def test_every_required_package_is_one_a_run_records():
    expected = repro.load_expected(Path(__file__).resolve().parents[1] / "tests" / "expected_stats.toml")
    required = {spec["requires"] for specs in expected.values() for spec in specs.values() if "requires" in spec}
    assert required and required <= set(repro.OPTIONAL_PACKAGES)


def test_statistics_without_an_entry_keep_their_recorded_order(tmp_path):
    """Rows of statistics not in the expected file follow the record, not a set's hash order (INDEX.md is stable)."""
    folder = tmp_path / "figures" / "nb"
    folder.mkdir(parents=True)
    names = [f"time_{k}" for k in "qwertyuiopasdfghjkl"]
    (folder / "stats.json").write_text(json.dumps({"quality": "ci", "statistics": {name: 1.0 for name in names}}))
    expected = tmp_path / "expected.toml"
    expected.write_text('[nb.other]\nkind = "truth"\nvalue = 1.0\nsource = "by construction"\n')
    table = repro.check_stats(tmp_path / "figures", expected)
    assert list(table.statistic[table.status == "shown"]) == names


# --------------------------------------------------------------------------- numba kernels used

_KERNELS_SCRIPT = """
import json, sys
import numpy as np
from paperlib import repro
import paperlib.sketch._kernels as kernels
from paperlib._kernels_used import kernels_used
before = kernels_used()
repro.start(sys.argv[1], seed=0, quality="ci")
kernels._wrap(1.0)
repro.record("a", 1)
after_record = json.load(open(sys.argv[1] + "/stats.json"))["numba_kernels"]
kernels.rank_by_similarity(np.zeros((3, 2)), np.ones(2), np.array([[0, 1, 2]] * 3), 1.0, 2)
print(json.dumps({"before": before, "after_record": after_record, "now": kernels_used()}))
"""


def test_a_run_records_the_numba_kernels_it_used_with_their_callees(tmp_path):
    import subprocess
    import sys

    folder = tmp_path / "nb"
    completed = subprocess.run([sys.executable, "-c", _KERNELS_SCRIPT, str(folder)], capture_output=True, text=True,
                               check=True, timeout=600)
    seen = json.loads(completed.stdout.strip().splitlines()[-1])
    assert seen["before"] == []  # importing compiles nothing
    assert seen["after_record"] == ["paperlib.sketch._kernels._wrap"]
    # rank_by_similarity calls _direction_difference: listed even when its code came from the cache
    assert seen["now"] == sorted(["paperlib.sketch._kernels._wrap", "paperlib.sketch._kernels.rank_by_similarity",
                                  "paperlib.sketch._kernels._direction_difference"])
