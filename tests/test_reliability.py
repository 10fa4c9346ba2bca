"""Issue 21: budgets, no hang, hardened formats, safe publishing, one rng check (the worst cases, each alone)."""

from __future__ import annotations

import gzip
import math
import os

import numpy as np
import pytest

from paperlib import repro
from paperlib._atomic import publish_folder, recover_folder
from paperlib._checks import as_generator, positive_number
from paperlib.acontrario import meaningful_intervals
from paperlib.geometry import read_svg
from paperlib.mlts import Script, render
from paperlib.reproduce import recover_figures
from paperlib.sketch import multiscale_angles, train
from paperlib.strokepattern import ring_neighbourhoods

SVG = '<svg xmlns="http://www.w3.org/2000/svg">{}</svg>'


def test_ring_growth_stops_when_the_neighbourhood_stops_growing():
    pointers, neighbours = ring_neighbourhoods(4, [[0, 1], [1, 2], [2, 3]], 10**9)
    assert pointers.tolist() == [0, 3, 6, 9, 12]


def test_ring_neighbourhoods_count_past_127_paths():
    star = [[0, leaf] for leaf in range(1, 201)]   # 2 rings from a leaf: every other leaf, through the centre
    pointers, _ = ring_neighbourhoods(201, star, 2)
    assert np.diff(pointers).min() == 200


def test_scales_are_bounded_by_the_signal_and_a_budget():
    theta = np.linspace(0, 6, 50)
    with pytest.raises(ValueError, match="at most the signal's length"):
        multiscale_angles(theta, 10**12, [1.0], closed=False)
    with pytest.raises(ValueError, match="max_values"):
        multiscale_angles(theta, 50, [1.0], closed=False, max_values=100)
    ring = np.column_stack([np.cos(np.linspace(0, 6, 40)), np.sin(np.linspace(0, 6, 40))])
    with pytest.raises(ValueError, match="scales must be at most samples_per_curve"):
        train([ring], scales=2**63)
    with pytest.raises(ValueError, match="max_values"):
        train([ring], samples_per_curve=10**9)


def test_svg_total_flattened_points_budget():
    arcs = '<path d="M 0 0 A 1000 1000 0 1 1 1 0" stroke="black" fill="none"/>' * 50
    text = SVG.format(f'<g transform="scale(2e7)">{arcs}</g>')
    with pytest.raises(ValueError, match="max_points"):
        read_svg(text, max_points=100_000)


def test_svgz_decompressed_size_budget(tmp_path):
    bomb = gzip.compress(b"<svg xmlns='http://www.w3.org/2000/svg'>" + b" " * (4 * 2**20) + b"</svg>")
    with pytest.raises(ValueError, match="max_bytes"):
        read_svg(bomb, max_bytes=2**20)
    (tmp_path / "a.svgz").write_bytes(gzip.compress(SVG.format('<path d="M0 0 L1 1" stroke="black"/>').encode()))
    assert len(read_svg(tmp_path / "a.svgz")) == 1


@pytest.mark.parametrize("text", [
    '<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY a "aaaa">]>' + SVG.format("&a;"),
    '<!DOCTYPE svg SYSTEM "file:///etc/passwd">' + SVG.format('<path d="M0 0 L1 1" stroke="black"/>'),
])
def test_svg_declarations_are_rejected(text):
    with pytest.raises(ValueError, match="ENTITY declarations"):
        read_svg(text)


def test_the_standard_svg_doctype_is_accepted():
    # Inkscape, Illustrator and matplotlib write it; it declares nothing and nothing fetches it.
    doctype = ('<?xml version="1.0"?><!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" '
               '"http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd">')
    assert len(read_svg(doctype + SVG.format('<path d="M0 0 L1 1" stroke="black"/>'))) == 1


@pytest.mark.parametrize("body", [
    '<path d="l Z" stroke="black"/>',
    '<path d="M0 0 A 1e308 1e308 0 1 1 1e308 1" stroke="black"/>',
    '<path d="M0 0 C 1e200 0 0 1e200 1 1" stroke="black"/>',
    "<g>" * 5000 + "</g>" * 5000,
])
def test_svg_arithmetic_and_svgelements_failures_are_value_errors(body):
    with pytest.raises(ValueError):
        read_svg(SVG.format(body), tolerance=1e-300)


def test_meaningful_intervals_bins_budget():
    with pytest.raises(ValueError, match="max_bins"):
        meaningful_intervals(np.ones(16000, int))
    assert meaningful_intervals(np.ones(40, int), max_bins=40) == []


def test_script_json_nesting_and_types():
    with pytest.raises(ValueError, match="nests too deeply"):
        Script.from_json("[" * 100_000 + "]" * 100_000)
    values = Script().to_dict()
    values["layers"][0]["texels"] = 665
    with pytest.raises(ValueError, match="script layer 0: texels"):
        Script.from_dict(values)


def test_render_budget_is_checked_before_sampling():
    with pytest.raises(ValueError, match="max_samples"):
        render(Script(16384, 16384), max_samples=2**20)


@pytest.mark.parametrize("bad", ["", "stats.json"])
def test_repro_start_rejects_an_empty_or_file_out_dir(bad, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "stats.json").write_text("{}")
    with pytest.raises(ValueError, match="out_dir"):
        repro.start(bad, seed=0, quality="ci")
    assert (tmp_path / "stats.json").read_text() == "{}"


def _folder(path, text):
    path.mkdir(parents=True)
    (path / "stats.json").write_text(text)
    return path


def test_publish_replaces_the_folder_and_recovers_an_interrupted_publish(tmp_path):
    figures = tmp_path / "figures"
    target = _folder(figures / "nb", "old")
    publish_folder(_folder(tmp_path / "staging" / "nb", "new"), target)
    assert (target / "stats.json").read_text() == "new" and not (figures / ".nb.old").exists()
    # a kill between the two renames: the old copy set aside, the target missing
    os.replace(target, figures / ".nb.old")
    assert recover_figures(figures) == ["nb"] and (target / "stats.json").read_text() == "new"
    # a kill after the second rename: both exist, the leftover is removed
    _folder(figures / ".nb.old", "older")
    assert recover_folder(target) is False and not (figures / ".nb.old").exists()


@pytest.mark.parametrize("bad", ["seed", 1.5, True, np.random.RandomState(0)])
def test_rng_kinds_are_checked_in_one_place(bad):
    with pytest.raises(TypeError, match="rng must be None, an int seed, a SeedSequence or a numpy.random.Generator"):
        as_generator(bad)


@pytest.mark.parametrize("bad", [True, np.bool_(True), "3", b"3"])
def test_bools_and_strings_are_not_positive_numbers(bad):
    """float() turns True into 1.0 and "3" into 3.0: a flag or a text passed for a size must be refused."""
    with pytest.raises(ValueError, match="radius must be a number"):
        positive_number(bad, "radius")
    assert positive_number(np.float32(2.5), "radius") == 2.5 and positive_number(3, "radius") == 3.0


def test_an_eighth_random_fuzz_run_gets_messages_naming_the_parameter(tmp_path):
    """'~user' of an unknown user raised pathlib's RuntimeError; a short theta and a wrong amacrine file were
    refused naming no parameter of the function called (``path`` of close_curve; the file itself)."""
    from paperlib.datasets import amacrine_exemplar
    from paperlib.sketch import coarse_ring
    from paperlib.widgets import mlts_explorer

    _raises(ValueError, r"^output_dir names the home of an unknown user", mlts_explorer, output_dir="~no_such_user_x",
            size=37)
    _raises(ValueError, r"^theta must hold at least 3 angles", coarse_ring, [0.1], 1.0, (0.0, 0.0))
    (tmp_path / "x.json").write_text("{}")
    _raises(ValueError, r"^path '.*x\.json' does not hold the amacrine pattern", amacrine_exemplar,
            path=tmp_path / "x.json")


def test_as_generator_is_default_rng_bit_for_bit():
    for seed in (None, 0, 12345, np.random.SeedSequence(7)):
        if seed is None:
            continue
        assert as_generator(seed).random() == np.random.default_rng(seed).random()
    generator = np.random.default_rng(3)
    assert as_generator(generator) is generator


# --------------------------------------------------------------------------- issue 21, second pass: the listed failures
# Each case: the exact exception type, and a message that names the parameter (and the budget keyword).


def _unit_pattern(n=10):
    from paperlib.pointprocess import PointPattern, Window

    return PointPattern(np.random.default_rng(0).random((n, 2)), Window.rectangle((0, 1), (0, 1)))


def _raises(exception, pattern, function, *args, **kwargs):
    with pytest.raises(exception, match=pattern) as info:
        function(*args, **kwargs)
    assert type(info.value) is exception
    return str(info.value)


def test_wrong_objects_get_a_type_error_naming_the_parameter(tmp_path):
    from paperlib.claims import claim_problems, ledger_table, write_ledger
    from paperlib.pointprocess import Window, fine_nd, intensity_map_values, interaction_counts, interaction_pairs
    from paperlib.repro import statistics_without_times
    from paperlib.reproduce import paper_and_figure, write_index
    from paperlib.stipple import paper_radius_quantiles
    from paperlib.strokepattern import continuation, plot_boxes, target_count

    window = Window.rectangle((0, 1), (0, 1))
    _raises(TypeError, r"^pattern must be a PointPattern, got NoneType None", fine_nd, None, 0.1, 0.05)
    _raises(TypeError, r"^model must be a MultiStraussHard, got str 'x'", interaction_pairs, "x", [[0, 0]], [0],
            [[0, 0]], [0])
    _raises(TypeError, r"^model must be a MultiStraussHard", interaction_counts, None, [[0, 0]], [0], [[0, 0]], [0])
    _raises(TypeError, r"^window must be a Window, got str", intensity_map_values, np.ones((2, 2)), "w", [[0, 0]])
    _raises(ValueError, r"^intensity_map must be a non-empty 2-D image .*got None", intensity_map_values, None,
            window, [[0, 0]])
    _raises(TypeError, r"^claims must be a Claims, got str", claim_problems, "claims", {})
    _raises(TypeError, r"^claims must be a Claims", ledger_table, None, None)
    _raises(TypeError, r"^table must be a DataFrame, got list", write_ledger, tmp_path / "l.md", "t", [])
    _raises(TypeError, r"^data must be a dict, got list", statistics_without_times, [])
    _raises(ValueError, r"^data must be a loaded stats.json with a 'statistics' table", statistics_without_times,
            {"x": 1})
    _raises(TypeError, r"^stem must be a str, got NoneType None", paper_and_figure, None)
    _raises(TypeError, r"^layout must be a Layout, got str", write_index, "figures", [], {})
    _raises(TypeError, r"^geometry must be a StippleGeometry, got float", paper_radius_quantiles, 1.0)
    _raises(TypeError, r"^boxes_a must be an OrientedBoxes, got list", continuation, [], [], 1.0)
    _raises(TypeError, r"^boxes must be an OrientedBoxes, got list", plot_boxes, [np.zeros((4, 2))])
    _raises(TypeError, r"^analysis must be a PatternAnalysis, got NoneType", target_count, None, [[0, 0], [1, 0]])


def test_result_dataclasses_type_check_their_arrays():
    from paperlib.arrangement import Categorization, Split

    _raises(TypeError, r"^members must be an? ndarray, got list", Split, "all", [0, 1], None, None, (), "too_few")
    _raises(TypeError, r"^labels must be an? ndarray, got NoneType", Categorization, None, (), np.zeros(0, int),
            None, None, (), {})


def test_folders_given_where_a_file_is_expected_are_value_errors(tmp_path):
    from paperlib.claims import load_claims
    from paperlib.repro import load_expected

    for load in (load_claims, load_expected):
        _raises(ValueError, r"^path must name a file, got the folder", load, tmp_path)
        _raises(ValueError, r"^path must name a file, got ''", load, "")
        _raises(TypeError, r"^path must be a file path \(str or pathlib.Path\), got int", load, 3)


def test_array_shapes_are_checked_at_the_boundary():
    from paperlib.arrangement import box_distance_matrix, recursive_feature_values, unwrapped_orientation
    from paperlib.strokepattern import measure_tables, plot_graph

    _raises(ValueError, r"^corners_a must be an array of shape \(n, 4, 2\), got shape \(24, 2\)",
            box_distance_matrix, np.zeros((24, 2)))
    _raises(ValueError, r"^corners_b must be an array of shape \(n, 4, 2\)", box_distance_matrix,
            np.zeros((2, 4, 2)), np.zeros((2, 4, 3)))
    assert box_distance_matrix(np.zeros((0, 4, 2))).shape == (0, 0)
    _raises(ValueError, r"^orientation must be 1-D", unwrapped_orientation, np.ones((3, 3)))
    _raises(TypeError, r"^features must be a DataFrame, got ndarray", recursive_feature_values, np.zeros(3))
    _raises(ValueError, r"^half_lengths must be an array of shape \(2, 2\), got shape \(2,\)", measure_tables,
            np.ones(2), np.zeros(2), np.zeros((2, 3)))
    _raises(ValueError, r"^edges name nodes outside \[0, 3\)", plot_graph, np.zeros((3, 2)), [[0, 24]])


def test_scalar_arguments_are_checked():
    from paperlib.arrangement import subset_size
    from paperlib.pointprocess import default_nd

    _raises(ValueError, r"^alpha must be in \[0.5, 1\]; got -inf", subset_size, 33, 2, -np.inf)
    _raises(ValueError, r"^n must be an integer >= 1, got 0", subset_size, 0, 1, 0.75)
    _raises(ValueError, r"^n_points must be an integer >= 0, got inf", default_nd, np.inf)
    assert subset_size(40, 1, 0.75) == 30


@pytest.mark.parametrize("bad, match", [
    ((np.zeros((4, 4)), np.zeros((3, 2, 2), np.int64), 0, 0, np.array([[0, 1]] * 3)), r"^texture must be a 2-D bool"),
    ((np.zeros((4, 4), bool), [[0]], 0, 0, np.array([[0, 1]])), r"^counts must be the int64 \(k, 2, 2\) array"),
    ((np.zeros((4, 4), bool), np.zeros((1, 2, 2), np.int64), 0, 9, np.array([[0, 1]])), r"^x = 9 is outside"),
    ((np.zeros((4, 4), bool), np.zeros((1, 2, 2), np.int64), 0, 0, np.array([0.0, 1.0])), r"^offsets must be"),
])
def test_numba_kernels_check_their_arguments_before_entering_numba(bad, match):
    from paperlib.stipple import ace_change_kernel, flip_update_kernel

    _raises(ValueError, match, flip_update_kernel, *bad)
    _raises(ValueError, match, ace_change_kernel, *bad, np.full((1, 2, 2), 0.25), np.ones(1))


def test_ace_change_kernel_checks_target_and_totals():
    from paperlib.stipple import ace_change_kernel

    texture, counts, offsets = np.zeros((4, 4), bool), np.zeros((1, 2, 2), np.int64), np.array([[0, 1]])
    _raises(ValueError, r"^target must be an array of shape \(1, 2, 2\)", ace_change_kernel, texture, counts, 0, 0,
            offsets, np.zeros((2, 2)), np.ones(1))
    _raises(ValueError, r"^totals must be positive", ace_change_kernel, texture, counts, 0, 0, offsets,
            np.full((1, 2, 2), 0.25), np.zeros(1))


@pytest.mark.parametrize("call, keyword", [
    (lambda: __import__("paperlib.pointprocess").pointprocess.quadscheme(_unit_pattern(), nd=10**9), "max_dummies"),
    (lambda: __import__("paperlib.pointprocess").pointprocess.quadscheme(_unit_pattern(), nd=64, max_dummies=64**2 - 1),
     "max_dummies"),
    (lambda: __import__("paperlib.pointprocess").pointprocess.rpoispp(2.4e16, _unit_pattern().window), "max_points"),
    (lambda: __import__("paperlib.pointprocess").pointprocess.rmh(
        __import__("paperlib.pointprocess").pointprocess.Poisson(10.0), _unit_pattern().window, 10**9), "max_steps"),
    (lambda: __import__("paperlib.geometry").geometry.resample_open_curve([[0, 0], [1, 1]], 2**63 - 1), "max_points"),
    (lambda: __import__("paperlib.geometry").geometry.resample_closed_curve([[0, 0], [1, 0], [0, 1]], 10**8),
     "max_points"),
    (lambda: __import__("paperlib.datasets").datasets.glyph_outlines(10**12), "max_points"),
    (lambda: __import__("paperlib.datasets").datasets.leaf_outlines(6256, n_points=5938), "max_points"),
    (lambda: __import__("paperlib.datasets").datasets.hand_drawn_curve(10**12), "max_points"),
    (lambda: __import__("paperlib.datasets").datasets.leaf_outlines(2908, n_points=855), "max_points"),
    (lambda: __import__("paperlib.datasets").datasets.andrews_like_tones(2024), "max_pixels"),
    (lambda: __import__("paperlib.datasets").datasets.alternating_color_exemplar(10**9), "max_elements"),
    (lambda: __import__("paperlib.datasets").datasets.bars_exemplar(height=2489), "max_elements"),
    (lambda: __import__("paperlib.datasets").datasets.two_hatchings_exemplar(width=1e308), "max_elements"),
    (lambda: __import__("paperlib.datasets").datasets.irregular_exemplar(10, width=1e9, height=1e9), "max_elements"),
    (lambda: __import__("paperlib.datasets").datasets.regularity_exemplar(0.5, T=10**9), "max_steps"),
    (lambda: __import__("paperlib.datasets").datasets.stipple_tone_sheet(2**63 - 1), "max_pixels"),
    (lambda: __import__("paperlib.datasets").datasets.stipple_tone_texture(0.5, 10**5), "max_pixels"),
    (lambda: __import__("paperlib.stipple").stipple.paper_offsets(10**9), "max_n"),
    (lambda: __import__("paperlib.strokepattern").strokepattern.ring_neighbourhoods(10**12, [[0, 1]], 2), "max_pairs"),
    # a random fuzz run: a 1e9 x 1e9 line tessellation without lines reached a 7.45 GiB allocation
    (lambda: __import__("paperlib.mlts").mlts.poisson_line_tessellation((10**9, 10**9), 0), "max_pixels"),
    (lambda: __import__("paperlib.mlts").mlts.voronoi_tessellation((10**5, 10**5), 3), "max_pixels"),
    (lambda: __import__("paperlib.mlts").mlts.dead_leaves((64, 64), n_leaves=3, r_min=1, r_max=4, max_pixels=4095),
     "max_pixels"),
    (lambda: __import__("paperlib.mlts").mlts.coverage([(0, 0), (1e9, 0), (0, 1e9)], (10**6, 10**6)), "max_samples"),
    (lambda: __import__("paperlib.geometry").geometry.lloyd_relaxation([(0.5, 0.5)], (0, 1, 0, 1), 10**9), "max_cells"),
    (lambda: __import__("paperlib.strokepattern").strokepattern.seeds_2d((0, 1, 0, 1), 4, iterations=10**9),
     "max_cells"),
    (lambda: __import__("paperlib.strokepattern").strokepattern.ring_neighbourhoods(
        5000, [[0, leaf] for leaf in range(1, 5000)], 2, max_pairs=10**6), "max_pairs"),
])
def test_size_budgets_raise_before_allocating_and_name_their_keyword(call, keyword):
    with pytest.raises(ValueError, match=rf"above the budget {keyword}=[\d,]+; pass a larger {keyword}="):
        call()


def test_budget_defaults_leave_the_paper_sizes_alone():
    from paperlib.datasets import bars_exemplar, leaf_outlines, stipple_tone_sheet
    from paperlib.pointprocess import fine_nd, quadscheme
    from paperlib.stipple import paper_offsets

    pattern = _unit_pattern()
    assert quadscheme(pattern, nd=fine_nd(pattern, np.array([[0.02]]), np.array([[0.01]]))).nd == 512
    assert len(leaf_outlines(14, rng=0)) == 14 and len(paper_offsets(256)) == 765
    assert stipple_tone_sheet(8, 64, rng=0, transition=8)[0].shape == (64, 512)
    assert len(bars_exemplar(rng=0).strokes) > 50


# --------------------------------------------------------------------------- checks moved to the boundary (the
# library's own message used to leave numpy, pathlib, scipy or ipywidgets)


def test_boundary_checks_replace_the_libraries_messages(tmp_path):
    from paperlib.acontrario import log_binomial_tail
    from paperlib.datasets import amacrine_exemplar, categorization_cases
    from paperlib.geometry import OrientedBox
    from paperlib.repro import load_stats
    from paperlib.reproduce import find_notebooks
    from paperlib.strokepattern import unskewed_delaunay_edges

    _raises(ValueError, r"^box center must be an array of shape \(2\), got shape \(0,\)", OrientedBox,
            np.zeros(0), np.eye(2), (2.0, 1.0), 0.0)
    _raises(TypeError, r"^notebooks_dir must be a str or PathLike, got NoneType", find_notebooks, None)
    _raises(TypeError, r"^path must be a file path", load_stats, [[]])
    _raises(ValueError, r"^path must name a file, got the folder", load_stats, tmp_path)
    _raises(TypeError, r"^rng must be None, an int seed", categorization_cases, rng=1.5)
    _raises(TypeError, r"^path must be a file path", amacrine_exemplar, path=np.zeros(3))
    _raises(ValueError, r"^n, k and p must broadcast to one shape", log_binomial_tail, 133, np.ones((2, 2, 2)),
            np.zeros(0))
    _raises(ValueError, r"^points contains NaN or infinite values", unskewed_delaunay_edges, np.full((4, 2), np.nan))


@pytest.mark.parametrize("keywords, match", [
    (dict(figsize=(0, 0)), r"^figsize must be a pair of positive finite numbers"),
    (dict(figsize="wide"), r"^figsize must be a pair of numbers"),
    (dict(dpi=4.5), r"^dpi must be an integer >= 10"),
    (dict(figsize=(1e4, 1e4)), r"makes a figure above 33,554,432 pixels"),
])
def test_explorer_figure_settings(keywords, match):
    from paperlib.widgets._base import figure_settings

    _raises(ValueError, match, figure_settings, **({"figsize": (11, 5), "dpi": 80} | keywords))
    assert figure_settings((11, 5), np.int64(80)) == ((11.0, 5.0), 80)


def test_explorer_classes_check_their_arguments_like_their_factories():
    # the classes are public: a wrong value used to reach ipywidgets (TraitError), not a ValueError
    from paperlib.widgets import ArrangementExplorer, StippleExplorer, StrokePatternExplorer

    _raises(ValueError, r"^exemplar must be one of", ArrangementExplorer, exemplar=None, exemplar_seed=0, seed=0,
            T=1000, window_scale=1.0, density="uniform", labels="categorize", interaction="centre", image="camera",
            figsize=(4, 3), dpi=40)
    _raises(ValueError, r"^source must be one of", StippleExplorer, source="out.svg", sheet_seed=0, n_tones=8,
            block=128, tone=0.5, N=32, T1=0.1, T2=0.2, iterations=1, tile=32, seed=0, image="camera", render_size=64,
            min_chunk=1, workers=1, figsize=(4, 3), dpi=40)
    _raises(TypeError, r"^contour must be True or False, got array", StrokePatternExplorer,
            exemplar="sketchy_hatching", exemplar_seed=0, contour=np.zeros((0, 2)), rings=2, amount=0.0, vary=False,
            choice="close", seed=0, figsize=(4, 3), dpi=40, canvas_size=(200, 100))


def test_registry_required_keywords_are_always_passed():
    import sys
    from pathlib import Path

    from hypothesis import HealthCheck, given, settings

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import fuzz_registry

    assert fuzz_registry.required_keywords("out_dir=any | seed=rng quality=str") == [("seed", "rng"),
                                                                                   ("quality", "str")]
    assert fuzz_registry.parse_entry("out_dir=any ; x=str | seed=rng") == ([("out_dir", "any")], [("x", "str")])

    # the strategy builds arrays and paths: on a loaded machine its generation trips the too_slow health check
    @settings(max_examples=20, database=None, deadline=None, suppress_health_check=[HealthCheck.too_slow])
    @given(fuzz_registry.case_strategy("paperlib.repro.start"))
    def check(case):
        args, kwargs = case
        assert len(args) == 1 and {"seed", "quality"} <= set(kwargs)

    check()


@pytest.mark.parametrize("name, args", [
    ("normalized_area", (None, 0.01)), ("normalized_count", (None,)), ("normalized_orientation", ([np.nan],)),
    ("normalized_elongation", ([np.nan, 2.0],)),
])
def test_feature_normalisations_reject_nan_instead_of_returning_it(name, args):
    from paperlib import arrangement

    _raises(ValueError, r"contains NaN", getattr(arrangement, name), *args)
    assert arrangement.normalized_elongation([np.inf, 1.5]).tolist() == [1.0, 0.5]  # infinite elongation: capped


def test_csr_L_sd_checks_its_counts():
    from paperlib.pointprocess import csr_L_sd

    _raises(ValueError, r"^n_b must be an integer >= 1, got 0", csr_L_sd, 1e-266, 1, 0, False)
    _raises(ValueError, r"^area must be a positive finite number", csr_L_sd, -1.0, 1, 1, False)
    _raises(TypeError, r"^same_type must be True or False", csr_L_sd, 1.0, 1, 1, [])
    assert csr_L_sd(2.0, 1, 1, True) == pytest.approx((1 / np.pi) ** 0.5)  # sqrt(|W| / (2 pi n^2))


def test_choices_given_an_array_are_refused_naming_the_parameter():
    """A random fuzz run passed empty arrays as choices: ``array in (...)`` raised NumPy's ambiguous-truth error."""
    from paperlib.datasets import two_category_exemplar
    from paperlib.mlts import ifs_fractal
    from paperlib.pointprocess import PointPattern, Window, pcf

    empty = np.array([])
    _raises(ValueError, r"^mode must be one of", ifs_fractal, (32, 32), mode=empty, n_points=100, rng=0)
    _raises(ValueError, r"^between must be one of", two_category_exemplar, between=empty, rng=0)
    pattern = PointPattern(np.random.default_rng(0).random((20, 2)), Window.rectangle())
    _raises(ValueError, r"^divisor must be one of", pcf, pattern, divisor=np.array(["r", "d"]))



def test_every_choice_is_checked_as_a_choice():
    """A 250-input fuzz run found more choices compared with ``in``: arrays raised NumPy's ambiguous-truth error."""
    from paperlib.arrangement import categorize, fit
    from paperlib.datasets import categorization_cases, drawn_glyph_exemplar
    from paperlib.pointprocess import Window
    from paperlib.stipple import extract_marks

    flags = np.zeros((5, 2), dtype=bool)
    exemplar = drawn_glyph_exemplar((("o", 0.05, 12),), rng=0)
    _raises(ValueError, r"^interaction must be one of", fit, exemplar.elements, exemplar.labels, Window.rectangle(),
            interaction=flags)
    for keyword in ("method", "histogram_range", "orientation", "topology"):
        _raises(ValueError, rf"^{keyword} must be one of", categorize, exemplar.elements, exemplar.window.area,
                **{keyword: flags})
    _raises(ValueError, r"^family must be one of", categorization_cases, flags)
    _raises(ValueError, r"^level must be one of", extract_marks, np.eye(8, dtype=bool), flags)


def test_segment_blocks_reads_integer_and_bool_grays_as_numbers():
    """Integers would wrap when subtracted (uint8) and NumPy does not subtract bools (found by fuzzing)."""
    from paperlib.stipple import segment_blocks

    eight_bit = np.array([[0, 255, 255], [0, 255, 255]], dtype=np.uint8)
    np.testing.assert_array_equal(segment_blocks(eight_bit, 10), segment_blocks(eight_bit.astype(float), 10))
    np.testing.assert_array_equal(segment_blocks(eight_bit > 0, 0.5), segment_blocks((eight_bit > 0) * 1.0, 0.5))


def test_resample_curve_names_its_own_parameter():
    from paperlib.sketch import resample_curve

    _raises(ValueError, r"^points: cannot resample a curve of zero length", resample_curve, np.zeros((6, 2)), 34,
            closed=True)



def test_defects_of_the_later_250_input_fuzz_runs():
    """texel_batch and synthesize_distribution allocated for any size; a huge mark radius overflowed ``**``; a
    string r was read by NumPy; a tiny glyph size collapsed the pen; a tiny r_min overflowed (runs 2-4)."""
    from paperlib.datasets import amacrine_exemplar, stipple_tone_sheet
    from paperlib.mlts import dead_leaves_coverage_std, texel_batch
    from paperlib.pointprocess import PointPattern, Window, fit_strauss_hardcore
    from paperlib.stipple import synthesize_distribution

    _raises(ValueError, r"max_count=10,000,000", texel_batch, "rectangle", 2**63 - 1)
    assert len(texel_batch("rectangle", 3, max_count=3)) == 3
    _raises(ValueError, r"^mark_radius must be between 1 pixel and half the block \(8 px\)", stipple_tone_sheet,
            2, 16, rng=0, transition=0, mark_radius=2.3e191)  # (a third run: 1e308 reached int(nan))
    _raises(ValueError, r"above the budget max_pixels=16,777,216", synthesize_distribution, np.eye(4, dtype=bool),
            size=10**9)
    _raises(ValueError, r"^size must keep the glyphs' coordinates finite and their area above 0", amacrine_exemplar,
            size=1e-308)
    # a fourth run: r_min**(1 - alpha) overflowed in the quadrature of the lens areas
    assert math.isfinite(dead_leaves_coverage_std(10**12, (64, 2), 1.65e-295, 1.0))
    assert math.isfinite(dead_leaves_coverage_std(200, (32, 32), 1e-300, 4.0, alpha=2.5))
    pattern = PointPattern(np.random.default_rng(0).random((30, 2)), Window.rectangle())
    _raises(ValueError, r"^r must be an array of numbers", fit_strauss_hardcore, pattern, r="0.1 or so")


def test_a_quadrature_grid_of_no_side_is_refused_naming_quadrature():
    from paperlib.pointprocess import PointPattern, Window, fit_strauss_hardcore

    pattern = PointPattern(np.random.default_rng(1).random((30, 2)), Window.rectangle())
    _raises(ValueError, r"^quadrature \(an nd", fit_strauss_hardcore, pattern, r=0.1, quadrature=0)
