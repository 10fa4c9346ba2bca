"""Issue 21: budgets, no hang, hardened formats, safe publishing, one rng check (the worst cases, each alone)."""

from __future__ import annotations

import gzip
import os

import numpy as np
import pytest

from paperlib import repro
from paperlib._atomic import publish_folder, recover_folder
from paperlib._checks import as_generator
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


def test_as_generator_is_default_rng_bit_for_bit():
    for seed in (None, 0, 12345, np.random.SeedSequence(7)):
        if seed is None:
            continue
        assert as_generator(seed).random() == np.random.default_rng(seed).random()
    generator = np.random.default_rng(3)
    assert as_generator(generator) is generator
