"""Claims ledgers: every figure and quantitative sentence of a paper, and what checks it.

``tests/claims/<paper>.toml`` lists a paper's claims::

    paper = "kim2009"
    figures = 14            # the paper's figure count: every Fig. 1..14 must be named by a claim

    [[claim]]
    where = "Fig. 8"        # "Fig. 8", "Figs. 7-8", "section 3.3", "Table 1", "eq. (4)", "abstract"
    claim = "the paper's words, or a faithful paraphrase"
    statistics = ["kim2009_fig07-08_distributions_glcm.glcm_correlation_min"]
    verdict = "partly"      # optional: may only lower the verdict the statistics give
    why = "..."             # required without statistics, with a verdict, or when a statistic is an xfail

:func:`ledger_table` joins the claims with a statistics check
(:func:`paperlib.repro.check_stats`): a claim whose statistics all pass is
*reproduced*, one whose statistics all fail or are expected failures is *not*, a mix is
*partly*, and a claim without statistics is *not checked* (as is one whose statistics were all
skipped, an optional comparison whose package is not installed). :func:`write_ledger` writes
the table as ``figures/ledger_<paper>.md``.

Like :mod:`paperlib.repro`, this module knows no method: it only reads claims and
statistics.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from ._atomic import atomic_path
from ._checks import data_frame, file_path, instance_of
from .repro import read_toml

__all__ = ["Claim", "Claims", "VERDICTS", "claim_problems", "ledger_table", "load_claims", "write_ledger"]

#: Verdicts from best to worst.
VERDICTS = ("reproduced", "partly", "not", "not checked")
_LOWERING_VERDICTS = ("partly", "not")
_CLAIM_KEYS = {"where", "claim", "statistics", "verdict", "why"}
_FIGURE_REFERENCE = re.compile(r"\bFig(?:s?\.|ures?)\s*(\d+)(?:\s*(?:-|–|and|,)\s*(\d+))?", re.IGNORECASE)
_STATISTIC_REFERENCE = re.compile(r"^[A-Za-z0-9_\-]+\.[A-Za-z][A-Za-z0-9_.\-]*$")


@dataclass(frozen=True)
class Claim:
    """One figure or quantitative sentence of a paper and the statistics that check it.

    Parameters
    ----------
    where : str
        Where in the paper: ``"Fig. 8"``, ``"Figs. 7-8"``, ``"section 3.3"``, ``"eq. (4)"``, ...
    claim : str
        The paper's words, or a faithful paraphrase.
    statistics : tuple of str
        The recorded statistics that check it, each ``"<notebook>.<statistic>"``.
    verdict : {"", "partly", "not"}, default ""
        A verdict that lowers the one the statistics give; empty to keep it.
    why : str, default ""
        The reason, required without statistics, with a lowered verdict, or when a
        statistic is an expected failure.
    """

    where: str
    claim: str
    statistics: tuple[str, ...]
    verdict: str = ""
    why: str = ""


@dataclass(frozen=True)
class Claims:
    """A paper's claims file.

    Parameters
    ----------
    paper : str
        The paper's key, the stem of its claims file (``"kim2009"``).
    figures : int
        The paper's figure count (>= 1): every Fig. 1..figures must be named by a claim.
    claims : tuple of Claim
        The claims, in the file's order.
    """

    paper: str
    figures: int
    claims: tuple[Claim, ...]

    def figures_named(self) -> set[int]:
        """The figure numbers that some claim's ``where`` names (``Figs. 7-8`` names 7 and 8).

        Returns
        -------
        set of int
            The figure numbers named by the ``where`` of at least one claim.
        """
        named = set()
        for claim in self.claims:
            for first, last in _FIGURE_REFERENCE.findall(claim.where):
                named.update(range(int(first), int(last or first) + 1))
        return named


def load_claims(path) -> Claims:
    """Read and validate ``tests/claims/<paper>.toml``.

    Parameters
    ----------
    path : str or os.PathLike
        The claims file, ``tests/claims/<paper>.toml``; its ``paper`` key must equal its stem.

    Returns
    -------
    Claims
        The validated claims.

    Raises
    ------
    ValueError
        Naming the file and the claim, for a missing key, a wrong type, an unknown
        verdict, a malformed statistic reference or a lowered verdict without a reason.
    """
    path = file_path(path)
    data = read_toml(path, "claims")
    if data.get("paper") != path.stem:
        raise ValueError(f"{path}: 'paper' must be the file's stem {path.stem!r}, got {data.get('paper')!r}")
    figures = data.get("figures")
    if not isinstance(figures, int) or isinstance(figures, bool) or figures < 1:
        raise ValueError(f"{path}: 'figures' must be the paper's figure count (a positive integer), got {figures!r}")
    entries = data.get("claim")
    if not isinstance(entries, list) or not entries:
        raise ValueError(f"{path}: give the claims as a non-empty [[claim]] array")
    claims = tuple(_parse_claim(entry, f"{path}: claim {number}") for number, entry in enumerate(entries, 1))
    return Claims(paper=data["paper"], figures=figures, claims=claims)


def _parse_claim(entry, where: str) -> Claim:
    if not isinstance(entry, dict):
        raise ValueError(f"{where} must be a table")
    unknown = set(entry) - _CLAIM_KEYS
    if unknown:
        raise ValueError(f"{where}: unknown keys {sorted(unknown)}; allowed: {sorted(_CLAIM_KEYS)}")
    for key in ("where", "claim"):
        if not isinstance(entry.get(key), str) or not entry[key].strip():
            raise ValueError(f"{where}: {key!r} must be a non-empty string")
    statistics = entry.get("statistics", [])
    if not isinstance(statistics, list) or not all(isinstance(s, str) for s in statistics):
        raise ValueError(f"{where}: 'statistics' must be a list of '<notebook>.<statistic>' strings")
    for reference in statistics:
        if not _STATISTIC_REFERENCE.match(reference):
            raise ValueError(f"{where}: {reference!r} is not '<notebook>.<statistic>'")
    verdict, why = entry.get("verdict", ""), entry.get("why", "")
    if verdict and verdict not in _LOWERING_VERDICTS:
        raise ValueError(f"{where}: 'verdict' may only lower the computed one: {_LOWERING_VERDICTS}, got {verdict!r}")
    if not isinstance(why, str):
        raise ValueError(f"{where}: 'why' must be a string")
    if (verdict or not statistics) and not why.strip():
        raise ValueError(f"{where}: say 'why' when a claim has no statistic or its verdict is lowered")
    return Claim(entry["where"].strip(), entry["claim"].strip(), tuple(statistics), verdict, why.strip())


def claim_problems(claims: Claims, expected: dict) -> list[str]:
    """What a claims file misses against the expected statistics (empty when complete).

    Every referenced statistic must be expected; every ``kind = "paper"`` statistic of
    the paper's notebooks must be referenced; every figure must be named; a claim
    checked by an expected failure must say why.

    Parameters
    ----------
    claims : Claims
        A paper's claims (:func:`load_claims`).
    expected : dict
        The expected statistics, ``{notebook: {statistic: spec}}`` as read from
        ``tests/expected_stats.toml`` (:func:`paperlib.repro.load_expected`).

    Returns
    -------
    list of str
        One message per problem, naming the paper and the claim; empty when complete.
    """
    instance_of(claims, Claims, "claims")
    for notebook, statistics in instance_of(expected, dict, "expected").items():
        instance_of(statistics, dict, f"expected[{notebook!r}]")
    problems = []
    referenced = {reference for claim in claims.claims for reference in claim.statistics}
    for claim in claims.claims:
        for reference in claim.statistics:
            notebook, statistic = reference.split(".", 1)
            spec = expected.get(notebook, {}).get(statistic)
            if spec is None:
                problems.append(f"{claims.paper}: {claim.where}: {reference} is not in tests/expected_stats.toml")
            elif _has_xfail(spec) and not claim.why:
                problems.append(f"{claims.paper}: {claim.where}: {reference} is an expected failure: say 'why'")
    for notebook, statistics in expected.items():
        if not notebook.startswith(f"{claims.paper}_"):
            continue
        for statistic, spec in statistics.items():
            if spec.get("kind") == "paper" and f"{notebook}.{statistic}" not in referenced:
                problems.append(f"{claims.paper}: paper statistic {notebook}.{statistic} is in no claim")
    missing = sorted(set(range(1, claims.figures + 1)) - claims.figures_named())
    if missing:
        problems.append(f"{claims.paper}: no claim names Fig. {', '.join(map(str, missing))}")
    return problems


def _has_xfail(spec: dict) -> bool:
    return "xfail" in spec or any(isinstance(item, dict) and "xfail" in item for item in spec.values())


def ledger_table(claims: Claims, check: pd.DataFrame) -> pd.DataFrame:
    """One row per claim: where, claim, its statistics with kind, value and status, verdict, why.

    Parameters
    ----------
    claims : Claims
    check : pandas.DataFrame
        The table of :func:`paperlib.repro.check_stats` for the paper's notebooks.

    Returns
    -------
    pandas.DataFrame
        Columns ``where``, ``claim``, ``statistics`` (a list of ``(reference, kind, value,
        status)`` tuples, status ``"not run"`` for a statistic absent from ``check``),
        ``verdict`` (one of :data:`VERDICTS`, lowered by the claim's own verdict) and ``why``;
        one row per claim, in order.
    """
    instance_of(claims, Claims, "claims")
    data_frame(check, "check", ("notebook", "statistic", "kind", "value", "status"))
    by_reference = {f"{row.notebook}.{row.statistic}": row for row in check.itertuples()}
    rows = []
    for claim in claims.claims:
        found = [by_reference.get(reference) for reference in claim.statistics]
        statuses = [row.status if row is not None else "not run" for row in found]
        verdict = _verdict(statuses)
        if claim.verdict and VERDICTS.index(claim.verdict) > VERDICTS.index(verdict):
            verdict = claim.verdict
        rows.append(
            dict(
                where=claim.where,
                claim=claim.claim,
                statistics=[
                    (reference, row.kind if row is not None else "", row.value if row is not None else None, status)
                    for reference, row, status in zip(claim.statistics, found, statuses)
                ],
                verdict=verdict,
                why=claim.why,
            )
        )
    return pd.DataFrame(rows, columns=["where", "claim", "statistics", "verdict", "why"])


def _verdict(statuses: list[str]) -> str:
    statuses = [status for status in statuses if status != "skipped"]  # optional comparison not installed
    if not statuses:
        return "not checked"
    passed = sum(status == "pass" for status in statuses)
    if passed == len(statuses):
        return "reproduced"
    return "not" if passed == 0 else "partly"


def write_ledger(path, title: str, table: pd.DataFrame) -> Path:
    """Write a ledger table (:func:`ledger_table`) as Markdown at ``path``, atomically.

    Parameters
    ----------
    path : str or os.PathLike
        The Markdown file to write (``figures/ledger_<paper>.md``); replaced atomically.
    title : str
        Title of the ledger, after ``# Claims ledger:``.
    table : pandas.DataFrame
        A ledger table of :func:`ledger_table`.

    Returns
    -------
    pathlib.Path
        ``path``, as written.
    """
    path = file_path(path)
    instance_of(title, str, "title")
    data_frame(table, "table", ("where", "claim", "statistics", "verdict", "why"))
    counts = table.verdict.value_counts()
    lines = [
        f"# Claims ledger: {title}",
        "",
        "Written by `python -m paperlib reproduce` from `tests/claims/` and the recorded statistics; do not edit.",
        "Each figure and quantitative sentence of the paper, the statistics that check it (kind, our value,",
        "status) and the verdict: reproduced when every statistic passes, not when none does, partly between.",
        "",
        "Verdicts: " + ", ".join(f"{verdict} {int(counts.get(verdict, 0))}" for verdict in VERDICTS),
        "",
        "| where | claim | statistics (kind: value, status) | verdict | why |",
        "|---|---|---|---|---|",
    ]
    for row in table.itertuples():
        checks = "<br>".join(
            f"`{reference}` ({kind or '?'}: {_short(value)}, {status})" for reference, kind, value, status in row.statistics
        )
        lines.append(f"| {row.where} | {_cell(row.claim)} | {checks or '-'} | {row.verdict} | {_cell(row.why)} |")
    with atomic_path(path) as temporary:
        temporary.write_text("\n".join(lines) + "\n")
    return path


def _short(value) -> str:
    if isinstance(value, float):
        return f"{value:.4g}"
    text = "-" if value is None else str(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")
