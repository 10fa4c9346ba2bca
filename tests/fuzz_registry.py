"""Fuzz registry: a Hypothesis strategy for every public callable of paperlib (issue 21).

Every public callable (each name in the ``__all__`` of the subpackages in :data:`MODULES` that is a
function or a class) has an entry in :data:`REGISTRY`; ``tests/test_fuzz.py`` fails when one is
missing, so a new public function must come with its fuzz strategy. An entry is a line of
``parameter=kind`` pairs: the parameters before ``;`` are required and passed positionally in that
order, those after it are optional keywords, each drawn or left out; those after ``|`` are required
keyword-only parameters, always passed by keyword. Kinds name the strategies of
:data:`KINDS`: every kind mixes plausible values (small valid inputs of the right shape) with the
hostile values a careless or malicious caller passes (NaN, infinities, empty and ragged arrays,
wrong types, negative and huge counts, strings, legacy random states).

:data:`NOT_FUZZED` lists the callables deliberately not run, with why; :data:`KNOWN_FAILURES` the
callables whose fuzzing still finds bad outcomes that belong to code outside this change (the
pointprocess and arrangement subpackages), with the measured failure: they are run and reported
but do not fail the CI profile. Remove an entry once its callable passes.

Plausible values stay small (tens of points, 32 x 32 images) so that a case that is valid runs in
well under a second; the harness (``tests/fuzz_harness.py``) bounds each case in time and memory.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import strategies as st

#: The subpackages (and top-level modules) whose ``__all__`` are fuzzed.
MODULES = (
    "paperlib.geometry", "paperlib.pointprocess", "paperlib.acontrario", "paperlib.arrangement",
    "paperlib.strokepattern", "paperlib.stipple", "paperlib.mlts", "paperlib.sketch", "paperlib.datasets",
    "paperlib.widgets", "paperlib.repro", "paperlib.parallel", "paperlib.reproduce", "paperlib.claims",
    "paperlib.fidelity", "paperlib.apps",
)


class Factory:
    """A value built inside the worker process (objects that are awkward to pickle or costly to draw)."""

    def __init__(self, name: str, seed: int = 0):
        self.name, self.seed = name, seed

    def __repr__(self) -> str:
        return f"Factory({self.name!r}, {self.seed})"


# ---------------------------------------------------------------------------------------- hostile values

_NAN, _INF = float("nan"), float("inf")


def _hostile_arrays():
    return st.sampled_from([
        np.zeros((0,)), np.zeros((0, 2)), np.full((4, 2), _NAN), np.array([[0.0, 1.0], [_INF, 2.0], [3.0, 1.0]]),
        np.ones((3, 3)), np.ones((2, 2, 2)), np.array([1e308, -1e308, 1e308]), np.array(["a", "b"]),
        np.array([[1, 2], [3, 4]], dtype=np.int8), np.array([1 + 2j, 3j]), np.zeros((5, 2), dtype=bool),
        np.array([[0.0, 0.0]] * 6),
    ])


HOSTILE = st.one_of(
    st.sampled_from([None, "", "x", "seed", -1, 0, 1, 10**9, 2**63, -(2**63), _NAN, _INF, -_INF, 1e308, 1e-308,
                     True, False, b"\x00\xff", [], [[]], [[_NAN, 1.0]], {"a": 1}, (0,), (10**9, 10**9), object(),
                     np.random.RandomState(0), "http://127.0.0.1:9/x.png", "../../etc/passwd", "\x00"]),
    _hostile_arrays(),
    st.text(max_size=12),
)


def _or_hostile(plausible, weight: int = 3):
    """``plausible`` most of the time, a hostile value otherwise."""
    return st.one_of(*([plausible] * weight), HOSTILE)


# ---------------------------------------------------------------------------------------- plausible values

_finite = st.floats(-1e3, 1e3, allow_nan=False)
_any_float = st.floats(allow_nan=True, allow_infinity=True)


def _point_arrays(min_n: int = 0, max_n: int = 24):
    return st.builds(
        lambda n, seed, scale, special: _points(n, seed, scale, special),
        st.integers(min_n, max_n), st.integers(0, 2**16), st.sampled_from([1.0, 10.0, 1e-9, 1e12]),
        st.sampled_from([None, None, None, "nan", "inf", "duplicate", "line"]),
    )


def _points(n: int, seed: int, scale: float, special) -> np.ndarray:
    points = np.random.default_rng(seed).random((n, 2)) * scale
    if n and special == "nan":
        points[n // 2, 0] = _NAN
    elif n and special == "inf":
        points[0, 1] = _INF
    elif n > 1 and special == "duplicate":
        points[1] = points[0]
    elif special == "line":
        points[:, 1] = 0.0
    return points


def _ring(n: int, seed: int, radius: float) -> np.ndarray:
    angles = np.sort(np.random.default_rng(seed).uniform(0, 2 * math.pi, n))
    return radius * np.column_stack([np.cos(angles), np.sin(angles)])


_rings = st.builds(_ring, st.integers(0, 40), st.integers(0, 2**16), st.sampled_from([1.0, 50.0, 1e-12, 1e300]))
_vectors = st.one_of(
    st.lists(_any_float, max_size=20).map(np.array),
    st.lists(_finite, min_size=1, max_size=64).map(np.array),
)
_counts = st.one_of(
    st.lists(st.integers(0, 50), min_size=0, max_size=40).map(lambda v: np.array(v, dtype=np.int64)),
    st.lists(st.integers(-3, 10**12), min_size=1, max_size=8).map(np.array),
)
_images = st.builds(
    lambda h, w, channels, seed, kind: _image(h, w, channels, seed, kind),
    st.integers(0, 32), st.integers(0, 32), st.sampled_from([None, None, 3, 4, 1]), st.integers(0, 2**16),
    st.sampled_from(["float", "uint8", "bitonal", "nan", "constant"]),
)


def _image(h: int, w: int, channels, seed: int, kind: str) -> np.ndarray:
    shape = (h, w) if channels is None else (h, w, channels)
    rng = np.random.default_rng(seed)
    if kind == "uint8":
        return rng.integers(0, 256, shape, dtype=np.uint8)
    if kind == "bitonal":
        return (rng.random(shape) < 0.3).astype(np.float64)
    if kind == "constant":
        return np.full(shape, 0.5)
    image = rng.random(shape)
    if kind == "nan" and image.size:
        image.flat[0] = _NAN
    return image


_edges = st.lists(st.tuples(st.integers(-2, 30), st.integers(-2, 30)), max_size=30).map(
    lambda pairs: np.array(pairs, dtype=np.int64).reshape(-1, 2))
_counts_scalar = st.one_of(st.integers(0, 64), st.integers(65, 10**4), st.sampled_from([10**9, 10**12, 2**63 - 1]))
_strings = st.one_of(st.sampled_from(["chelsea", "coffee", "rectangle", "ellipse", "uniform", "paper", "ci",
                                      "sharp", "isotropic", "border", "none", "Ripley", "rowman", "futural",
                                      "a", "A", "france", "leaf", "K", "L", "max", "sample"]), st.text(max_size=10))
_svg_docs = st.one_of(st.sampled_from([
    '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 L10 10 L20 0" stroke="black" fill="none"/></svg>',
    '<svg xmlns="http://www.w3.org/2000/svg"><circle cx="5" cy="5" r="4" stroke="black"/></svg>',
    '<svg xmlns="http://www.w3.org/2000/svg"><path d="l Z" stroke="black"/></svg>',
    '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 A 1e308 1e308 0 1 1 1e308 1" stroke="black"/></svg>',
    '<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY a "aaaa">]><svg xmlns="http://www.w3.org/2000/svg">&a;</svg>',
    '<svg xmlns="http://www.w3.org/2000/svg"><g transform="scale(2e7)">'
    + '<path d="M 0 0 A 1000 1000 0 1 1 1 0" stroke="black" fill="none"/>' * 40 + "</g></svg>",
    '<svg xmlns="http://www.w3.org/2000/svg">' + "<g>" * 3000 + "</g>" * 3000 + "</svg>",
    "<svg", "<html/>", "not svg at all",
]), st.text(max_size=40).map(lambda t: f'<svg xmlns="http://www.w3.org/2000/svg"><path d="{t}" stroke="red"/></svg>'))
_element_lists = st.one_of(
    st.lists(st.lists(_point_arrays(1, 8), min_size=1, max_size=3), max_size=6),
    st.lists(_point_arrays(0, 8), max_size=6),
    st.lists(_rings, min_size=1, max_size=3),
)
_shapes = st.one_of(st.tuples(st.integers(-2, 40), st.integers(-2, 40)),
                    st.sampled_from([(10**6, 10**6), (2**31, 2), (0, 5), (4.5, 3), (1, 2, 3)]))
_paths = st.sampled_from(["out.svg", "out/figure.png", "figures/x", "", ".", "missing.json", "a/../../b.txt",
                          "stats.json"])
_rngs = st.one_of(st.none(), st.integers(0, 2**32), st.integers(-5, -1), st.sampled_from(["seed", 1.5, True]),
                  st.builds(np.random.default_rng, st.integers(0, 100)),
                  st.builds(np.random.SeedSequence, st.integers(0, 100)),
                  st.builds(np.random.RandomState, st.integers(0, 100)))

#: The strategy of each kind named in :data:`REGISTRY`.
KINDS = {
    "any": HOSTILE,
    "points": _or_hostile(_point_arrays()),
    "curves": _or_hostile(st.lists(_rings, min_size=1, max_size=3)),
    "counts": _or_hostile(_counts),
    "vector": _or_hostile(_vectors),
    "image": _or_hostile(_images),
    "edges": _or_hostile(_edges),
    "window": _or_hostile(st.one_of(st.builds(Factory, st.just("window"), st.integers(0, 3)),
                                    st.tuples(st.tuples(_any_float, _any_float), st.tuples(_any_float, _any_float)))),
    "pattern": _or_hostile(st.builds(Factory, st.just("pattern"), st.integers(0, 3))),
    "structure": _or_hostile(st.builds(Factory, st.just("structure"), st.integers(0, 3))),
    "layers": _or_hostile(st.builds(Factory, st.just("layers"), st.integers(0, 3))),
    "float": _or_hostile(st.one_of(st.floats(0.01, 100.0), _any_float)),
    "count": _or_hostile(_counts_scalar),
    "bool": _or_hostile(st.booleans(), 2),
    "str": _or_hostile(_strings),
    "app": _or_hostile(st.sampled_from(["hurtut2009", "barla2006", "kim2009", "alvarez2015", "simhon2001",
                                        "stipple", "sketch"])),
    "path": _or_hostile(_paths),
    "vectorish": _or_hostile(_vectors),
    "shape": _or_hostile(_shapes),
    "elements": _or_hostile(_element_lists),
    "svg": _or_hostile(_svg_docs),
    "rng": _rngs,
}


#: One entry per public callable: required parameters, then ``;`` and optional keywords (module docstring).
REGISTRY = {
    "paperlib.geometry.Element": "; strokes=elements name=str",
    "paperlib.geometry.OrientedBox": "center=any axes=any half_lengths=vector angle=float",
    "paperlib.geometry.OrientedBoxes": "centers=points axes=any half_lengths=vector angles=vector",
    "paperlib.geometry.StackedStrokes": "vertices=points stroke_offsets=any stroke_element=any stroke_width=any n_elements=count",
    "paperlib.geometry.Stroke": "points=points ; width=count color=str",
    "paperlib.geometry.as_elements": "elements=elements ; name=str",
    "paperlib.geometry.as_points": "points=points ; name=str min_points=count",
    "paperlib.geometry.directed_hausdorff": "a=points b=points",
    "paperlib.geometry.directed_hausdorff_boxes": "corners_a=points corners_b=points",
    "paperlib.geometry.drop_repeated_vertices": "ring=points",
    "paperlib.geometry.hausdorff": "a=points b=points",
    "paperlib.geometry.hausdorff_boxes": "corners_a=points corners_b=points",
    "paperlib.geometry.lloyd_relaxation": "points=points window=window ; iterations=count tol=float max_cells=count",
    "paperlib.geometry.oriented_bounding_box": "points_or_element=any ; weights=vector include_width=bool",
    "paperlib.geometry.oriented_bounding_boxes": "elements=elements ; include_width=bool",
    "paperlib.geometry.oriented_ccw": "ring=points",
    "paperlib.geometry.read_svg": "path_or_text=any ; tolerance=float y_up=bool max_points=count max_bytes=count",
    "paperlib.geometry.resample_closed_curve": "ring=points n_points=count",
    "paperlib.geometry.resample_open_curve": "points=points n_points=count",
    "paperlib.geometry.ring_centroid": "ring=points",
    "paperlib.geometry.signed_area": "ring=points",
    "paperlib.geometry.stack_strokes": "elements=elements",
    "paperlib.geometry.svg_string": "elements=elements ; width=count height=count y_up=bool",
    "paperlib.geometry.turning_angles": "points=points | closed=bool",
    "paperlib.geometry.write_svg": "elements=elements path=path",
    "paperlib.pointprocess.Kcross": "pattern=pattern i=count j=count ; r=float correction=str rmax=float",
    "paperlib.pointprocess.Kest": "pattern=pattern ; r=float correction=str rmax=float",
    "paperlib.pointprocess.Lcross": "pattern=pattern i=count j=count ; r=float correction=str rmax=float centered=bool",
    "paperlib.pointprocess.Lest": "pattern=pattern ; r=float correction=str rmax=float centered=bool",
    "paperlib.pointprocess.MultiStraussHard": "beta=float ; gamma=float r=float hc=float closed=bool",
    "paperlib.pointprocess.PPMFit": "model=any coefficients=any vcov=any vcov_hessian=any log_pl=any quadrature=count correction=str rbord=any n_fitted=any iterations=count ; gamma_max=float",
    "paperlib.pointprocess.PairDistance": "distance=any",
    "paperlib.pointprocess.PointPattern": "points=points window=window ; marks=counts",
    "paperlib.pointprocess.Poisson": "beta=float",
    "paperlib.pointprocess.QuadratureScheme": "points=points types=counts weights=vector n_data=any nd=count ntile=any window=window",
    "paperlib.pointprocess.RadiusSelection": "r=float table=any curves=elements",
    "paperlib.pointprocess.Strauss": "beta=float gamma=float r=float ; closed=bool",
    "paperlib.pointprocess.StraussHard": "beta=float gamma=float r=float hc=float ; closed=bool",
    "paperlib.pointprocess.StraussHardcoreFit": "fit=any hardcore=float distances=any L_curves=any",
    "paperlib.pointprocess.Window": "kind=str xrange=any yrange=any area=float ; polygon=points mask=image",
    "paperlib.pointprocess.GlobalTest": "test=str statistic=float p_value=float n_sim=count rinterval=any simulated=image column=str alternative=str reference=str leaveout=count",
    "paperlib.pointprocess.dclf_test": "observed=pattern ; fun=any nsim=count r=vector alternative=str leaveout=count rng=rng progress=bool",
    "paperlib.pointprocess.mad_test": "observed=pattern ; fun=any nsim=count r=vector alternative=str leaveout=count rng=rng progress=bool",
    "paperlib.pointprocess.csr_L_sd": "area=float n_a=any n_b=any same_type=any",
    "paperlib.pointprocess.default_nd": "n_points=count",
    "paperlib.pointprocess.envelope": "observed=any fun=any ; kind=str r=float rng=rng workers=count progress=bool savefuns=bool",
    "paperlib.pointprocess.fine_nd": "pattern=pattern r=float hc=float",
    "paperlib.pointprocess.fit_strauss_hardcore": "pattern=pattern ; hardcore=float r=float correction=str quadrature=count rmax=float rebound=float gamma_max=float",
    "paperlib.pointprocess.hardcore_distances": "pattern=pattern ; method=str",
    "paperlib.pointprocess.intensity_map_values": "intensity_map=any window=window points=points",
    "paperlib.pointprocess.interaction_counts": "model=any locations=points types=counts pattern_points=points pattern_marks=counts ; exclude=bool pair_distance=str",
    "paperlib.pointprocess.interaction_pairs": "model=any locations=points types=counts pattern_points=points pattern_marks=counts ; exclude=bool pair_distance=str",
    "paperlib.pointprocess.interaction_radii": "pattern=pattern hardcore=float ; correction=str rmax=float rebound=float",
    "paperlib.pointprocess.pcf": "pattern=pattern ; r=float correction=str rmax=float bw=float",
    "paperlib.pointprocess.ppm": "pattern=pattern r=float ; hc=float closed=bool correction=str quadrature=count pair_distance=str gamma_max=float",
    "paperlib.pointprocess.quadscheme": "pattern=pattern ; nd=count",
    "paperlib.pointprocess.rMatClust": "kappa=any scale=float mu=any window=window ; rng=rng",
    "paperlib.pointprocess.rmh": "model=any window=window ; T=count rng=rng progress=bool",
    "paperlib.pointprocess.rpoispp": "intensity=float window=window ; rng=rng",
    "paperlib.pointprocess.select_radius": "r=float L=any hardcore=float rebound_height=any",
    "paperlib.acontrario.HistogramModes": "counts=counts prior=counts epsilon=float modes=any outliers=any",
    "paperlib.acontrario.Interval": "start=any end=any log10_nfa=any",
    "paperlib.acontrario.gap_log10_nfa": "counts=counts ; prior=counts max_bins=count",
    "paperlib.acontrario.histogram_modes": "counts=counts ; epsilon=float prior=counts max_bins=count",
    "paperlib.acontrario.interval_labels": "values=counts bin_edges=any intervals=any",
    "paperlib.acontrario.interval_log10_nfa": "counts=counts ; prior=counts max_bins=count",
    "paperlib.acontrario.log_binomial_tail": "n=count k=count p=any",
    "paperlib.acontrario.maximal_meaningful_modes": "counts=counts ; epsilon=float prior=counts max_bins=count",
    "paperlib.acontrario.meaningful_gaps": "counts=counts ; epsilon=float prior=counts max_bins=count",
    "paperlib.acontrario.meaningful_intervals": "counts=counts ; epsilon=float prior=counts max_bins=count",
    "paperlib.acontrario.meaningful_modes": "counts=counts ; epsilon=float prior=counts max_bins=count",
    "paperlib.acontrario.outlier_intervals": "counts=counts modes=any",
    "paperlib.acontrario.unimodal_segments": "counts=counts ; epsilon=float",
    "paperlib.arrangement.Arrangement": "pattern=pattern elements=elements labels=counts window=window categories=any",
    "paperlib.arrangement.ArrangementModel": "model=any fit=any references=any categories=any window=window pattern=pattern ; interaction=str",
    "paperlib.arrangement.AreaCategory": "name=str kind=str members=any status=any",
    "paperlib.arrangement.Categorization": "labels=counts categories=any counts=counts features=any area_histogram=any area_categories=any parameters=any",
    "paperlib.arrangement.DistanceCutoffs": "score=float orthogonal=any",
    "paperlib.arrangement.ExactFitError": "",
    "paperlib.arrangement.FeatureHistogram": "values=counts edges=edges bins=any analysis=any groups=elements group_names=any",
    "paperlib.arrangement.RobustPCA": "center=any components=any eigenvalues=any scores=any score_distances=any orthogonal_distances=any cutoffs=any is_outlier=any subset_size=any ; method=str",
    "paperlib.arrangement.Split": "name=str members=counts feature=str histogram=any children=any status=str",
    "paperlib.arrangement.recursive_feature_values": "features=any",
    "paperlib.arrangement.adjusted_rand_index": "labels_a=any labels_b=any",
    "paperlib.arrangement.separability_ceiling": "features=any labels=counts ; bins=count neighbours=count",
    "paperlib.arrangement.box_distance_matrix": "corners_a=points ; corners_b=points",
    "paperlib.arrangement.categorize": "elements=elements reference_area=float ; method=str epsilon=float topology=str rng=rng",
    "paperlib.arrangement.crossing_points": "element=elements ; curvature_scale=float join_tolerance=float topology=str",
    "paperlib.arrangement.element_features": "elements=elements reference_area=float ; include_width=bool curvature_scale=float corner_angle=float join_tolerance=float topology=str",
    "paperlib.arrangement.element_positions": "elements=elements",
    "paperlib.arrangement.extremity_points": "element=elements ; curvature_scale=float corner_angle=float join_tolerance=float topology=str",
    "paperlib.arrangement.ink_centrelines": "element=elements ; pixels_per_pen=count spur_length=float crossings=points",
    "paperlib.arrangement.overdrawn_fraction": "element=elements",
    "paperlib.arrangement.minimum_box_areas": "elements=elements ; include_width=bool",
    "paperlib.arrangement.fit": "elements=elements labels=counts window=window ; interaction=str",
    "paperlib.arrangement.normalized_area": "area=float reference_area=float",
    "paperlib.arrangement.normalized_count": "count=count",
    "paperlib.arrangement.normalized_elongation": "elongation=any",
    "paperlib.arrangement.normalized_orientation": "angle=float",
    "paperlib.arrangement.render": "arrangement=any",
    "paperlib.arrangement.robust_pca": "X=any ; alpha=float rng=rng",
    "paperlib.arrangement.subset_size": "n=count k=count alpha=float",
    "paperlib.arrangement.synthesize": "model=any window=window ; density=image T=count rng=rng progress=bool",
    "paperlib.arrangement.unwrapped_orientation": "orientation=any",
    "paperlib.strokepattern.PatternAnalysis": "strokes=elements epsilon=float contour=points dimension=count element_of_stroke=counts elements=elements boxes=elements colors=vector frames=points arc=vector edges=edges shifts=any neighbourhood_area=any area=float",
    "paperlib.strokepattern.Seeds": "positions=points frames=points edges=edges arc=vector",
    "paperlib.strokepattern.Synthesis": "elements=elements positions=points frames=points edges=edges source=path order=counts matched=any n_candidates=any score=float seeded=any dimension=count rings=count target=any",
    "paperlib.strokepattern.Thresholds": "; shape=shape",
    "paperlib.strokepattern.analyze": "strokes=elements epsilon=float ; dimension=count contour=points path=path region=points",
    "paperlib.strokepattern.as_region": "region=points",
    "paperlib.strokepattern.chain_edges": "order=counts",
    "paperlib.strokepattern.cluster_strokes": "strokes=elements epsilon=float ; contour=points",
    "paperlib.strokepattern.continuation": "boxes_a=any boxes_b=any epsilon=float",
    "paperlib.strokepattern.exchange_parameters": "synthesis=any analysis=any amount=float ; rng=rng",
    "paperlib.strokepattern.fit_elements": "groups=elements ; contour=points",
    "paperlib.strokepattern.graph_edges": "edges=edges n=count ; name=str",
    "paperlib.strokepattern.growth_order": "positions=points edges=edges start=any",
    "paperlib.strokepattern.plot_boxes": "boxes=elements",
    "paperlib.strokepattern.plot_graph": "positions=points edges=edges",
    "paperlib.strokepattern.plot_strokes": "items=any ; colors=vector alpha=float",
    "paperlib.strokepattern.measure_tables": "half_lengths=vector angles=vector colors=vector",
    "paperlib.strokepattern.proximity": "corners_a=points corners_b=points",
    "paperlib.strokepattern.ring_neighbourhoods": "n=count edges=edges rings=count",
    "paperlib.strokepattern.rule_score": "means=any sigmas=any",
    "paperlib.strokepattern.seeds_1d": "path=path n=count ; iterations=count rng=rng max_seeds=count max_cells=count",
    "paperlib.strokepattern.seeds_2d": "region=points n=count ; iterations=count rng=rng max_seeds=count max_cells=count",
    "paperlib.strokepattern.shift_vectors": "positions=points edges=edges",
    "paperlib.strokepattern.synthesize": "analysis=any target=any ; rings=count n=count choice=str tolerance=float iterations=count rng=rng max_seeds=count",
    "paperlib.strokepattern.target_count": "analysis=any target=any",
    "paperlib.strokepattern.unskewed_delaunay_edges": "points=points",
    "paperlib.strokepattern.vary_positions": "synthesis=any analysis=any ; k=count",
    "paperlib.stipple.ace": "features_a=any features_b=any",
    "paperlib.stipple.ace_change_kernel": "texture=image counts=counts y=points x=points offsets=vector target=any totals=any",
    "paperlib.stipple.block_dispersion": "texture=image ; block=count",
    "paperlib.stipple.block_gray_levels": "image=image ; block_size=count",
    "paperlib.stipple.compare_spacing": "reference=points texture=image",
    "paperlib.stipple.check_bitonal": "image=image",
    "paperlib.stipple.ChunkRemoval": "image=image removed_ink=image removed_paper=image",
    "paperlib.stipple.classify_level": "texture=image ; merge_factor=float merged_share=float",
    "paperlib.stipple.cooccurrence_counts": "texture=image offsets=vector",
    "paperlib.stipple.distribution_image": "tone_index=counts distribution_textures=image ; rng=rng pure_levels=vector",
    "paperlib.stipple.DistributionResult": "distribution=image centres=points pixels=any level=float white_marks=any s_avg=float",
    "paperlib.stipple.extract_distribution": "texture=image ; level=float s_avg=float iterations=count tol=float merge_factor=float merged_share=float",
    "paperlib.stipple.extract_marks": "texture=image ; level=float merge_factor=float merged_share=float",
    "paperlib.stipple.extract_tone_map": "image=image ; block_size=count",
    "paperlib.stipple.flip_update": "texture=image counts=counts y=points x=points offsets=vector",
    "paperlib.stipple.flip_update_kernel": "texture=image counts=counts y=points x=points offsets=vector",
    "paperlib.stipple.glcm_features": "counts=counts",
    "paperlib.stipple.GLCMFeatures": "glcm=any contrast=any energy=any correlation=any",
    "paperlib.stipple.largest_rectangle": "mask=image",
    "paperlib.stipple.learn_stipple_library": "tone_textures=any ; size=count iterations=count levels=count workers=count rng=rng progress=bool",
    "paperlib.stipple.level_grays": "tone_grays=vector ; pure_levels=vector",
    "paperlib.stipple.offset_directions": "offsets=vector",
    "paperlib.stipple.paper_radius_quantiles": "geometry=any",
    "paperlib.stipple.Mark": "mask=image offset=any white=any",
    "paperlib.stipple.nearest_neighbour_distances": "texture=image",
    "paperlib.stipple.pair_correlation": "texture=image ; r=float bw=float",
    "paperlib.stipple.normalized_glcms": "counts=counts",
    "paperlib.stipple.pair_totals": "shape=shape offsets=vector",
    "paperlib.stipple.paper_offsets": "n=count",
    "paperlib.stipple.place_marks": "distribution=image tone_index=counts marks_per_tone=vector ; rng=rng pure_levels=vector",
    "paperlib.stipple.remove_small_chunks": "image=image min_size=any",
    "paperlib.stipple.render_stipples": "points=points shape=shape ; density=image",
    "paperlib.stipple.render_stippling": "image=image distribution_textures=image marks_per_tone=vector ; tone_grays=vector min_chunk=float pure_levels=vector rng=rng",
    "paperlib.stipple.render_tone": "distribution=image marks=counts ; rng=rng",
    "paperlib.stipple.segment_blocks": "block_gray=image t1=any",
    "paperlib.stipple.select_tones": "image=image tone_grays=vector ; rng=rng pure_levels=vector",
    "paperlib.stipple.SpacingComparison": "nn_ks=any pcf_rms=any r=float g_reference=any g_texture=any nn_reference=any nn_texture=any",
    "paperlib.stipple.stipple_density": "image=image",
    "paperlib.stipple.stipple_pattern": "texture=image",
    "paperlib.stipple.stipple_geometry": "example=any ; marks=counts",
    "paperlib.stipple.StippleGeometry": "s_avg=float o_min=any o_avg=any o_max=any ; count=count",
    "paperlib.stipple.StippleLibrary": "examples=any distributions=any syntheses=any marks=counts tone_grays=vector",
    "paperlib.stipple.StippleRendering": "image=image tone_index=counts distribution=image tone_grays=vector removed_ink=image removed_paper=image level_grays=any pure_levels=vector",
    "paperlib.stipple.SynthesisResult": "texture=image ace_history=any accepted_flips=any attempts=any fallback_passes=any converged=bool seconds=float counts=counts offsets=vector geometry=any ; spacing=float acceptance=float",
    "paperlib.stipple.synthesize_distribution": "example=any ; size=count iterations=count offsets=vector spacing=float acceptance=float rng=rng max_pixels=count",
    "paperlib.stipple.to_bitonal": "image=image",
    "paperlib.stipple.tone_gray_levels": "distribution_textures=image marks_per_tone=vector ; rng=rng",
    "paperlib.stipple.ToneMap": "gray_levels=any textures=any rectangles=any region_ids=any block_labels=any block_gray=image block_size=count",
    "paperlib.stipple.VoronoiStipples": "points=points displacements=any converged=bool",
    "paperlib.stipple.weighted_centroids": "points=points density=image",
    "paperlib.stipple.weighted_voronoi_stipples": "image=image n_points=count ; iterations=count tol=float rng=rng",
    "paperlib.mlts.Layer": "; max_trials=count",
    "paperlib.mlts.MLObject": "layer=any father=any kind=str center=any diameter=float angle=float reductions=any polygon=points",
    "paperlib.mlts.RenderSettings": "; palette=str seed=rng samples=count",
    "paperlib.mlts.Script": "; width=count height=count seed=rng layers=layers",
    "paperlib.mlts.Structure": "width=count height=count layers=layers objects=any tried=any placed=any",
    "paperlib.mlts.affine_object": "vertices=points center=any diameter=float aspect=any angle=float",
    "paperlib.mlts.affine_objects": "vertices_list=any centers=points diameters=any aspects=any angles=vector",
    "paperlib.mlts.barnsley_fern": "",
    "paperlib.mlts.box_counting_dimension": "points=points ; levels=count",
    "paperlib.mlts.coverage": "vertices=points shape=shape ; samples=count clip=bool max_samples=count",
    "paperlib.mlts.dead_leaves": "shape=shape ; n_leaves=count alpha=float palette=str rng=rng return_labels=bool return_geometry=bool max_pixels=count | r_min=float r_max=float",
    "paperlib.mlts.dead_leaves_coverage": "n=count mean_area=any area=float",
    "paperlib.mlts.dead_leaves_coverage_std": "n=count shape=shape r_min=float r_max=float ; alpha=float",
    "paperlib.mlts.dead_leaves_mean_area": "r_min=float r_max=float ; alpha=float",
    "paperlib.mlts.dead_leaves_window_area": "shape=shape r_max=float",
    "paperlib.mlts.ifs_chaos_game": "; n_points=count rng=rng max_points=count",
    "paperlib.mlts.ifs_fractal": "shape=shape ; n_points=count mode=str palette=str rng=rng return_labels=bool return_geometry=bool max_points=count max_pixels=count",
    "paperlib.mlts.load_palette": "source=path",
    "paperlib.mlts.object_diameter": "polygon=points",
    "paperlib.mlts.orientation_angle": "center=any point=any",
    "paperlib.mlts.paint": "canvas=image polygons=elements colors=vector ; alphas=vector lights=points light_height=float clip=bool samples=count",
    "paperlib.mlts.read_texture_svg": "path_or_text=svg",
    "paperlib.mlts.poisson_line_tessellation": "shape=shape intensity=float ; palette=str rng=rng return_labels=bool return_geometry=bool max_pixels=count",
    "paperlib.mlts.render": "script=any ; palette=str max_samples=count",
    "paperlib.mlts.render_polygons": "polygons=elements colors=vector shape=shape ; alphas=vector lights=points light_height=float clip=bool samples=count max_samples=count",
    "paperlib.mlts.render_structure": "structure=structure settings=any ; palette=str max_samples=count",
    "paperlib.mlts.rule_violations": "structure=structure",
    "paperlib.mlts.sample_script": "; rng=rng width=count height=count palette=str",
    "paperlib.mlts.sample_structure": "layers=layers width=count height=count ; seed=rng max_trials=count order=str",
    "paperlib.mlts.sierpinski_triangle": "",
    "paperlib.mlts.tessellation_cells": "structure=structure samples=count ; rng=rng max_samples=count",
    "paperlib.mlts.texture_svg": "structure=structure settings=any ; palette=str",
    "paperlib.mlts.texel": "kind=str ; rng=rng n_vertices=count",
    "paperlib.mlts.texel_batch": "kind=str count=count ; rng=rng n_vertices=count max_count=count",
    "paperlib.mlts.write_texture_svg": "structure=structure settings=any path=path ; palette=str",
    "paperlib.mlts.voronoi_tessellation": "shape=shape n_cells=count ; palette=str rng=rng return_labels=bool return_geometry=bool max_pixels=count",
    "paperlib.sketch.box_counting_dimension": "points=points ; max_samples=count | closed=bool",
    "paperlib.sketch.curve_hausdorff": "a=points b=points ; resolution=float max_samples=count | closed=bool",
    "paperlib.sketch.densify": "points=points ; max_samples=count | closed=bool spacing=float",
    "paperlib.sketch.turning_ks": "a=points b=points",
    "paperlib.sketch.turning_per_sample": "points=points | closed=bool",
    "paperlib.sketch.Elaboration": "points=points angles=vector sketch=points steering=any states=any closed=bool closing_gap=any restarts=any crossings=any untangled=any",
    "paperlib.sketch.SketchModel": "order=counts scales=count steering_scale=any weights=vector similarity_sigma=any filter=any causal=bool subsample=bool closed=bool samples_per_curve=any curve_samples=any curves=elements states=any angles=vector steering=vector curve=points sample=any position=any successor=any neighbours=any similarity=any transitions=str transition=any extent_ratio=any",
    "paperlib.sketch.check_curve": "points=points ; min_points=count name=str | closed=bool",
    "paperlib.sketch.close_angles": "theta=vector",
    "paperlib.sketch.close_curve": "path=path",
    "paperlib.sketch.coarse_ring": "theta=vector step=float start=any",
    "paperlib.sketch.coarsen": "curve=points model=any ; n_samples=count closed=bool",
    "paperlib.sketch.copied_runs": "model=any states=any",
    "paperlib.sketch.crossing_segments": "points=points | closed=bool",
    "paperlib.sketch.default_weights": "scales=count order=counts ; max_values=count",
    "paperlib.sketch.elaborate": "model=any sketch=points ; closed=bool n_samples=count sigma=float top=count mode=str window=window closure=str rng=rng",
    "paperlib.sketch.filter_weights": "; filter_width=count",
    "paperlib.sketch.gyration_radius": "points=points",
    "paperlib.sketch.integrate_angles": "theta=vector step=float",
    "paperlib.sketch.lowpass": "theta=vector weights=vector ; causal=bool | closed=bool",
    "paperlib.sketch.match_size": "points=points reference=points",
    "paperlib.sketch.multiscale_angles": "theta=vector scales=count weights=vector ; causal=bool max_values=count | closed=bool",
    "paperlib.sketch.resample_curve": "points=points n_points=count | closed=bool",
    "paperlib.sketch.resample_simple": "points=points n_points=count ; name=str | closed=bool",
    "paperlib.sketch.sketch_from_svg": "source=path ; tolerance=float",
    "paperlib.sketch.state_similarity": "a=points b=points weights=vector sigma=float",
    "paperlib.sketch.tangent_angles": "points=points | closed=bool",
    "paperlib.sketch.total_turning": "theta=vector",
    "paperlib.sketch.train": "curves=elements ; order=counts scales=count filter_width=count weights=vector transitions=str causal=bool subsample=bool samples_per_curve=any closed=bool close_steering=bool max_values=count",
    "paperlib.sketch.wrap_angle": "angle=float",
    "paperlib.datasets.Exemplar": "elements=elements labels=counts categories=any window=window pattern=pattern truth=any description=str",
    "paperlib.datasets.GlyphType": "char=str size=count count=count ; name=str",
    "paperlib.datasets.GshhsPolygon": "lonlat=any level=float area_km2=any index=any",
    "paperlib.datasets.amacrine_exemplar": "; chars=str size=count font=str path=path",
    "paperlib.datasets.big_small_exemplar": "; window=window chars=str sizes=vector beta=float T=count font=str rng=rng",
    "paperlib.datasets.categorization_cases": "; rng=rng",
    "paperlib.datasets.coastlines": "; n=count min_points=count resolution=float",
    "paperlib.datasets.country_english_names": "",
    "paperlib.datasets.country_names": "",
    "paperlib.datasets.country_outline": "code=any ; tolerance=float y_up=bool",
    "paperlib.datasets.drawn_glyph": "char=str size=count ; angle=float jitter=float tremor=float font=str rng=rng",
    "paperlib.datasets.drawn_glyph_exemplar": "types=counts ; window=window jitter=float tremor=float font=str rng=rng",
    "paperlib.datasets.drawn_hatching_exemplar": "; window=window n=count char=str length=float angle=float font=str rng=rng",
    "paperlib.datasets.glyph_outline": "name=str ; n_points=count",
    "paperlib.datasets.character_outline": "char=str",
    "paperlib.datasets.glyph_outlines": "; n_points=count",
    "paperlib.datasets.grayscale_image": "name=str",
    "paperlib.datasets.grayscale_names": "",
    "paperlib.datasets.hand_drawn_curve": "; n_points=count closed=bool size=count rng=rng tremor=float",
    "paperlib.datasets.hatching_exemplar": "; window=window char=str length=float angle=float angle_jitter=float beta=float gamma=float r=float hc=float T=count font=str rng=rng",
    "paperlib.datasets.gshhs_polygons": "; resolution=float level=float",
    "paperlib.datasets.gshhs_resolutions": "",
    "paperlib.datasets.hershey_fonts": "",
    "paperlib.datasets.hershey_glyph": "char=str ; font=str width=count color=str",
    "paperlib.datasets.hershey_glyphs": "text_or_chars=any ; font=str width=count color=str",
    "paperlib.datasets.lattice_exemplar": "; window=window char=str size=count spacing=float jitter=float angle_jitter=float font=str rng=rng",
    "paperlib.datasets.leaf_outline": "kind=str ; rng=rng n_points=count",
    "paperlib.datasets.leaf_outlines": "; n=count rng=rng n_points=count",
    "paperlib.datasets.near_identical_exemplar": "; window=window chars=str size=count beta=float gamma=float r=float hc=float T=count font=str rng=rng",
    "paperlib.datasets.outline_names": "",
    "paperlib.datasets.photograph": "name=str",
    "paperlib.datasets.photograph_names": "",
    "paperlib.datasets.regularity_exemplar": "; gamma=float window=window char=str size=count beta=float r=float hc=float T=count font=str rng=rng",
    "paperlib.datasets.andrews_like_tones": "; size=count rng=rng return_truth=bool",
    "paperlib.datasets.stipple_tone_sheet": "; n_tones=count block=count rng=rng mark_radius=float",
    "paperlib.datasets.stipple_tone_texture": "tone=image ; size=count rng=rng mark_radius=float return_truth=bool",
    "paperlib.datasets.two_category_exemplar": "; window=window chars=str sizes=vector beta=float gamma=float r=float hc=float T=count font=str rng=rng",
    "paperlib.datasets.StrokePatternExemplar": "strokes=elements element_of_stroke=counts dimension=count path=path region=points epsilon=float params=any description=str",
    "paperlib.datasets.alternating_color_exemplar": "; n_elements=count colors=vector rng=rng",
    "paperlib.datasets.bars_exemplar": "; structure=structure width=count height=count rng=rng",
    "paperlib.datasets.drops_exemplar": "; structure=structure width=count height=count rng=rng",
    "paperlib.datasets.flowers_exemplar": "; colors=vector structure=structure width=count height=count rng=rng",
    "paperlib.datasets.gradient_hatching_exemplar": "parameter=any ; n_elements=count spacing=float jitter=float rng=rng",
    "paperlib.datasets.irregular_exemplar": "; n_elements=count width=count height=count rng=rng",
    "paperlib.datasets.jittered_hatching_exemplar": "; n_elements=count spacing=float length=float rng=rng",
    "paperlib.datasets.sketchy_hatching_exemplar": "; n_elements=count spacing=float length=float rng=rng",
    "paperlib.datasets.two_hatchings_exemplar": "; width=count height=count rng=rng",
    "paperlib.datasets.wave_hatching_exemplar": "; n_elements=count jitter=float spacing=float rng=rng",
    "paperlib.widgets.ArrangementExplorer": "| exemplar=any exemplar_seed=rng seed=rng T=count window_scale=any density=image labels=counts interaction=str image=image figsize=shape dpi=float",
    "paperlib.widgets.Drawing": "name=str elements=elements frame=any window=window truth=any truth_categories=any description=str",
    "paperlib.widgets.arrangement_explorer": "; exemplar_seed=rng seed=rng T=count density=image labels=counts interaction=str image=image figsize=shape dpi=float svg=svg file_root=path",
    "paperlib.widgets.density_image": "kind=str window=window ; image=image resolution=float",
    "paperlib.widgets.scaled_window": "window=window scale=float",
    "paperlib.widgets.MLTSExplorer": "; output_dir=path | random_seed=any max_tried=any",
    "paperlib.widgets.mlts_explorer": "; size=count output_dir=path file_root=path",
    "paperlib.apps.resolve_method": "method=app",
    "paperlib.apps.default_file_root": "",
    "paperlib.apps.app_notebook": "method=app",
    "paperlib.apps.voila_command": "method=app ; port=count open_browser=bool",
    "paperlib.apps.voila_environment": "; file_root=path",
    "paperlib.apps.app": "method=app ; file_root=path",
    "paperlib.apps.serve": "method=app ; port=count file_root=path open_browser=bool",
    "paperlib.widgets.StippleExplorer": "| source=path sheet_seed=any n_tones=count block=count tone=image N=any T1=any T2=any iterations=count tile=any seed=rng image=image render_size=any min_chunk=float workers=count figsize=shape dpi=float",
    "paperlib.widgets.stipple_explorer": "; source=path n_tones=count block=count tone=image iterations=count seed=rng image=image min_chunk=float workers=count figsize=shape dpi=float",
    "paperlib.widgets.StrokePatternExplorer": "| exemplar=any exemplar_seed=rng contour=points rings=count amount=float vary=any choice=str seed=rng figsize=shape dpi=float canvas_size=shape",
    "paperlib.widgets.strokepattern_explorer": "; exemplar_seed=rng epsilon=float contour=points rings=count amount=float choice=str seed=rng figsize=shape dpi=float canvas_size=shape",
    "paperlib.widgets.SketchExplorer": "| training=any order=counts scales=count sigma=float top=count mode=str closure=str window=window seed=rng n_samples=count preset=any figsize=shape dpi=float canvas_size=shape",
    "paperlib.widgets.sketch_explorer": "; order=counts scales=count sigma=float top=count mode=str closure=str window=window seed=rng n_samples=count figsize=shape dpi=float canvas_size=shape",
    "paperlib.repro.atomic_path": "path=path",
    "paperlib.repro.check_stats": "; figures_dir=path",
    "paperlib.repro.current_out_dir": "",
    "paperlib.repro.load_expected": "path=path",
    "paperlib.repro.load_stats": "path=path",
    "paperlib.repro.record": "name=str value=any",
    "paperlib.repro.save_figure": "fig=any name=str ; svg=svg dpi=float",
    "paperlib.repro.start": "out_dir=any | seed=rng quality=str",
    "paperlib.repro.statistics_without_times": "data=any",
    "paperlib.parallel.run_many": "fn=any tasks=any ; rng=rng workers=count progress=bool",
    "paperlib.parallel.spawn_seeds": "rng=rng n=count",
    "paperlib.reproduce.NotebookRun": "notebook=str ok=any seconds=float",
    "paperlib.reproduce.find_notebooks": "notebooks_dir=any ; pattern=pattern",
    "paperlib.reproduce.kernel_manager_on_sockets_in": "folder=path",
    "paperlib.reproduce.paper_and_figure": "stem=any",
    "paperlib.reproduce.reproduce": "; root=path quality=str jobs=count seed=rng timeout=float progress=bool figures_dir=path build_dir=path",
    "paperlib.reproduce.run_notebook": "path=path layout=any ; quality=str seed=rng timeout=float progress=bool",
    "paperlib.reproduce.seed_study": "only=any seeds=any ; root=path quality=str jobs=count timeout=float build_dir=path",
    "paperlib.reproduce.write_index": "layout=any stems=any expected=any",
    "paperlib.claims.Claim": "where=any claim=any statistics=any",
    "paperlib.claims.Claims": "paper=any figures=any claims=any",
    "paperlib.claims.claim_problems": "claims=any expected=any",
    "paperlib.claims.ledger_table": "claims=any check=any",
    "paperlib.claims.load_claims": "path=path",
    "paperlib.claims.write_ledger": "path=path title=any table=any",
    "paperlib.fidelity.FidelityScore": "measure=str value=float control=float controls=vector control_kind=str better_than_control=bool ratio=float p_value=float",
    "paperlib.fidelity.glcm_correlation": "image=image ; distances=vector",
    "paperlib.fidelity.glcm_score": "exemplar=image synthesis=image ; distances=vector nsim=count rng=rng",
    "paperlib.fidelity.hausdorff_score": "guide=points synthesis=points ; nsim=count rng=rng | closed=bool",
    "paperlib.fidelity.l_score": "exemplar=pattern synthesis=pattern ; r=vector nsim=count rng=rng",
    "paperlib.fidelity.lcross_score": "exemplar=pattern synthesis=pattern i=count j=count ; r=vector nsim=count rng=rng",
    "paperlib.fidelity.mark_difference_score": "exemplar=pattern exemplar_marks=vector synthesis=pattern synthesis_marks=vector ; period=float nsim=count rng=rng",
    "paperlib.fidelity.nn_distance_score": "exemplar=pattern synthesis=pattern ; nsim=count rng=rng",
    "paperlib.fidelity.pcf_score": "exemplar=pattern synthesis=pattern ; r=vector nsim=count rng=rng",
    "paperlib.fidelity.turning_angles": "points=points | closed=bool",
    "paperlib.fidelity.turning_score": "exemplar_curves=curves synthesis=points guide=points | closed=bool",

}


#: Callables deliberately not fuzzed, and why.
NOT_FUZZED = {
    "paperlib.reproduce.reproduce": "runs every notebook through papermill (minutes per case); tests/test_reproduce_cli.py",
    "paperlib.reproduce.run_notebook": "executes a notebook through papermill; tests/test_reproduce_cli.py",
    "paperlib.reproduce.seed_study": "runs notebooks over many seeds; tests/test_reproduce_cli.py",
    "paperlib.parallel.run_many": "runs a caller's function in worker processes (the fuzz worker must not fork pools)",
    "paperlib.apps.app": "builds a whole explorer (up to 20 s with a cold numba cache); its parts are fuzzed: "
                         "resolve_method and the five explorer factories of paperlib.widgets",
    "paperlib.apps.serve": "starts a Voila server and blocks until interrupted; tests/test_apps.py checks its command "
                           "and environment, tests/test_apps_browser.py serves every app",
}

#: Callables in code outside this change (paperlib.pointprocess, paperlib.arrangement) whose fuzzing still
#: gives bad outcomes: name -> the failure measured by ``make fuzz`` (tests/fuzz_harness.py). They run in the
#: CI profile and are reported, but do not fail it. Remove an entry once the callable passes.
KNOWN_FAILURES: dict[str, str] = {
    # measured by `make fuzz` (33 derandomized inputs per callable, 6 GiB / 10 s per case)
}

#: Callables of this change's own modules whose fuzzing still gives bad outcomes: not fixed yet for lack of
#: time (issue 21 stays open for them), with the failure measured by ``make fuzz``. Like KNOWN_FAILURES they are
#: run and reported but do not fail the CI profile; the list is the to-do of the issue.
OPEN_FAILURES: dict[str, str] = {
}

#: Exceptions that are part of a callable's contract rather than bad input: calling it out of order.
EXPECTED_EXCEPTIONS = {
    "paperlib.repro.record": "RuntimeError: no run started",
    "paperlib.repro.save_figure": "RuntimeError: no run started",
    "paperlib.repro.current_out_dir": "RuntimeError: no run started",
}


def _pairs(text: str) -> list[tuple[str, str]]:
    return [tuple(item.split("=", 1)) for item in text.split()]


def parse_entry(spec: str) -> tuple[list[tuple[str, str]], list[tuple[str, str]]]:
    """``(required, optional)`` lists of ``(parameter, kind)`` from a registry line (without its ``|`` part)."""
    required, _, optional = spec.partition("|")[0].partition(";")
    return _pairs(required), _pairs(optional)


def required_keywords(spec: str) -> list[tuple[str, str]]:
    """``(parameter, kind)`` of the required keyword-only parameters: the pairs after ``|`` in a registry line.

    For callables whose parameters have no default and cannot be passed positionally (``def f(a, *, b)``):
    ``"a=any | b=rng"`` always passes ``b=`` by keyword.
    """
    return _pairs(spec.partition("|")[2])


def case_strategy(name: str):
    """The Hypothesis strategy of one call of ``name``: ``(args, kwargs)``."""
    required, optional = parse_entry(REGISTRY[name])
    args = st.tuples(*(KINDS[kind] for _, kind in required))
    always = {parameter: KINDS[kind] for parameter, kind in required_keywords(REGISTRY[name])}
    kwargs = st.fixed_dictionaries(always, optional={parameter: KINDS[kind] for parameter, kind in optional})
    return st.tuples(args, kwargs)


def public_callables() -> list[str]:
    """Every public callable of paperlib: ``module.name`` for each callable in the modules' ``__all__``."""
    import importlib

    names = []
    for module_name in MODULES:
        module = importlib.import_module(module_name)
        names += [f"{module_name}.{name}" for name in module.__all__ if callable(getattr(module, name))]
    return names
