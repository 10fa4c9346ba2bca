"""paperlib.mlts layers, sampler, scripts and renderer: Alvarez 2015 sections 3-5."""

import json
from dataclasses import replace

import numpy as np
import pytest
import shapely
from shapely.geometry import Polygon

from paperlib.mlts.layers import Layer
from paperlib.mlts.render import load_palette, render, render_structure, tessellation_cells
from paperlib.mlts import sampler
from paperlib.mlts.sampler import MLObject, Structure, rule_violations, sample_structure
from paperlib.mlts.script import RenderSettings, Script, sample_script


def geometries(structure, layer):
    return [Polygon(item.polygon) for item in structure.layer_objects(layer)]


def intersecting_pairs(polygons):
    tree = shapely.STRtree(polygons)
    left, right = tree.query(polygons, predicate="intersects")
    return int(np.sum(left < right))


# ---------------------------------------------------------------------------- layers


@pytest.mark.parametrize(
    "arguments, message",
    [
        (dict(texels=()), "at least one texel"),
        (dict(texels=("hexagon",)), "unknown texel"),
        (dict(max_objects=0), "max_objects"),
        (dict(max_objects=2.5), "max_objects"),
        (dict(aspect_ratio=0.5), "aspect_ratio"),
        (dict(max_diameter=-3), "max_diameter"),
        (dict(max_diameter=float("nan")), "max_diameter"),
        (dict(max_trials=0), "max_trials"),
        (dict(size_reduction=1.0), "size_reduction"),
        (dict(max_reductions=-1), "max_reductions"),
        (dict(inclusion=1), "inclusion"),
        (dict(v0=(0, 0, 0)), "not a projective point"),
        (dict(v1=(1, 2)), "three finite numbers"),
        (dict(vanishing=-1), "vanishing"),
    ],
)
def test_layer_rejects_bad_parameters(arguments, message):
    with pytest.raises(ValueError, match=message):
        Layer(**arguments)


def test_layer_dict_round_trip_and_unknown_keys():
    layer = Layer(texels=("triangle", "ellipse"), max_objects=7, v0=(10, 20, 1), vanishing=0.5)
    assert Layer.from_dict(json.loads(json.dumps(layer.to_dict()))) == layer
    with pytest.raises(ValueError, match="unknown layer parameter"):
        Layer.from_dict({**layer.to_dict(), "colour": "red"})
    values = layer.to_dict()
    del values["max_trials"]
    with pytest.raises(ValueError, match="missing layer parameter"):
        Layer.from_dict(values)


# ---------------------------------------------------------------------------- structure


@pytest.fixture(scope="module")
def structure():
    layers = [
        Layer(texels=("rectangle", "ellipse"), max_objects=25, max_diameter=90, exclusion=True, max_trials=30),
        Layer(texels=("triangle",), max_objects=6, max_diameter=30, inclusion=True, exclusion=True),
        Layer(texels=("convex_polygon",), max_objects=4, max_diameter=10, inclusion=True),
    ]
    return sample_structure(layers, 320, 240, seed=4)


def test_first_layer_is_the_image_rectangle_and_fathers_are_in_the_previous_layer(structure):
    image = structure.objects[0]
    assert image.layer == 0 and image.father == -1
    assert Polygon(image.polygon).equals(shapely.box(0, 0, 320, 240))
    for item in structure.objects[1:]:
        assert structure.objects[item.father].layer == item.layer - 1


def test_exclusion_and_inclusion_rules_hold(structure):
    assert intersecting_pairs(geometries(structure, 1)) == 0
    assert intersecting_pairs(geometries(structure, 2)) == 0
    for item in structure.objects:
        if item.layer >= 2:
            father = Polygon(structure.objects[item.father].polygon)
            assert father.contains_properly(Polygon(item.polygon))
    # layer 3 has no exclusion rule: its objects do overlap (the test can see overlaps)
    assert intersecting_pairs(geometries(structure, 3)) > 0


def test_counts_and_reductions_are_reported(structure):
    np.testing.assert_array_equal(structure.tried, [1, 25, 6 * structure.placed[1], 4 * structure.placed[2]])
    assert np.all(structure.placed <= structure.tried)
    for layer in (1, 2, 3):
        assert len(structure.layer_objects(layer)) == structure.placed[layer]
    reductions = [item.reductions for item in structure.objects[1:]]
    assert max(reductions) > 0  # crowded layers needed smaller objects (Figs. 13, 14)
    for item in structure.objects[1:]:
        layer = structure.layers[item.layer - 1]
        assert item.diameter == pytest.approx(layer.max_diameter * layer.size_reduction**item.reductions)


def test_same_seed_same_structure_and_another_differs(structure):
    again = sample_structure(structure.layers, 320, 240, seed=4)
    assert len(again.objects) == len(structure.objects)
    for a, b in zip(again.objects, structure.objects):
        np.testing.assert_array_equal(a.polygon, b.polygon)
    other = sample_structure(structure.layers, 320, 240, seed=5)
    assert not np.array_equal(other.objects[1].polygon, structure.objects[1].polygon)


def test_orientation_toward_points_at_infinity_and_finite_vanishing_point():
    horizontal = [Layer(max_objects=30, max_diameter=20, aspect_ratio=4, v0=(1, 0, 0), v1=(-1, 0, 0))]
    angles = [item.angle for item in sample_structure(horizontal, 200, 200, seed=0).objects[1:]]
    np.testing.assert_allclose(np.abs(np.cos(angles)), 1.0, atol=1e-12)
    towards = [Layer(max_objects=200, max_diameter=20, v0=(100, 100, 1), v1=(200, 200, 2), vanishing=1.0)]
    objects = sample_structure(towards, 200, 200, seed=1).objects[1:]
    distances = np.array([np.hypot(item.center[0] - 100, item.center[1] - 100) for item in objects])
    diameters = np.array([item.diameter for item in objects])
    far = np.hypot(100, 100)
    np.testing.assert_allclose(diameters, 20 * distances / far)  # linear perspective toward (100, 100)


def test_impossible_rules_end_and_report_what_was_placed():
    crowded = [Layer(max_objects=50, max_diameter=150, exclusion=True, max_trials=3, max_reductions=0)]
    result = sample_structure(crowded, 100, 100, seed=0)
    assert result.tried[1] == 50 and 1 <= result.placed[1] < 50
    too_big = [Layer(max_objects=3, max_diameter=40), Layer(max_objects=5, max_diameter=500, inclusion=True,
                                                            max_trials=2, max_reductions=1)]
    result = sample_structure(too_big, 100, 100, seed=0)
    assert result.placed[2] == 0 and result.tried[2] == 15


@pytest.mark.parametrize("arguments, message", [
    (dict(layers=[Layer()], width=0, height=10), "width"),
    (dict(layers=[Layer()], width=10, height=2.5), "height"),
    (dict(layers=["layer"], width=10, height=10), "must be a paperlib.mlts.Layer"),
])
def test_sample_structure_bad_input(arguments, message):
    with pytest.raises(ValueError, match=message):
        sample_structure(**arguments)


# ---------------------------------------------------------------------------- scripts


def test_script_json_round_trip_and_file(tmp_path):
    script = sample_script(3, width=96, height=64)
    assert Script.from_json(script.to_json()) == script
    path = script.save(tmp_path / "texture.json")
    assert Script.load(path) == script
    assert not list(tmp_path.glob(".texture*"))  # no temporary file left behind


@pytest.mark.parametrize("edit, message", [
    (lambda d: d.update(colour=1), "unknown script key"),
    (lambda d: d.pop("seed"), "missing script key"),
    (lambda d: d["render"].update(glow=True), "unknown render key"),
    (lambda d: d["layers"][0].update(max_trials=-2), "max_trials"),
    (lambda d: d.update(layers=[]), "at least one layer"),
    (lambda d: d.update(width=-5), "width"),
    (lambda d: d.update(version=7), "version"),
    (lambda d: d["render"].update(transparency=1.5), "transparency"),
])
def test_script_rejects_unknown_missing_and_out_of_range_keys(edit, message):
    values = sample_script(1, width=64, height=64).to_dict()
    edit(values)
    with pytest.raises(ValueError, match=message):
        Script.from_dict(values)


def test_unreadable_script_and_palette_give_clear_errors(tmp_path):
    with pytest.raises(ValueError, match="cannot read script"):
        Script.load(tmp_path / "missing.json")
    (tmp_path / "bad.json").write_text("{not json")
    with pytest.raises(ValueError, match="not a JSON script"):
        Script.load(tmp_path / "bad.json")
    (tmp_path / "palette.png").write_text("not an image")
    with pytest.raises(ValueError, match="cannot read palette image"):
        load_palette(tmp_path / "palette.png")  # a local image is passed explicitly as a Path


@pytest.mark.parametrize("source", ["http://127.0.0.1:9/palette.png", "file:///etc/passwd", "/etc/passwd", "nope"])
def test_palette_strings_name_only_bundled_photographs(source):
    # issue 21: a string (as a shared JSON script holds) never fetches a URL nor reads a file
    with pytest.raises(ValueError, match="not a bundled photograph"):
        load_palette(source)
    with pytest.raises(ValueError, match="bundled photograph"):
        RenderSettings(palette=source)


def test_sample_script_draws_in_the_documented_ranges():
    for seed in range(20):
        script = sample_script(seed, width=200, height=100)
        assert 1 <= len(script.layers) <= 4
        fathers = 1
        for layer in script.layers:
            assert 1 <= layer.aspect_ratio <= 6 and 0.5 <= layer.size_reduction <= 0.95
            assert fathers * layer.max_objects <= 4000 or layer.max_objects == 1  # at most 4,000 tried per layer
            fathers *= layer.max_objects
        assert 0 <= script.render.transparency <= 0.8


# ---------------------------------------------------------------------------- rendering


def test_render_is_reproducible_and_seeds_are_independent():
    script = Script(96, 72, 5, (Layer(max_objects=12, max_diameter=40), Layer(max_objects=3, max_diameter=10)),
                    RenderSettings(palette="coffee", seed=1, transparency=0.5, light_distance=30.0))
    image = render(script)
    assert image.shape == (72, 96, 3) and 0 <= image.min() and image.max() <= 1
    np.testing.assert_array_equal(image, render(Script.from_json(script.to_json())))
    recoloured = render(Script(96, 72, 5, script.layers, RenderSettings(palette="coffee", seed=2)))
    reshaped = render(Script(96, 72, 6, script.layers, script.render))
    assert not np.array_equal(image, recoloured) and not np.array_equal(image, reshaped)


def test_opaque_render_shows_palette_colours_and_tessellation_cells():
    palette = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    structure = sample_structure([Layer(texels=("rectangle",), max_objects=4, max_diameter=30)], 64, 64, seed=2)
    flat = render_structure(structure, RenderSettings(samples=1), palette=palette)
    colours = {tuple(pixel) for pixel in flat.reshape(-1, 3)}
    assert colours <= {(1.0, 0.0, 0.0), (0.0, 0.0, 1.0)}
    cells = render_structure(structure, RenderSettings(samples=1, tessellation=True), palette=palette)
    assert {tuple(pixel) for pixel in cells.reshape(-1, 3)} <= {(1.0, 0.0, 0.0), (0.0, 0.0, 1.0)}


def test_keep_father_inclusion_draws_children_only_inside_their_father():
    layers = (Layer(texels=("rectangle",), max_objects=1, max_diameter=30),
              Layer(texels=("rectangle",), max_objects=30, max_diameter=25))
    structure = sample_structure(layers, 80, 80, seed=3)
    father = Polygon(structure.layer_objects(1)[0].polygon)
    rows, cols = np.mgrid[0:80, 0:80] + 0.5
    outside = ~shapely.contains_xy(father, cols, rows)
    palette = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    clipped = render_structure(structure, RenderSettings(samples=1, keep_father_inclusion=True), palette=palette)
    unclipped = render_structure(structure, RenderSettings(samples=1), palette=palette)
    assert outside.any()
    background = clipped[outside][0]  # the image rectangle's colour, wherever the father is not
    np.testing.assert_array_equal(clipped[outside], np.broadcast_to(background, clipped[outside].shape))
    assert not np.array_equal(unclipped[outside], np.broadcast_to(background, unclipped[outside].shape))


# ---------------------------------------------------------------------------- fast placement internals


def test_resolution_in_order_equals_the_one_by_one_rule():
    """Object i takes its first alive trial that intersects no earlier choice (naive loop as oracle)."""
    rng = np.random.default_rng(7)
    trials, n_objects = 5, 60
    shapes = shapely.buffer(shapely.points(rng.uniform(0, 100, size=(n_objects * trials, 2))),
                            rng.uniform(2, 9, size=n_objects * trials))
    alive = rng.random(n_objects * trials) < 0.8
    expected, kept = [], []
    for row in range(n_objects):
        choice = -1
        for index in range(row * trials, (row + 1) * trials):
            if alive[index] and not any(shapes[index].intersects(other) for other in kept):
                choice = index
                kept.append(shapes[index])
                break
        expected.append(choice)
    chosen = sampler._resolve_in_order(shapes, alive, trials)
    np.testing.assert_array_equal(chosen, expected)
    assert (chosen >= 0).sum() < n_objects  # some objects found no room: the check can fail


def test_probe_vertices_only_skip_trials_that_the_rules_reject(monkeypatch):
    """The cheap pre-tests are necessary conditions: without them the structure is the same bit for bit."""
    layers = (Layer(texels=("triangle", "convex_polygon"), max_objects=40, max_diameter=60, exclusion=True),
              Layer(texels=("random_shape", "ellipse"), max_objects=6, max_diameter=25, inclusion=True,
                    exclusion=True, aspect_ratio=2.0),
              Layer(texels=("random_shape",), max_objects=4, max_diameter=12, inclusion=True))
    fast = sample_structure(layers, 200, 160, seed=11)
    monkeypatch.setattr(sampler, "_probe_test", lambda slots, rows, *args: np.ones(len(rows), dtype=bool))
    slow = sample_structure(layers, 200, 160, seed=11)
    assert len(fast.objects) == len(slow.objects) and fast.placed[3] > 0
    for a, b in zip(fast.objects, slow.objects):
        np.testing.assert_array_equal(a.polygon, b.polygon)


def test_larger_trials_of_every_object_come_before_reductions():
    """Rounds by diameter level (module docstring): objects of a round never wait for later ones."""
    layer = Layer(texels=("ellipse",), max_objects=200, max_diameter=40, exclusion=True, max_trials=4,
                  size_reduction=0.5, max_reductions=3)
    structure = sample_structure([layer], 200, 200, seed=2)
    levels = np.array([item.reductions for item in structure.objects[1:]])
    assert set(levels) == {0, 1, 2, 3}
    assert rule_violations(structure)["exclusion"] == 0


def test_a_sliver_father_ends_and_places_nothing_inside():
    sliver = (Layer(texels=("rectangle",), max_objects=1, max_diameter=150, aspect_ratio=1e5),
              Layer(texels=("rectangle",), max_objects=3, max_diameter=1.0, inclusion=True, max_trials=2,
                    max_reductions=1))
    structure = sample_structure(sliver, 100, 100, seed=0)
    assert structure.placed[1] == 1 and structure.tried[2] == 3 and structure.placed[2] == 0


def test_rule_violations_counts_what_shapely_sees():
    layers = (Layer(texels=("rectangle",), max_objects=30, max_diameter=30),
              Layer(texels=("rectangle",), max_objects=3, max_diameter=10))
    structure = sample_structure(layers, 100, 100, seed=0)
    counts = rule_violations(structure)
    assert counts["exclusion_per_layer"] == [None, None] and counts["inclusion_per_layer"] == [None, None]
    strict = sample_structure([replace(layers[0], exclusion=True), replace(layers[1], inclusion=True)], 100, 100,
                              seed=0)
    assert rule_violations(strict) == {"exclusion": 0, "inclusion": 0, "exclusion_per_layer": [0, None],
                                       "inclusion_per_layer": [None, 0]}
    # the unconstrained objects judged by the strict rules: the counts must see the breaches
    relabelled = Structure(100, 100, strict.layers, structure.objects, structure.tried, structure.placed)
    expected_pairs = intersecting_pairs(geometries(structure, 1))
    outside = sum(not Polygon(structure.objects[item.father].polygon).contains_properly(Polygon(item.polygon))
                  for item in structure.layer_objects(2))
    assert expected_pairs > 0 and outside > 0
    assert rule_violations(relabelled)["exclusion"] == expected_pairs
    assert rule_violations(relabelled)["inclusion"] == outside
    with pytest.raises(ValueError, match="Structure"):
        rule_violations("structure")


def test_blocks_of_objects_keep_the_rules(monkeypatch):
    monkeypatch.setattr(sampler, "ROUND_TRIALS", 50)  # a few objects per block
    layers = (Layer(texels=("ellipse", "triangle"), max_objects=60, max_diameter=30, exclusion=True),
              Layer(texels=("rectangle",), max_objects=7, max_diameter=12, inclusion=True, exclusion=True))
    structure = sample_structure(layers, 150, 150, seed=3)
    assert structure.placed[1] > 20 and structure.placed[2] > 20
    assert rule_violations(structure)["exclusion"] == 0 and rule_violations(structure)["inclusion"] == 0


def test_changing_the_texels_keeps_the_placements_of_a_layer_without_rules():
    ellipses = Layer(texels=("ellipse",), max_objects=25, max_diameter=20)
    triangles = replace(ellipses, texels=("triangle", "random_shape"))
    a = sample_structure([ellipses], 200, 200, seed=8).objects[1:]
    b = sample_structure([triangles], 200, 200, seed=8).objects[1:]
    assert [item.center for item in a] == [item.center for item in b]
    assert [item.angle for item in a] == [item.angle for item in b]
    assert {item.kind for item in b} == {"triangle", "random_shape"}


def test_tessellation_cells_are_the_faces_of_the_boundary_arrangement():
    """Pixel cells = shapely's faces of the union of object boundaries (no face thinner than a pixel here)."""
    squares = [(10, 10, 60, 50), (40, 30, 90, 80), (20, 60, 70, 90), (65, 5, 95, 25)]
    objects = [MLObject(0, -1, "image", (50.0, 50.0), 141.0, 0.0, 0,
                        np.array([[0.0, 0.0], [100.0, 0.0], [100.0, 100.0], [0.0, 100.0]]))]
    for x0, y0, x1, y1 in squares:
        objects.append(MLObject(1, 0, "rectangle", ((x0 + x1) / 2, (y0 + y1) / 2), x1 - x0, 0.0, 0,
                                np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], dtype=float)))
    structure = Structure(100, 100, (Layer(),), objects, np.array([1, 4]), np.array([1, 4]))
    edges = shapely.get_parts(shapely.union_all([Polygon(item.polygon).boundary for item in objects]))
    faces = shapely.get_parts(shapely.polygonize(edges))
    cells = tessellation_cells(structure, 2, np.random.default_rng(0))
    # outside, A only, A and B, B only, B and C, C only, D
    assert cells.max() == len(faces) == 7


# ---------------------------------------------------------------------------- order of insertion (issue 25)

PACKING = Layer(texels=("ellipse", "rectangle", "triangle"), max_objects=60, aspect_ratio=2.0, max_diameter=60.0,
                max_trials=10, size_reduction=0.8, max_reductions=6, exclusion=True, v0=(1.0, 0.0, 0.0),
                v1=(0.0, 1.0, 0.0))


def _trace_rounds(monkeypatch):
    """Record (first slot, number of slots, diameter) of every exclusion round the sampler runs."""
    calls = []
    original = sampler._exclusion_round

    def traced(slots, pending, layer, diameter, *args):
        calls.append((int(pending[0]), len(pending), float(diameter)))
        return original(slots, pending, layer, diameter, *args)

    monkeypatch.setattr(sampler, "_exclusion_round", traced)
    return calls


def test_sequential_order_finishes_each_object_before_the_next(monkeypatch):
    calls = _trace_rounds(monkeypatch)
    structure = sample_structure([PACKING], 128, 128, seed=3, order="sequential")
    assert structure.order == "sequential" and all(count == 1 for _, count, _ in calls)
    slots = [slot for slot, _, _ in calls]
    assert slots == sorted(slots) and set(slots) == set(range(PACKING.max_objects))  # one object after another
    for slot in set(slots):  # each object: Max_D, Max_D s_R, ... until placed or given up
        diameters = [d for s, _, d in calls if s == slot]
        assert diameters == pytest.approx([PACKING.max_diameter * PACKING.size_reduction**k
                                           for k in range(len(diameters))])
    calls.clear()
    sample_structure([PACKING], 128, 128, seed=3)  # rounds: every object's trial at one diameter first
    diameters = [d for _, _, d in calls]
    assert diameters == sorted(diameters, reverse=True) and calls[0][1] == PACKING.max_objects


def test_orders_keep_the_rules_are_reproducible_and_differ_only_under_exclusion():
    for order in sampler.ORDERS:
        first = sample_structure([PACKING], 128, 128, seed=5, order=order)
        again = sample_structure([PACKING], 128, 128, seed=5, order=order)
        assert rule_violations(first)["exclusion"] == 0
        assert all(np.array_equal(a.polygon, b.polygon) for a, b in zip(first.objects, again.objects))
        assert np.array_equal(first.trials, again.trials)
    rounds = sample_structure([PACKING], 128, 128, seed=5)
    sequential = sample_structure([PACKING], 128, 128, seed=5, order="sequential")
    assert [item.center for item in rounds.objects] != [item.center for item in sequential.objects]
    free = replace(PACKING, exclusion=False)  # objects do not interact: one process, sampled identically
    a = sample_structure([free], 128, 128, seed=5)
    b = sample_structure([free], 128, 128, seed=5, order="sequential")
    assert all(np.array_equal(x.polygon, y.polygon) for x, y in zip(a.objects, b.objects))
    with pytest.raises(ValueError, match="order"):
        sample_structure([PACKING], 64, 64, seed=0, order="random")


@pytest.mark.parametrize("order", ["rounds", "sequential"])
def test_trials_are_counted_as_the_sequential_process_makes_them(order):
    n, trials, reductions = 7, 5, 2
    huge = dict(texels=("ellipse",), max_objects=n, max_diameter=300.0, max_trials=trials, max_reductions=reductions,
                size_reduction=0.99)
    # exclusion, disks much wider than the image: the first fits at its first trial, no other ever fits
    stuck = sample_structure([Layer(exclusion=True, **huge)], 100, 100, seed=0, order=order)
    assert stuck.placed.tolist() == [1, 1]
    assert stuck.trials.tolist() == [0, 1 + (n - 1) * trials * (reductions + 1)]
    # inclusion in the image of the same disks: nothing ever fits
    none = sample_structure([Layer(inclusion=True, **huge)], 100, 100, seed=0, order=order)
    assert none.placed.tolist() == [1, 0] and none.trials.tolist() == [0, n * trials * (reductions + 1)]
