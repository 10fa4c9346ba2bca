"""Fidelity of a synthesis to its exemplar, each measure scored against a control (issue 24).

Every method of paperlib produces one of three things: element centres (with categories, marks,
orientations or sizes), a binary image, or a curve. These measures compare a synthesis with its
exemplar on what it produced, independently of the method's own objective, and score the same
comparison for a *control* a wrong answer would score like (DESIGN.md, "Validation"): complete
spatial randomness (CSR) with the synthesis's number of points in its window, or a shuffle of the
synthesis itself (its category labels, its marks, its pixels, the steps of its curve), or a plain
smoothing (the guide curve). A score therefore says how much better than chance the synthesis is.

Point patterns (:class:`paperlib.pointprocess.PointPattern`):

- :func:`l_score`: the largest difference ``sup_r |L_syn(r) - L_ex(r)|`` of Besag's L functions
  (:func:`paperlib.pointprocess.Lest`, translation correction), against CSR. With the exemplar's
  L as the reference curve, the control draws give the global (maximum absolute deviation)
  envelope of chance around it (Baddeley et al. 2015, 10.7; Myllymaki et al. 2017); a synthesis
  closer than all ``nsim`` draws lies inside a band around the exemplar that a chance pattern
  misses with probability ``1 - 1 / (nsim + 1)``;
- :func:`pcf_score`: root mean square difference of the pair correlation functions
  (:func:`paperlib.pointprocess.pcf`, the exemplar's kernel width for both), against CSR;
- :func:`lcross_score`: ``sup_r |L_ij,syn(r) - L_ij,ex(r)|`` of the cross-type L
  (:func:`paperlib.pointprocess.Lcross`), against a random relabelling of the synthesis;
- :func:`nn_distance_score`: two-sample Kolmogorov-Smirnov statistic of the nearest-neighbour
  distances, against CSR;
- :func:`mark_difference_score`: KS statistic of the differences between the mark (size,
  orientation, with ``period`` for angles) of every element and that of its nearest neighbour,
  against the synthesis with its marks shuffled among its elements (Illian et al. 2008, 5.3:
  the mark correlation a shuffle destroys).

Binary images: :func:`glcm_correlation` (the GLCM correlation against pixel distance,
``skimage.feature.graycomatrix``/``graycoprops``, averaged over four directions) and
:func:`glcm_score` (RMS difference of those curves, against the synthesis's pixels shuffled).

Curves: :func:`turning_angles` (:func:`paperlib.geometry.turning_angles`, re-exported here),
:func:`turning_score` (KS statistic of the turning angles against those of the exemplar curves, the
control the guide curve resampled alike: a plain smoothing) and :func:`hausdorff_score` (Hausdorff
distance to the guide over the guide's diameter, against the synthesis's own steps in shuffled order).

Every score is a :class:`FidelityScore`: lower values are closer; ``better_than_control`` holds
when the synthesis is closer than *every* control draw, which a synthesis that is no better than
the control does with probability ``1 / (nsim + 1)`` (a Monte Carlo test at level 0.05 for the
default ``nsim = 19``).

A floor module: it builds on :mod:`paperlib.geometry` and :mod:`paperlib.pointprocess` and never
imports a method. Written by hand only where no library does it (the scores and controls); the
summary functions are paperlib's spatstat-equal ones and the GLCM is scikit-image's.

References
----------
.. [1] A. Baddeley, E. Rubak, R. Turner, *Spatial Point Patterns: Methodology and Applications
   with R*, CRC Press, 2015 (chapters 7 and 10: K, L, pcf, envelopes, Monte Carlo tests).
.. [2] J. Illian, A. Penttinen, H. Stoyan, D. Stoyan, *Statistical Analysis and Modelling of
   Spatial Point Patterns*, Wiley, 2008 (4.2 nearest-neighbour distances, 5.3 mark correlations).
.. [3] R. M. Haralick, K. Shanmugam, I. Dinstein, "Textural features for image classification",
   IEEE Trans. SMC 3(6), 1973 (GLCM correlation).
.. [4] M. Myllymaki, T. Mrkvicka, P. Grabarnik, H. Seijo, U. Hahn, "Global envelope tests for
   spatial processes", JRSS B 79(2), 2017.
"""

from __future__ import annotations

from dataclasses import dataclass
import numpy as np
from scipy.spatial import cKDTree
from scipy.stats import ks_2samp

from ._checks import as_generator, check_flag, finite_array, integer_at_least, point_array, positive_number
from .geometry import hausdorff, resample_closed_curve, resample_open_curve, turning_angles
from .pointprocess import Lcross, Lest, PointPattern, pcf

__all__ = [
    "FidelityScore",
    "glcm_correlation",
    "glcm_score",
    "hausdorff_score",
    "l_score",
    "lcross_score",
    "mark_difference_score",
    "nn_distance_score",
    "pcf_score",
    "turning_angles",
    "turning_score",
]

#: Default number of control draws: with 19, "closer than every draw" is a Monte Carlo test at 0.05.
NSIM = 19
#: Steps of the default r grid of the L, Lcross and pcf scores.
R_STEPS = 64
#: The default r grid reaches this many mean spacings of the exemplar (and a quarter of the shorter side).
R_REACH = 3.0
#: Default pixel distances of the GLCM correlation curve.
GLCM_DISTANCES = tuple(range(1, 9))
#: Most control draws a call may ask for.
MAX_NSIM = 999


@dataclass(frozen=True, eq=False)
class FidelityScore:
    """One fidelity measure of a synthesis, with the same measure of its control.

    Parameters
    ----------
    measure : str
        What was measured (e.g. ``"L sup"``, ``"NN-distance KS"``).
    value : float
        The synthesis's distance to the exemplar (0 = identical; lower is closer).
    control : float
        Median of the control's distances to the exemplar.
    controls : numpy.ndarray
        Every control draw's distance (one value for a deterministic control).
    control_kind : str
        What the control is (``"CSR"``, ``"random labelling"``, ``"mark shuffle"``,
        ``"pixel shuffle"``, ``"guide (smoothing)"``, ``"step shuffle"``).
    better_than_control : bool
        True when ``value`` is below every control draw: a synthesis no better than the
        control does so with probability ``1 / (len(controls) + 1)``.
    ratio : float
        ``value / control``: 1 scores as chance, 0 as the exemplar itself (1 when both are 0: the
        measure cannot tell the synthesis from the control; ``inf`` when only the control is 0).
    p_value : float
        Monte Carlo p-value ``(1 + #{controls <= value}) / (len(controls) + 1)`` of the null
        "the synthesis is no closer to the exemplar than the control".
    """

    measure: str
    value: float
    control: float
    controls: np.ndarray
    control_kind: str
    better_than_control: bool
    ratio: float
    p_value: float


def _score(measure: str, value: float, controls, control_kind: str) -> FidelityScore:
    controls = np.asarray(controls, dtype=np.float64).ravel()
    control = float(np.median(controls))
    value = float(value)
    if control > 0:
        ratio = value / control
    else:  # a control at the exemplar itself: the measure cannot tell them apart (0 / 0 scores as chance)
        ratio = 1.0 if value == 0 else float("inf")
    return FidelityScore(measure, value, control, controls, control_kind, bool(value < controls.min()), ratio,
                         float((1 + np.sum(controls <= value)) / (len(controls) + 1)))


# ---------------------------------------------------------------------------------------- checks


def _pattern(value, name: str, min_points: int = 2) -> PointPattern:
    if not isinstance(value, PointPattern):
        raise TypeError(f"{name} must be a paperlib.pointprocess.PointPattern, got {type(value).__name__}")
    if len(value.points) < min_points:
        raise ValueError(f"{name} must hold at least {min_points} points, got {len(value.points)}")
    return value


def _nsim(nsim) -> int:
    nsim = integer_at_least(nsim, "nsim", 1)
    if nsim > MAX_NSIM:
        raise ValueError(f"nsim must be at most {MAX_NSIM}, got {nsim}")
    return nsim


def _intensity(pattern: PointPattern) -> float:
    return len(pattern.points) / pattern.window.area


def _r_grid(r, exemplar: PointPattern, synthesis: PointPattern) -> np.ndarray:
    if r is None:
        windows = (exemplar.window, synthesis.window)
        reach = min(min(min(w.width, w.height) for w in windows) / 4.0, R_REACH / np.sqrt(_intensity(exemplar)))
        return np.linspace(0.0, reach, R_STEPS + 1)
    grid = finite_array(r, "r", ndim=1)
    if len(grid) < 2 or grid[0] != 0 or np.any(np.diff(grid) <= 0):
        raise ValueError(f"r must be an increasing grid of at least 2 radii starting at 0, got {grid[:5]!r}...")
    return grid


def _csr(pattern: PointPattern, rng: np.random.Generator) -> PointPattern:
    """Binomial CSR: the pattern's number of points, uniform in its window (its marks kept in order)."""
    points = pattern.window.uniform_points(len(pattern.points), rng)
    return PointPattern(points, pattern.window, pattern.marks, pattern.categories)


def _quietly(function, *args, **kwargs):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # duplicated points: counted as spatstat does
        return function(*args, **kwargs)


# ---------------------------------------------------------------------------------------- point patterns


def _l_curve(pattern: PointPattern, r: np.ndarray) -> np.ndarray:
    return _quietly(Lest, pattern, r, correction="translate")["trans"].to_numpy()


def _sup(curve: np.ndarray, reference: np.ndarray) -> float:
    return float(np.nanmax(np.abs(curve - reference)))


def l_score(exemplar, synthesis, *, r=None, nsim: int = NSIM, rng=None) -> FidelityScore:
    """Largest difference between the L functions of a synthesis and its exemplar, against CSR.

    Parameters
    ----------
    exemplar, synthesis : paperlib.pointprocess.PointPattern
        Element centres, at least 2 each; marks are ignored. Their windows may differ (L is
        normalised by intensity).
    r : array_like, optional
        Radii, increasing from 0. Default: 65 values up to the smaller of a quarter of the
        shorter window side and 3 mean spacings of the exemplar.
    nsim : int
        Number of CSR draws (the synthesis's number of points, uniform in its window).
    rng : None, int or numpy.random.Generator

    Returns
    -------
    FidelityScore
        ``value = sup_r |L_syn(r) - L_ex(r)|`` (Besag's ``L = sqrt(K / pi)``, translation
        correction, spatstat's ``Lest``); the control draws give the global maximum-deviation
        envelope of CSR around the exemplar's L (Baddeley et al. 2015, 10.7).
    """
    exemplar, synthesis = _pattern(exemplar, "exemplar"), _pattern(synthesis, "synthesis")
    grid, nsim, rng = _r_grid(r, exemplar, synthesis), _nsim(nsim), as_generator(rng)
    reference = _l_curve(exemplar, grid)
    controls = [_sup(_l_curve(_csr(synthesis, rng), grid), reference) for _ in range(nsim)]
    return _score("L sup", _sup(_l_curve(synthesis, grid), reference), controls, "CSR")


def pcf_score(exemplar, synthesis, *, r=None, nsim: int = NSIM, rng=None) -> FidelityScore:
    """Root mean square difference between the pair correlation functions, against CSR.

    Parameters
    ----------
    exemplar, synthesis : paperlib.pointprocess.PointPattern
        At least 2 points each.
    r : array_like, optional
        Radii, increasing from 0 (default as :func:`l_score`); the RMS is over ``r > 0``.
    nsim : int
        Number of CSR draws.
    rng : None, int or numpy.random.Generator

    Returns
    -------
    FidelityScore
        ``value = sqrt(mean_r (g_syn(r) - g_ex(r))^2)`` with spatstat's ``pcf`` (translation
        correction), every pattern smoothed with the exemplar's kernel width (Stoyan's rule).
    """
    exemplar, synthesis = _pattern(exemplar, "exemplar"), _pattern(synthesis, "synthesis")
    grid, nsim, rng = _r_grid(r, exemplar, synthesis), _nsim(nsim), as_generator(rng)
    bw = 0.15 / np.sqrt(5.0 * _intensity(exemplar))

    def curve(pattern):
        return _quietly(pcf, pattern, grid, correction="translate", bw=bw)["trans"].to_numpy()[1:]

    reference = curve(exemplar)

    def rms(pattern):
        return float(np.sqrt(np.nanmean((curve(pattern) - reference) ** 2)))

    controls = [rms(_csr(synthesis, rng)) for _ in range(nsim)]
    return _score("pcf RMS", rms(synthesis), controls, "CSR")


def _type_index(pattern: PointPattern, value, name: str) -> int:
    if isinstance(value, str):
        if value not in pattern.categories:
            raise ValueError(f"{name} must be a category of the patterns {pattern.categories}, got {value!r}")
        return pattern.categories.index(value)
    return integer_at_least(value, name, 0)


def lcross_score(exemplar, synthesis, i, j, *, r=None, nsim: int = NSIM, rng=None) -> FidelityScore:
    """Largest difference between the cross-type L functions ``L_ij``, against random labelling.

    Parameters
    ----------
    exemplar, synthesis : paperlib.pointprocess.PointPattern
        Multitype patterns with the same categories, each holding points of types ``i`` and ``j``.
    i, j : int or str
        The two types (index or category name), ``i != j``.
    r : array_like, optional
        Radii, increasing from 0 (default as :func:`l_score`).
    nsim : int
        Number of random relabellings of the synthesis (its labels permuted among its points:
        positions and type counts kept, the dependence between types destroyed).
    rng : None, int or numpy.random.Generator

    Returns
    -------
    FidelityScore
        ``value = sup_r |L_ij,syn(r) - L_ij,ex(r)|`` (spatstat's ``Lcross``, translation
        correction; Hurtut 2009, 3.2.2 uses the centred version, which differs by ``r`` in both).
    """
    exemplar, synthesis = _pattern(exemplar, "exemplar"), _pattern(synthesis, "synthesis")
    if tuple(exemplar.categories) != tuple(synthesis.categories):
        raise ValueError(f"exemplar and synthesis must have the same categories, got {exemplar.categories} "
                         f"and {synthesis.categories}")
    i, j = _type_index(exemplar, i, "i"), _type_index(exemplar, j, "j")
    if i == j:
        raise ValueError(f"i and j must be two different types, got {i} and {j}")
    for name, pattern in (("exemplar", exemplar), ("synthesis", synthesis)):
        for t in (i, j):
            if t >= len(pattern.categories) or not np.any(pattern.marks == t):
                raise ValueError(f"{name} has no point of type {t} (categories {pattern.categories})")
    grid, nsim, rng = _r_grid(r, exemplar, synthesis), _nsim(nsim), as_generator(rng)

    def curve(pattern):
        return _quietly(Lcross, pattern, i, j, grid, correction="translate")["trans"].to_numpy()

    reference = curve(exemplar)
    controls = []
    for _ in range(nsim):
        shuffled = PointPattern(synthesis.points, synthesis.window, rng.permutation(synthesis.marks),
                                synthesis.categories)
        controls.append(_sup(curve(shuffled), reference))
    return _score("Lcross sup", _sup(curve(synthesis), reference), controls, "random labelling")


def _nn_distances(points: np.ndarray) -> np.ndarray:
    return cKDTree(points).query(points, k=2)[0][:, 1]


def nn_distance_score(exemplar, synthesis, *, nsim: int = NSIM, rng=None) -> FidelityScore:
    """Kolmogorov-Smirnov distance between nearest-neighbour distance distributions, against CSR.

    Parameters
    ----------
    exemplar, synthesis : paperlib.pointprocess.PointPattern
        At least 2 points each.
    nsim : int
        Number of CSR draws.
    rng : None, int or numpy.random.Generator

    Returns
    -------
    FidelityScore
        ``value`` = two-sample KS statistic (0 .. 1) of the distances from every point to its
        nearest other point (Illian et al. 2008, 4.2; not edge-corrected, so compare windows of
        comparable size).
    """
    exemplar, synthesis = _pattern(exemplar, "exemplar"), _pattern(synthesis, "synthesis")
    nsim, rng = _nsim(nsim), as_generator(rng)
    reference = _nn_distances(exemplar.points)

    def ks(points):
        return float(ks_2samp(_nn_distances(points), reference).statistic)

    controls = [ks(synthesis.window.uniform_points(len(synthesis.points), rng)) for _ in range(nsim)]
    return _score("NN-distance KS", ks(synthesis.points), controls, "CSR")


def _marks(values, name: str, n: int) -> np.ndarray:
    values = finite_array(values, name, ndim=1)
    if len(values) != n:
        raise ValueError(f"{name} must hold one mark per point ({n}), got {len(values)}")
    return values


def _neighbour_differences(points: np.ndarray, marks: np.ndarray, period) -> np.ndarray:
    neighbour = cKDTree(points).query(points, k=2)[1][:, 1]
    difference = np.abs(marks - marks[neighbour])
    if period is not None:
        difference = np.mod(difference, period)
        difference = np.minimum(difference, period - difference)
    return difference


def mark_difference_score(exemplar, exemplar_marks, synthesis, synthesis_marks, *, period=None,
                          nsim: int = NSIM, rng=None) -> FidelityScore:
    """KS distance between the nearest-neighbour mark differences, against a shuffle of the marks.

    Parameters
    ----------
    exemplar, synthesis : paperlib.pointprocess.PointPattern
        Element centres, at least 2 each.
    exemplar_marks, synthesis_marks : array_like, shape (n,)
        A real mark per element: a size, an orientation, a colour value.
    period : float, optional
        For angles: differences are taken modulo ``period`` and folded into ``[0, period / 2]``
        (``pi`` for axes without direction, ``2 pi`` for directions). Default: plain differences.
    nsim : int
        Number of shuffles of the synthesis's marks among its elements (positions and the set of
        marks kept; the dependence between neighbours' marks destroyed).
    rng : None, int or numpy.random.Generator

    Returns
    -------
    FidelityScore
        ``value`` = two-sample KS statistic of ``|m_i - m_nn(i)|`` over the elements of the
        synthesis against those of the exemplar (a nearest-neighbour mark-difference statistic, the
        discrete counterpart of the mark variogram, Illian et al. 2008, 5.3).
    """
    exemplar, synthesis = _pattern(exemplar, "exemplar"), _pattern(synthesis, "synthesis")
    exemplar_marks = _marks(exemplar_marks, "exemplar_marks", len(exemplar.points))
    synthesis_marks = _marks(synthesis_marks, "synthesis_marks", len(synthesis.points))
    if period is not None:
        period = positive_number(period, "period")
    nsim, rng = _nsim(nsim), as_generator(rng)
    reference = _neighbour_differences(exemplar.points, exemplar_marks, period)

    def ks(marks):
        return float(ks_2samp(_neighbour_differences(synthesis.points, marks, period), reference).statistic)

    controls = [ks(rng.permutation(synthesis_marks)) for _ in range(nsim)]
    return _score("NN mark-difference KS", ks(synthesis_marks), controls, "mark shuffle")


# ---------------------------------------------------------------------------------------- binary images


def _binary_image(image, name: str) -> np.ndarray:
    if isinstance(image, (str, bytes)):
        raise TypeError(f"{name} must be a 2-D array, got {type(image).__name__}")
    array = np.asarray(image)
    if array.dtype == object or not (np.issubdtype(array.dtype, np.number) or array.dtype == bool):
        raise TypeError(f"{name} must be a 2-D numeric or boolean array, got dtype {array.dtype}")
    if array.ndim != 2 or min(array.shape) < 2:
        raise ValueError(f"{name} must be a 2-D image of at least 2 x 2 pixels, got shape {array.shape}")
    if array.dtype != bool:
        if not np.all(np.isfinite(array)) or not np.all((array == 0) | (array == 1)):
            raise ValueError(f"{name} must be binary (only 0 and 1, or booleans)")
    return array.astype(np.uint8)


def _distances(distances, shape) -> np.ndarray:
    values = finite_array(distances, "distances", ndim=1)
    if len(values) == 0 or np.any(values != np.round(values)) or np.any(values < 1):
        raise ValueError(f"distances must be a non-empty sequence of pixel distances >= 1, got {values!r:.80}")
    if values.max() >= min(shape):
        raise ValueError(f"distances must be smaller than the image's shorter side {min(shape)}, got {values.max():g}")
    return values.astype(np.int64)


def _glcm_curve(image: np.ndarray, distances: np.ndarray) -> np.ndarray:
    from skimage.feature import graycomatrix, graycoprops

    angles = [0.0, np.pi / 4, np.pi / 2, 3 * np.pi / 4]
    glcm = graycomatrix(image, distances, angles, levels=2, symmetric=True, normed=True)
    return graycoprops(glcm, "correlation").mean(axis=1)


def glcm_correlation(image, distances=GLCM_DISTANCES) -> np.ndarray:
    """GLCM correlation of a binary image at each pixel distance, averaged over four directions.

    Parameters
    ----------
    image : array_like, 2-D
        Binary image (booleans, or 0 and 1), at least 2 x 2.
    distances : sequence of int
        Pixel distances (>= 1, below the shorter side). Default 1 .. 8.

    Returns
    -------
    numpy.ndarray
        Haralick's correlation at each distance: ``skimage.feature.graycomatrix`` (2 levels,
        symmetric, normalised) at angles 0, 45, 90 and 135 degrees, ``graycoprops(...,
        "correlation")`` averaged over the angles; 1 where an image is constant (skimage's
        convention).
    """
    image = _binary_image(image, "image")
    return _glcm_curve(image, _distances(distances, image.shape))


def glcm_score(exemplar, synthesis, *, distances=GLCM_DISTANCES, nsim: int = NSIM, rng=None) -> FidelityScore:
    """RMS difference between GLCM correlation curves, against the synthesis's pixels shuffled.

    Parameters
    ----------
    exemplar, synthesis : array_like, 2-D
        Binary images (sizes may differ; ``distances`` must fit both).
    distances : sequence of int
        Pixel distances of the curves (default 1 .. 8).
    nsim : int
        Number of random permutations of the synthesis's pixels (same ink share, no structure).
    rng : None, int or numpy.random.Generator

    Returns
    -------
    FidelityScore
        ``value = sqrt(mean_d (c_syn(d) - c_ex(d))^2)`` of :func:`glcm_correlation` curves.
    """
    exemplar, synthesis = _binary_image(exemplar, "exemplar"), _binary_image(synthesis, "synthesis")
    distances = _distances(distances, (min(exemplar.shape + synthesis.shape),) * 2)
    nsim, rng = _nsim(nsim), as_generator(rng)
    reference = _glcm_curve(exemplar, distances)

    def rms(image):
        return float(np.sqrt(np.mean((_glcm_curve(image, distances) - reference) ** 2)))

    controls = [rms(rng.permutation(synthesis.ravel()).reshape(synthesis.shape)) for _ in range(nsim)]
    return _score("GLCM correlation RMS", rms(synthesis), controls, "pixel shuffle")


# ---------------------------------------------------------------------------------------- curves


def _curve(points, name: str, min_points: int = 3) -> np.ndarray:
    points = point_array(points, name, min_points=min_points)
    steps = np.hypot(*np.diff(points, axis=0).T)
    if np.any(steps == 0):
        raise ValueError(f"{name} has repeated consecutive vertices: drop them first")
    return points


def _resampled(points: np.ndarray, n: int, closed: bool) -> np.ndarray:
    return resample_closed_curve(points, n) if closed else resample_open_curve(points, n)


def _curve_list(curves, name: str) -> list:
    if isinstance(curves, np.ndarray) and curves.ndim == 2:
        curves = [curves]
    if isinstance(curves, (str, bytes)) or not hasattr(curves, "__len__") or len(curves) == 0:
        raise ValueError(f"{name} must be a non-empty list of (n, 2) curves, got {type(curves).__name__}")
    return [_curve(curve, f"{name}[{k}]") for k, curve in enumerate(curves)]


def turning_score(exemplar_curves, synthesis, guide, *, closed: bool) -> FidelityScore:
    """KS distance between turning-angle distributions, against the guide curve (a plain smoothing).

    Parameters
    ----------
    exemplar_curves : sequence of array_like, shape (n_k, 2)
        Training (exemplar) curves, at the sampling the synthesis was made at (e.g. uniform
        arc length, as Simhon 2001 trains).
    synthesis : array_like, shape (n, 2)
        The synthesized curve.
    guide : array_like, shape (m, 2)
        The coarse curve the synthesis elaborates; resampled at uniform arc length to ``n``
        vertices it is the control: the shape with no detail added.
    closed : bool
        Whether the curves are closed.

    Returns
    -------
    FidelityScore
        ``value`` = two-sample KS statistic of :func:`turning_angles` of the synthesis against
        those pooled over the exemplar curves; one (deterministic) control value.
    """
    closed = check_flag(closed, "closed")
    exemplar_curves = _curve_list(exemplar_curves, "exemplar_curves")
    synthesis, guide = _curve(synthesis, "synthesis"), _curve(guide, "guide")
    reference = np.concatenate([turning_angles(curve, closed=closed) for curve in exemplar_curves])
    control = turning_angles(_resampled(guide, len(synthesis), closed), closed=closed)
    value = ks_2samp(turning_angles(synthesis, closed=closed), reference).statistic
    return _score("turning-angle KS", value, [ks_2samp(control, reference).statistic], "guide (smoothing)")


def _dense(points: np.ndarray, closed: bool, n: int) -> np.ndarray:
    return _resampled(points, n, closed)


def hausdorff_score(guide, synthesis, *, closed: bool, nsim: int = NSIM, rng=None) -> FidelityScore:
    """Hausdorff distance from the synthesis to its guide curve, against its steps shuffled.

    Parameters
    ----------
    guide : array_like, shape (m, 2)
        The coarse curve the synthesis should follow.
    synthesis : array_like, shape (n, 2)
        The synthesized curve.
    closed : bool
        Whether the curves are closed.
    nsim : int
        Number of controls: the synthesis's edge vectors in random order, chained from its first
        vertex (same steps, so same length and turning magnitudes, and still closed for a closed
        curve; the steering that keeps it on the guide destroyed).
    rng : None, int or numpy.random.Generator

    Returns
    -------
    FidelityScore
        ``value`` = symmetric Hausdorff distance between the two curves (both resampled at 8 times
        the larger vertex count, :func:`paperlib.geometry.hausdorff`) over the diameter of the
        guide's bounding box.
    """
    closed = check_flag(closed, "closed")
    guide, synthesis = _curve(guide, "guide"), _curve(synthesis, "synthesis")
    nsim, rng = _nsim(nsim), as_generator(rng)
    scale = float(np.hypot(*np.ptp(guide, axis=0)))
    if scale == 0:
        raise ValueError("guide must not be a single point")
    n = 8 * max(len(guide), len(synthesis))
    dense_guide = _dense(guide, closed, n)

    def distance(curve):
        return hausdorff(_dense(curve, closed, n), dense_guide) / scale

    edges = np.diff(np.vstack([synthesis, synthesis[:1]]) if closed else synthesis, axis=0)
    controls = []
    for _ in range(nsim):
        chained = synthesis[0] + np.vstack([np.zeros((1, 2)), np.cumsum(rng.permutation(edges), axis=0)])
        controls.append(distance(chained[:-1] if closed else chained))
    return _score("Hausdorff to guide", distance(synthesis), controls, "step shuffle")

