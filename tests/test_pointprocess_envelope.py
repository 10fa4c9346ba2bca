"""envelope(): order statistics of simulated summary functions, reproducible on any back end."""

import numpy as np
import pytest

from paperlib.pointprocess import Lest, StraussHard, Window, envelope, rpoispp

UNIT = Window.rectangle()
R = np.linspace(0, 0.1, 11)
ISO = {"correction": "isotropic"}


@pytest.fixture(scope="module")
def observed():
    return rpoispp(100, UNIT, rng=0)


def test_pointwise_bounds_are_the_nrank_order_statistics(observed):
    result = envelope(observed, Lest, nsim=19, nrank=2, r=R, fun_kwargs=ISO, rng=1, workers=1)
    # recompute the simulations the way envelope seeds them: child i of the parent seed
    children = np.random.SeedSequence(1).spawn(19)
    sims = np.array([Lest(rpoispp(observed.counts / UNIT.area, UNIT, rng=np.random.default_rng(c)), r=R,
                          correction="isotropic")["iso"] for c in children])
    ordered = np.sort(sims, axis=0)
    np.testing.assert_array_equal(result.lo, ordered[1])
    np.testing.assert_array_equal(result.hi, ordered[-2])
    np.testing.assert_allclose(result["mean"], sims.mean(axis=0))
    np.testing.assert_array_equal(result.obs, Lest(observed, r=R, correction="isotropic")["iso"])
    assert result.attrs["alpha"] == pytest.approx(4 / 20) and list(result.columns) == ["r", "obs", "theo", "lo",
                                                                                        "hi", "mean"]


def test_global_envelope_is_symmetric_about_theo(observed):
    result = envelope(observed, Lest, nsim=19, kind="global", r=R, fun_kwargs=ISO, rng=2, workers=1)
    np.testing.assert_allclose(result.hi - result.theo, result.theo - result.lo)
    assert np.ptp(result.hi - result.theo) < 1e-12 and result.attrs["alpha"] == pytest.approx(1 / 20)


def test_same_seed_same_envelope_in_process_and_in_processes(observed):
    one = envelope(observed, Lest, nsim=6, r=R, fun_kwargs=ISO, rng=3, workers=1)
    two = envelope(observed, Lest, nsim=6, r=R, fun_kwargs=ISO, rng=3, workers=2)
    assert one.equals(two)
    assert not one.equals(envelope(observed, Lest, nsim=6, r=R, fun_kwargs=ISO, rng=4, workers=1))


def test_model_envelope_brackets_a_realisation_of_the_model():
    model = StraussHard(200.0, 0.2, r=0.07, hc=0.03, closed=False)
    from paperlib.pointprocess import rmh

    pattern = rmh(model, UNIT, T=50_000, rng=5)
    result = envelope(pattern, Lest, model=model, nsim=19, kind="global", fun_kwargs=ISO,
                      simulate_kwargs={"T": 50_000}, rng=6, workers=1)
    csr = envelope(pattern, Lest, nsim=19, kind="global", fun_kwargs=ISO, rng=6, workers=1)
    inside = (result.obs >= result.lo) & (result.obs <= result.hi)
    assert inside.all()  # a realisation of the model itself stays inside (alpha = 5%; fixed seeds)
    assert (result["mean"] < csr["mean"]).iloc[20:200].all()  # the model is regular: L below CSR's


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(nsim=0), "nsim"),
        (dict(nrank=0), "nrank"),
        (dict(nsim=3, nrank=2), "at least 4"),
        (dict(kind="sideways"), "kind"),
        (dict(column="nope"), "no column"),
        (dict(model=StraussHard(1.0, 0.5, 0.1, 0.0).__class__([1.0, 1.0])), "types"),
    ],
)
def test_bad_input(observed, kwargs, message):
    with pytest.raises(ValueError, match=message):
        envelope(observed, Lest, **{"r": R, "fun_kwargs": ISO, **kwargs})


def test_observed_must_be_a_pattern():
    with pytest.raises(ValueError, match="PointPattern"):
        envelope(np.zeros((3, 2)), Lest)
