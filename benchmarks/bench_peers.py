"""Python peers as baselines: pointpats and astropy for K/L functions, scikit-image for GLCM counts.

Points: ``n`` uniform points in the unit square (``default_rng(n)``, as in
``bench_pointprocess_summary.py``), every estimate on our default r grid (513 values from 0
to ``rmax``), which is passed to the peer. What each peer computes, against the case timed:

* ``pointpats.distance_statistics.l`` (pointpats 2.5) against our ``Lest(correction="none")``:
  pointpats has no edge correction; it takes the area of the points' bounding box for the
  window, divides by ``n^2`` instead of ``n (n - 1)`` and counts ``d < r`` (we: ``d <= r``),
  so ``K_pointpats = K_un (n - 1) / n * |bbox|`` up to ties. Memory: an ``(n_r, n (n-1) / 2)``
  boolean array (256 MB at 1e3 points, 26 GB at 1e4), so 1e3 points only.
* ``astropy.stats.RipleysKEstimator`` (area 1, unit square) against our ``Kest``: mode
  "none" = our ``un``, "translation" = our ``trans`` (same estimators; astropy counts
  ``d < r``); mode "ripley" against our ``iso``: astropy weights each unordered pair once,
  by the circle around its first point in array order, where spatstat and we sum both
  ordered pairs (each with the circle around its own first point), so the values differ
  (about a percent). Memory and time: astropy holds all ``n (n - 1) / 2`` pair differences
  and makes one pass over them per r (513 passes), so 1e3 points only (at 1e4: 5e7 pairs,
  over a GB per array).
* ``skimage.feature.graycomatrix`` (scikit-image is a core dependency) against our
  :func:`paperlib.stipple.glcm.cooccurrence_counts`: the 3 (n - 1) non-symmetric 2x2 GLCMs
  of Kim 2009's offsets (horizontal, vertical, left-down diagonal, lengths 1 .. n - 1) of an
  n x n random bitonal texture (30 % ink); graycomatrix gets distances 1 .. n - 1 at angles
  0 and pi/2, and distances k sqrt(2) at 3 pi/4 (two calls); identical counts.

A peer that is not installed (CI does not install the ``bench`` extra) leaves its case
without a baseline and says so in the name. :func:`check_peers` compares the answers.
"""

from __future__ import annotations

import numpy as np
from skimage.feature import graycomatrix

from paperlib.pointprocess import PointPattern, Window
from paperlib.pointprocess.summary import Kest, Lest, default_r
from paperlib.stipple.glcm import cooccurrence_counts, paper_offsets
from registry import benchmark

try:
    from pointpats import distance_statistics as pointpats_distance
except ImportError:  # the bench extra is not installed
    pointpats_distance = None
try:
    from astropy.stats import RipleysKEstimator
except ImportError:
    RipleysKEstimator = None

POINT_SIZES = [1_000]
GLCM_SIDES = [64, 128, 256]
MISSING = "{} not installed (pip install .[bench]): no baseline"


def uniform_points(n: int) -> np.ndarray:
    return np.random.default_rng(n).random((n, 2))


def r_grid(n: int) -> np.ndarray:
    return default_r(Window.rectangle(), n)


def pattern(n: int) -> PointPattern:
    return PointPattern(uniform_points(n), Window.rectangle())


# ---------------------------------------------------------------------------- K and L


def pointpats_l(n: int):
    points, r = uniform_points(n), r_grid(n)
    return lambda: pointpats_distance.l(points, support=r)[1]


def astropy_k(mode: str):
    def make(n: int):
        points, r = uniform_points(n), r_grid(n)
        estimator = RipleysKEstimator(area=1.0, x_min=0.0, x_max=1.0, y_min=0.0, y_max=1.0)
        return lambda: estimator.evaluate(points, r, mode=mode)

    return make


def our_estimate(function, correction: str):
    def make(n: int):
        data = pattern(n)
        return lambda: function(data, correction=correction)

    return make


def _label(function: str, n: int, extra: str) -> str:
    return f"{function}, {n:.0e} pts, unit square, r 0..{r_grid(n)[-1]:.3g} (513), vs {extra}".replace("e+0", "e")


for _n in POINT_SIZES:
    if pointpats_distance is not None:
        benchmark(_label("Lest none (no edge corr.)", _n, "pointpats (bbox area, /n^2, d<r)"), sizes=[_n],
                  baseline=pointpats_l, baseline_name="pointpats.distance_statistics.l")(our_estimate(Lest, "none"))
    else:
        benchmark(_label("Lest none (no edge corr.)", _n, MISSING.format("pointpats")), sizes=[_n])(
            our_estimate(Lest, "none"))
    for _correction, _mode, _note in [("none", "none", "same estimator"), ("translate", "translation", "same estimator"),
                                      ("isotropic", "ripley", "one weight per unordered pair")]:
        _name = _label(f"Kest {_correction}", _n, f"astropy mode={_mode} ({_note})")
        if RipleysKEstimator is not None:
            benchmark(_name, sizes=[_n], baseline=astropy_k(_mode),
                      baseline_name=f"astropy RipleysKEstimator {_mode}")(our_estimate(Kest, _correction))
        else:
            benchmark(_label(f"Kest {_correction}", _n, MISSING.format("astropy")), sizes=[_n])(
                our_estimate(Kest, _correction))


# ---------------------------------------------------------------------------- GLCM


def bitonal_texture(side: int) -> np.ndarray:
    return np.random.default_rng(side).random((side, side)) < 0.3


def skimage_counts(texture: np.ndarray) -> np.ndarray:
    """graycomatrix's counts for the paper's offsets, in :func:`paper_offsets` order, shape (3 (n - 1), 2, 2)."""
    image = texture.astype(np.uint8)
    lengths = np.arange(1, min(texture.shape))
    axes = graycomatrix(image, lengths, [0.0, np.pi / 2], levels=2, symmetric=False)  # (2, 2, n - 1, 2)
    diagonal = graycomatrix(image, lengths * np.sqrt(2), [3 * np.pi / 4], levels=2, symmetric=False)
    stacked = np.concatenate([axes[:, :, :, 0], axes[:, :, :, 1], diagonal[:, :, :, 0]], axis=2)
    return np.moveaxis(stacked, 2, 0)


def glcm_case(side: int):
    texture, offsets = bitonal_texture(side), paper_offsets(side)
    return lambda: cooccurrence_counts(texture, offsets)


def glcm_baseline(side: int):
    texture = bitonal_texture(side)
    return lambda: skimage_counts(texture)


benchmark("GLCM counts, 3(n-1) paper offsets, NxN bitonal texture (30% ink), vs skimage", sizes=GLCM_SIDES,
          baseline=glcm_baseline, baseline_name="skimage graycomatrix (2 calls)")(glcm_case)


# ---------------------------------------------------------------------------- answers


def _relative(a, b) -> float:
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    both = np.isfinite(a) & np.isfinite(b) & (b != 0)
    return float(np.max(np.abs(a[both] - b[both]) / np.abs(b[both]), initial=0.0))


def check_peers(n: int = 1_000, side: int = 64) -> dict:
    """Largest relative differences between each peer and us (installed peers only)."""
    out = {}
    points, r = uniform_points(n), r_grid(n)
    k = Kest(pattern(n), correction=("none", "translate", "isotropic"))
    if pointpats_distance is not None:
        l_pointpats = pointpats_distance.l(points, support=r)[1]
        bbox = np.prod(points.max(axis=0) - points.min(axis=0))
        out["pointpats l vs Lest un, raw"] = _relative(l_pointpats, np.sqrt(k["un"] / np.pi))
        out["pointpats l vs Lest un, rescaled by sqrt((n-1)/n |bbox|)"] = _relative(
            l_pointpats, np.sqrt(k["un"] * (n - 1) / n * bbox / np.pi))
    if RipleysKEstimator is not None:
        estimator = RipleysKEstimator(area=1.0, x_min=0.0, x_max=1.0, y_min=0.0, y_max=1.0)
        for mode, column in [("none", "un"), ("translation", "trans"), ("ripley", "iso")]:
            out[f"astropy {mode} vs Kest {column}"] = _relative(estimator.evaluate(points, r, mode=mode), k[column])
    texture = bitonal_texture(side)
    ours = cooccurrence_counts(texture, paper_offsets(side))
    out["skimage graycomatrix vs cooccurrence_counts (count differences)"] = float(
        np.abs(skimage_counts(texture).astype(np.int64) - ours).max())
    return out
