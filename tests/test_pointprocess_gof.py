"""dclf_test and mad_test (global Monte Carlo tests) against spatstat's dclf.test and mad.test.

The spatstat answers come from tests/oracle/gof.json, written by tests/oracle/spatstat_gof.R:
the simulated patterns are in the fixture and were given to spatstat as ``simulate = <list>``,
so randomness is out of the comparison and statistics and p-values must agree.
"""

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from paperlib.pointprocess import (
    GlobalTest,
    Kcross,
    Kest,
    Lcross,
    Lest,
    PointPattern,
    StraussHard,
    Window,
    dclf_test,
    envelope,
    mad_test,
    pcf,
    rpoispp,
)

ORACLE = json.loads((Path(__file__).parent / "oracle" / "gof.json").read_text())
CASES = {case["name"]: case for case in ORACLE["cases"]}
FUNCTIONS = {"Lest": Lest, "Kest": Kest, "Lcross": Lcross, "pcf": pcf, "Kcross": Kcross}
COLUMNS = {"isotropic": "iso", "border": "border", "translate": "trans"}
TESTS = {"dclf": dclf_test, "mad": mad_test}
# relative; measured: 1.3e-13 (Lest), 6e-15 (Kest), 3e-14 (Lcross), 6e-14 (pcf)
TOLERANCE = {"Lest": 1e-11, "Kest": 1e-11, "Lcross": 1e-11, "pcf": 1e-11}
UNIT = Window.rectangle()


def pattern(data: dict, like: PointPattern | None = None) -> PointPattern:
    """A fixture pattern; without coordinates, ``like``'s points with these marks (rlabel)."""
    if "x" not in data:
        return PointPattern(like.points, like.window, [data["categories"].index(m) for m in data["marks"]],
                            data["categories"])
    window = Window.rectangle([float(v) for v in data["window"]["xrange"]],
                              [float(v) for v in data["window"]["yrange"]])
    points = np.column_stack([[float(v) for v in data["x"]], [float(v) for v in data["y"]]])
    if "marks" not in data:
        return PointPattern(points, window)
    return PointPattern(points, window, [data["categories"].index(m) for m in data["marks"]], data["categories"])


def case_inputs(name: str):
    case = CASES[name]
    observed = pattern(case["observed"])
    simulations = [pattern(data, observed) for data in ORACLE["simulations"][case["simulations"]]]
    fun_kwargs = dict(case["funargs"])
    column = COLUMNS[fun_kwargs["correction"]]
    return observed, simulations, FUNCTIONS[case["fun"]], fun_kwargs, column


def our_arguments(args: dict | None) -> dict:
    args = dict(args or {})
    if "use.theory" in args:
        args["use_theory"] = args.pop("use.theory")
    return args


VARIANTS = [(name, index) for name, case in CASES.items() for index in range(len(case["tests"]))]


@pytest.mark.filterwarnings("ignore:the observed summary function is not finite at r = 0")
@pytest.mark.parametrize("name, index", VARIANTS)
def test_statistic_and_p_value_are_spatstats(name, index):
    expected = CASES[name]["tests"][index]
    observed, simulations, fun, fun_kwargs, column = case_inputs(name)
    result = TESTS[expected["test"]](observed, fun, patterns=simulations, column=column, fun_kwargs=fun_kwargs,
                                     workers=1, **our_arguments(expected["args"]))
    tolerance = TOLERANCE[CASES[name]["fun"]]
    assert result.statistic == pytest.approx(expected["statistic"], rel=tolerance)
    np.testing.assert_allclose(result.simulated, expected["simulated"], rtol=tolerance)
    assert result.p_value == expected["p_value"]
    np.testing.assert_allclose(result.rinterval, expected["rinterval"], rtol=1e-15)
    assert result.leaveout == expected["leaveout"]
    assert (result.reference == "theoretical") == expected["use_theory"]
    assert result.n_sim == len(simulations) and result.test == expected["test"].upper()


def test_pcf_at_zero_moves_the_interval_with_a_warning():
    observed, simulations, fun, fun_kwargs, column = case_inputs("redwood_pcf")
    with pytest.warns(UserWarning, match="not finite at r = 0"):
        result = dclf_test(observed, fun, patterns=simulations, column=column, fun_kwargs=fun_kwargs, workers=1)
    assert result.rinterval[0] > 0


# ============================================================================ the p-value rule


def test_p_value_counts_simulations_at_least_as_extreme():
    observed, simulations, fun, fun_kwargs, column = case_inputs("binomial_csr")
    result = mad_test(observed, fun, patterns=simulations, column=column, fun_kwargs=fun_kwargs, workers=1)
    assert result.p_value == (1 + np.sum(result.simulated >= result.statistic)) / (len(simulations) + 1)
    assert 0 < result.p_value < 1


def test_ties_rules():
    observed = rpoispp(50, UNIT, rng=1)
    same = [observed] * 9  # every simulated T ties with the observed one
    r = np.linspace(0, 0.1, 11)
    kwargs = dict(patterns=same, r=r, fun_kwargs={"correction": "isotropic"}, column="iso", use_theory=True,
                  workers=1)
    assert dclf_test(observed, Lest, **kwargs).p_value == 1.0
    assert dclf_test(observed, Lest, ties="mean", **kwargs).p_value == pytest.approx((1 + 4.5) / 10)
    randomised = {dclf_test(observed, Lest, ties="randomise", rng=seed, **kwargs).p_value for seed in range(30)}
    assert randomised <= {k / 10 for k in range(2, 11)} and len(randomised) > 3


# ============================================================================ simulating the null model


def test_csr_by_default_with_the_theoretical_reference_and_envelope_seeds():
    observed = rpoispp(80, UNIT, rng=2)
    r = np.linspace(0, 0.12, 25)
    result = mad_test(observed, Lest, nsim=19, r=r, fun_kwargs={"correction": "isotropic"}, column="iso", rng=3,
                      workers=1)
    assert result.reference == "theoretical" and result.leaveout == 0
    # the same simulations as envelope's with the same seed: the global envelope's band is the
    # (nrank-th) largest simulated MAD, and the test rejects exactly when obs leaves it
    band = envelope(observed, Lest, nsim=19, kind="global", r=r, fun_kwargs={"correction": "isotropic"},
                    column="iso", rng=3, workers=1)
    assert (band.hi - band.theo).iloc[0] == pytest.approx(result.simulated.max(), rel=1e-15)
    assert result.statistic == pytest.approx(np.nanmax(np.abs(band.obs - band.theo)), rel=1e-15)


def test_a_model_null_hypothesis_rejects_csr_data():
    model = StraussHard(150.0, 0.1, r=0.08, hc=0.02, closed=False)
    observed = rpoispp(150, UNIT, rng=4)
    result = dclf_test(observed, Lest, model=model, nsim=19, fun_kwargs={"correction": "isotropic"}, column="iso",
                       simulate_kwargs={"T": 20_000}, rng=5, workers=1)
    assert result.reference == "sample mean" and result.p_value == pytest.approx(1 / 20)


def test_same_seed_same_test_in_one_process_or_two():
    observed = rpoispp(60, UNIT, rng=6)
    kwargs = dict(nsim=5, r=np.linspace(0, 0.1, 11), fun_kwargs={"correction": "isotropic"}, rng=7)
    one, two = dclf_test(observed, Lest, workers=1, **kwargs), dclf_test(observed, Lest, workers=2, **kwargs)
    assert one.statistic == two.statistic and np.array_equal(one.simulated, two.simulated)


@pytest.mark.parametrize("null", ["csr", "model", "patterns"])
def test_an_envelope_with_saved_curves_gives_the_tests_of_its_simulations(null):
    """spatstat's dclf.test(E) / mad.test(E) for E <- envelope(X, savefuns = TRUE): one set of simulations, both tests,
    equal bit for bit to the tests simulating the same curves themselves."""
    observed = rpoispp(70, UNIT, rng=8)
    simulations = dict(csr={}, model={"model": StraussHard(70.0, 0.3, r=0.06, hc=0.01, closed=False),
                                      "simulate_kwargs": {"T": 5_000}},
                       patterns={"patterns": [rpoispp(70, UNIT, rng=100 + k) for k in range(9)]})[null]
    curves = dict(r=np.linspace(0, 0.1, 21), fun_kwargs={"correction": "isotropic"}, column="iso", rng=9, workers=1,
                  **simulations)
    saved = envelope(observed, Lest, nsim=9, savefuns=True, **curves)
    assert saved.attrs["null"] == null and len(saved.attrs["simulated"]) == 9
    for test in (dclf_test, mad_test):
        direct, from_envelope = test(observed, Lest, nsim=9, **curves), test(saved)
        assert from_envelope.statistic == direct.statistic and from_envelope.p_value == direct.p_value
        assert np.array_equal(from_envelope.simulated, direct.simulated) and from_envelope.reference == direct.reference
    assert "simulated" not in envelope(observed, Lest, nsim=9, **curves).attrs
    assert len(pd.concat([saved, saved])) == 2 * len(saved)  # the saved curves do not break pandas' attrs


def test_an_envelope_must_have_saved_its_curves_and_comes_alone():
    observed = rpoispp(40, UNIT, rng=10)
    options = dict(r=np.linspace(0, 0.1, 11), nsim=5, rng=11, workers=1)
    with pytest.raises(ValueError, match="savefuns=True"):
        dclf_test(envelope(observed, Lest, **options))
    saved = envelope(observed, Lest, savefuns=True, **options)
    with pytest.raises(ValueError, match="fun, nsim must not be given"):
        mad_test(saved, Lest, nsim=5)
    with pytest.raises(TypeError, match="savefuns"):
        envelope(observed, Lest, savefuns="yes", **options)


def test_repr_names_the_test():
    observed, simulations, fun, fun_kwargs, column = case_inputs("binomial_csr")
    result = dclf_test(observed, fun, patterns=simulations, column=column, fun_kwargs=fun_kwargs, workers=1)
    assert isinstance(result, GlobalTest)
    text = repr(result)
    assert text.startswith("GlobalTest(DCLF, statistic=") and "p_value=" in text and "n_sim=39" in text


# ============================================================================ input validation


@pytest.mark.parametrize(
    "kwargs, error, message",
    [
        (dict(alternative="both"), ValueError, "alternative must be one of"),
        (dict(ties="first"), ValueError, "ties must be one of"),
        (dict(leaveout=3), ValueError, "leaveout must be 0, 1 or 2"),
        # a random fuzz run: an array met `in` and raised NumPy's ambiguous-truth error
        (dict(leaveout=np.array([[np.nan, 1.0]])), ValueError, "leaveout must be 0, 1 or 2"),
        (dict(leaveout=np.array([1])), ValueError, "leaveout must be 0, 1 or 2"),
        (dict(progress=np.zeros(2)), TypeError, "progress"),
        (dict(clamp="yes"), TypeError, "clamp"),
        (dict(use_theory=1), TypeError, "use_theory"),
        (dict(rinterval=(0.2, 0.1)), ValueError, "rinterval must satisfy"),
        (dict(rinterval=(0.5, 0.6)), ValueError, "beyond the largest r"),
        (dict(rinterval="all"), ValueError, "rinterval must be two numbers"),
        (dict(rinterval=(0.001, 0.002)), ValueError, "holds no r value"),
        (dict(nsim=0), ValueError, "nsim"),
        (dict(patterns=[], nsim=None), ValueError, "patterns is empty"),
        (dict(patterns=[np.zeros((3, 2))], nsim=None), TypeError, r"patterns\[0\]"),
        (dict(patterns=[rpoispp(20, UNIT, rng=0)], nsim=2), ValueError, "only 1 patterns"),
        (dict(patterns=[rpoispp(20, UNIT, rng=0)], model=StraussHard(1.0, 0.5, 0.1, 0.0), nsim=None), ValueError,
         "not both"),
    ],
)
def test_bad_input(kwargs, error, message):
    observed = rpoispp(50, UNIT, rng=8)
    arguments = {"nsim": 3, "r": np.linspace(0, 0.1, 11), "fun_kwargs": {"correction": "isotropic"}, "workers": 1,
                 **kwargs}
    with pytest.raises(error, match=message):
        dclf_test(observed, Lest, **arguments)


def test_rinterval_beyond_the_grid_is_trimmed_with_a_warning():
    observed = rpoispp(50, UNIT, rng=9)
    with pytest.warns(UserWarning, match="trimmed"):
        result = mad_test(observed, Lest, nsim=3, r=np.linspace(0, 0.1, 11), rinterval=(0.02, 0.5),
                          fun_kwargs={"correction": "isotropic"}, workers=1, rng=1)
    assert result.rinterval == (0.02, 0.1)
