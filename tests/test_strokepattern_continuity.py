"""Local continuity measures (paperlib.strokepattern.continuity) and the synthesis rules they judge."""

import numpy as np
import pytest
from scipy.stats import kstwo, spearmanr

from paperlib.datasets.strokepatterns import gradient_hatching_exemplar, jittered_hatching_exemplar, wave_hatching_exemplar
from paperlib.strokepattern import analyze, synthesize
from paperlib.strokepattern.continuity import (
    alternation_length,
    allowed_run,
    compare_continuity,
    element_parameters,
    ks_critical_value,
    longest_copy_run,
    neighbour_differences,
    shuffled,
)


def ramp(parameter="orientation", jitter=0.0, rng=0):
    exemplar = gradient_hatching_exemplar(parameter, jitter=jitter, rng=rng)
    return exemplar, analyze(exemplar.strokes, exemplar.epsilon, dimension=1, path=exemplar.path,
                             contour=parameter == "thickness")


def test_ks_critical_value_matches_the_asymptotic_distribution():
    # Smirnov: sqrt(n m / (n + m)) D is asymptotically Kolmogorov-distributed
    n, m = 400, 600
    effective = n * m / (n + m)
    assert ks_critical_value(n, m) == pytest.approx(kstwo.ppf(0.99, round(effective)) * 1.0, rel=0.02)
    assert ks_critical_value(29, 29) == pytest.approx(1.6276 * np.sqrt(2 / 29), rel=1e-3)
    with pytest.raises(ValueError, match="at least one"):
        ks_critical_value(0, 5)


def test_runs_and_alternations():
    assert longest_copy_run([3, 3, 3, 1, 1, 2]) == 3
    assert longest_copy_run([]) == 0
    assert alternation_length([1, 2, 3, 4]) == 0
    assert alternation_length([1, 2, 1]) == 3
    assert alternation_length([1, 2, 1, 2]) == 3
    assert alternation_length([7, 1, 9, 1, 4, 1]) == 5     # the 1, 17, 1, 22, 1 pattern
    assert alternation_length([1, 1, 1, 1]) == 0          # a copy run, not an alternation


def test_exemplar_against_itself_is_perfect_and_a_shuffle_fails():
    exemplar, analysis = ramp("orientation")
    itself = compare_continuity(analysis, analysis_as_synthesis(analysis))
    assert all(value == 0.0 for value in itself.ks.values())
    synthesis = synthesize(analysis, exemplar.path, rings=5, rng=1)
    control = compare_continuity(analysis, shuffled(synthesis, rng=2))
    assert control.ks["orientation"] > control.bound
    # a shuffle keeps the elements: same sources, permuted
    assert sorted(shuffled(synthesis, rng=2).source) == sorted(synthesis.source)


def analysis_as_synthesis(analysis):
    """The reference seen as a synthesis of itself (every element copies itself)."""
    from types import SimpleNamespace
    order = np.argsort(analysis.arc)
    return SimpleNamespace(elements=analysis.elements, frames=analysis.frames, edges=analysis.edges,
                           source=order)


def test_constant_parameters_are_not_compared_on_rounding_noise():
    exemplar = jittered_hatching_exemplar(rng=0)
    analysis = analyze(exemplar.strokes, exemplar.epsilon, dimension=1, path=exemplar.path)
    synthesis = synthesize(analysis, [(0.0, 0.0), (40.0, 0.0)], rings=2, rng=0)
    result = compare_continuity(analysis, synthesis)
    assert result.ks["length"] == 0.0 and result.ks["thickness"] == 0.0


def test_allowed_run_counts_elements_the_rule_cannot_tell_apart():
    _, analysis = ramp("orientation")
    # 80 degrees over 29 steps, sigma_par = 9 degrees; the shape branch (0.1 L for equal strokes of length
    # 2.5: 2 asin(0.1) = 11.5 degrees) admits 11.5 / 2.76 -> 5 elements in a row
    assert allowed_run(analysis) == 5
    exemplar = jittered_hatching_exemplar(rng=0)
    uniform = analyze(exemplar.strokes, exemplar.epsilon, dimension=1, path=exemplar.path)
    assert allowed_run(uniform) == len(uniform)
    with pytest.raises(ValueError, match="1D"):
        from paperlib.datasets.strokepatterns import bars_exemplar
        bars = bars_exemplar(rng=0)
        allowed_run(analyze(bars.strokes, bars.epsilon, dimension=2, region=bars.region))


@pytest.mark.parametrize("parameter", ["orientation", "length", "thickness", "color"])
def test_five_ring_synthesis_keeps_a_hand_drawn_ramp(parameter):
    exemplar, analysis = ramp(parameter, jitter=1.0)
    values = {"color": lambda p: p["color"][:, 2]}.get(parameter, lambda p: p[parameter])
    for rng in range(3):
        synthesis = synthesize(analysis, exemplar.path, rings=5, rng=rng)
        measured = values(element_parameters(synthesis.elements, synthesis.frames, contour=analysis.contour))
        assert abs(spearmanr(np.arange(len(measured)), measured)[0]) > 0.97
        result = compare_continuity(analysis, synthesis)
        assert result.passes(parameter)
        assert result.copy_run <= result.allowed_run and result.alternation <= result.allowed_alternation
        assert not synthesis.fallback.any()
        # the seed patch: the centre's 5-ring copied from the reference's centre, the rest matched
        assert synthesis.seeded.sum() == 11 and synthesis.matched[~synthesis.seeded].all()


def test_paper_rules_as_written_lose_the_ramp():
    exemplar, analysis = ramp("length", jitter=1.0)
    corr = []
    for rng in range(6):
        synthesis = synthesize(analysis, exemplar.path, rings=5, rng=rng, choice="random", matching="paper",
                               start="random")
        lengths = element_parameters(synthesis.elements, synthesis.frames)["length"]
        corr.append(abs(spearmanr(np.arange(len(lengths)), lengths)[0]))
    assert np.mean(corr) < 0.8


def test_wave_along_a_longer_path_stays_continuous():
    exemplar = wave_hatching_exemplar(rng=0)
    analysis = analyze(exemplar.strokes, exemplar.epsilon, dimension=1, path=exemplar.path)
    synthesis = synthesize(analysis, [(0.0, 0.0), (80.0, 0.0)], rings=5, rng=3)
    result = compare_continuity(analysis, synthesis)
    assert result.passes("orientation") and result.copy_run <= result.allowed_run
    assert result.alternation <= result.allowed_alternation


def test_first_element_copies_the_reference_centre_and_options_are_checked():
    exemplar, analysis = ramp("orientation")
    synthesis = synthesize(analysis, exemplar.path, rings=2, rng=0)
    assert synthesis.source[synthesis.order[0]] == int(np.argmin(np.abs(analysis.arc - analysis.arc.mean())))
    for name, value in (("choice", "any"), ("matching", "mutual"), ("start", "left")):
        with pytest.raises(ValueError, match=name):
            synthesize(analysis, exemplar.path, **{name: value})
    with pytest.raises(ValueError, match="tolerance"):
        synthesize(analysis, exemplar.path, tolerance=-0.1)


def test_neighbour_differences_fold_axes():
    parameters = {"orientation": np.array([0.05, np.pi - 0.05]), "length": np.array([1.0, 3.0]),
                  "thickness": np.array([0.1, 0.1]), "color": np.zeros((2, 3))}
    differences = neighbour_differences(parameters, [(0, 1)])
    assert differences["orientation"][0] == pytest.approx(0.1)
    assert differences["length"][0] == 2.0
    with pytest.raises(TypeError):
        element_parameters([], [])


def test_bad_inputs_name_the_parameter():
    with pytest.raises(ValueError, match="source"):
        longest_copy_run([[1, 2]])
    with pytest.raises(ValueError, match="source"):
        alternation_length([0.5, 1.5])
    with pytest.raises(ValueError, match="alpha"):
        ks_critical_value(5, 5, alpha=2.0)
    with pytest.raises(ValueError, match="parameters lacks"):
        neighbour_differences({"orientation": np.zeros(2)}, [(0, 1)])
    with pytest.raises(TypeError, match="PatternAnalysis"):
        compare_continuity("not an analysis", None)
