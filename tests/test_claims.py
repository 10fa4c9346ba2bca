"""Claims ledgers: every paper has one, complete against its figures and paper statistics."""

from pathlib import Path

import pandas as pd
import pytest

from paperlib import repro
from paperlib.claims import claim_problems, ledger_table, load_claims, write_ledger
from paperlib.reproduce import PAPERS

ROOT = Path(__file__).resolve().parents[1]
CLAIMS = ROOT / "tests" / "claims"


@pytest.mark.parametrize("paper", sorted(PAPERS))
def test_every_paper_has_a_complete_claims_file(paper):
    claims = load_claims(CLAIMS / f"{paper}.toml")
    expected = repro.load_expected(ROOT / "tests" / "expected_stats.toml")
    assert claim_problems(claims, expected) == []


def test_no_claims_file_for_an_unknown_paper():
    assert {path.stem for path in CLAIMS.glob("*.toml")} <= set(PAPERS)


# ----------------------------------------------------------------- the module on small inputs

CLAIMS_TEXT = """
paper = "demo2000"
figures = 2

[[claim]]
where = "Figs. 1-2"
claim = "the method works"
statistics = ["demo2000_fig01_x.a", "demo2000_fig01_x.b"]

[[claim]]
where = "section 3"
claim = "correlations greater than 0.99"
statistics = ["demo2000_fig01_x.c"]
why = "fewer offsets than the paper"

[[claim]]
where = "section 4"
claim = "it takes less than 5 s"
statistics = []
why = "speed is measured in benchmarks/"
"""

EXPECTED = {
    "demo2000_fig01_x": {
        "a": {"kind": "truth", "value": 1, "source": "ground truth"},
        "b": {"kind": "seed-study", "max": 1, "source": "seeds 0-4"},
        "c": {"kind": "paper", "min": 0.99, "source": "paper, section 3", "xfail": "measured 0.93; cause x"},
    }
}


def write_claims(tmp_path, text=CLAIMS_TEXT):
    path = tmp_path / "demo2000.toml"
    path.write_text(text)
    return path


def check_table(statuses):
    return pd.DataFrame(
        [dict(notebook="demo2000_fig01_x", statistic=name, kind="truth", value=1.0, status=status)
         for name, status in statuses.items()]
    )


def test_complete_claims_have_no_problems(tmp_path):
    assert claim_problems(load_claims(write_claims(tmp_path)), EXPECTED) == []


def test_problems_name_what_is_missing(tmp_path):
    text = CLAIMS_TEXT.replace('where = "Figs. 1-2"', 'where = "Fig. 1"').replace("why = \"fewer offsets than the paper\"\n", "")
    expected = {"demo2000_fig01_x": {**EXPECTED["demo2000_fig01_x"],
                                     "d": {"kind": "paper", "max": 1, "source": "paper, Fig. 2"}}}
    problems = claim_problems(load_claims(write_claims(tmp_path, text)), expected)
    assert any("no claim names Fig. 2" in problem for problem in problems)
    assert any("demo2000_fig01_x.d is in no claim" in problem for problem in problems)
    assert any("expected failure: say 'why'" in problem for problem in problems)


@pytest.mark.parametrize(
    "old, new, message",
    [
        ('paper = "demo2000"', 'paper = "other"', "file's stem"),
        ("figures = 2", "figures = 0", "figure count"),
        ('statistics = ["demo2000_fig01_x.c"]', 'statistics = ["c"]', "<notebook>.<statistic>"),
        ('why = "speed is measured in benchmarks/"', "", "say 'why'"),
        ('claim = "the method works"', 'claim = "the method works"\nverdict = "great"', "only lower"),
    ],
)
def test_malformed_claims_are_rejected(tmp_path, old, new, message):
    with pytest.raises(ValueError, match=message):
        load_claims(write_claims(tmp_path, CLAIMS_TEXT.replace(old, new)))


def test_verdicts_follow_the_statistics_and_can_only_be_lowered(tmp_path):
    claims = load_claims(write_claims(tmp_path))
    table = ledger_table(claims, check_table({"a": "pass", "b": "pass", "c": "xfail"}))
    assert list(table.verdict) == ["reproduced", "not", "not checked"]
    table = ledger_table(claims, check_table({"a": "pass", "b": "FAIL", "c": "pass"}))
    assert list(table.verdict) == ["partly", "reproduced", "not checked"]
    lowered = load_claims(write_claims(tmp_path, CLAIMS_TEXT.replace(
        'claim = "the method works"', 'claim = "the method works"\nverdict = "partly"\nwhy = "our data differ"')))
    assert ledger_table(lowered, check_table({"a": "pass", "b": "pass", "c": "pass"})).verdict.iloc[0] == "partly"


def test_ledger_is_written_as_markdown(tmp_path):
    claims = load_claims(write_claims(tmp_path))
    path = write_ledger(tmp_path / "ledger_demo2000.md", "Demo 2000",
                        ledger_table(claims, check_table({"a": "pass", "b": "pass", "c": "xfail"})))
    text = path.read_text()
    assert "# Claims ledger: Demo 2000" in text and "Verdicts: reproduced 1, partly 0, not 1, not checked 1" in text
    assert "`demo2000_fig01_x.c` (truth: 1, xfail)" in text
