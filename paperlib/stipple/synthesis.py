"""Synthesis of stipple distribution textures by GLCM error minimization (Kim et al. 2009, 3.4).

A new bitonal distribution texture is grown from a seed texture (empty white by default) by
Metropolis spin flips that lower the average co-occurrence error ACE (eq. 5) between its
normalised GLCMs and the example's (section 3.4.1), with the pixel choice constrained by the
example's stipple geometry (section 3.4.2): after each flip, every pixel within a radius ``D``
of it is "considered" and cannot be chosen again during the iteration, and each later pass
starts with the regions of all stipples placed so far considered.

Our reading of the paper, step by step (the docstring of :func:`synthesize_distribution` repeats
it with the parameters):

- One *iteration* visits the pixels in a fresh random order, skipping considered pixels. A
  visited pixel becomes considered; its flip is kept if and only if it lowers the ACE
  (strictly, by more than ``1e-12`` so rounding noise cannot accept a neutral flip). The paper
  gives no probability for accepting a worse flip (3.4.1: "otherwise, the pixel flips back"),
  so the Metropolis rule here is the zero-temperature one.
- After an accepted flip, ``D = O + R`` (3.4.2; the paper's "P = O + R" names ``D``) with
  ``O = O_min, O_avg, O_max`` with probabilities 0.1, 0.8, 0.1 and ``R`` uniform in
  ``[0, O_avg - O_min)``, ``{0}``, ``(O_avg - O_max, 0]`` respectively, so ``D`` lies in
  ``[O_min, O_max]``; the pixels at Euclidean distance ``<= D`` become considered. The disc
  is the stipple's *region* and the stipple keeps it: every pass starts with the regions of the
  stipples already placed considered (the stipple pixels themselves stay free, so a stipple can
  be flipped off). The paper says the considered mark lasts "during the current iteration" and
  that the rule serves to "avoid random selections within any stipple regions" and "maintain
  the geometrical information from the example texture"; clearing the mark at each iteration
  would let later iterations put stipples next to earlier ones (we measured O_min of 1-3 px
  against the example's 5-7 px that way), so the regions persist.
- When every pixel is considered but the synthesis holds less ink than the example ("may not
  yet have reached ... the average gray value of the example"), the iteration runs one more
  pass with ``D = O_min`` for the new stipples and the regions of the existing ones (the
  paper's fallback "we arbitrarily assign O_min to D"), so no two stipples come closer than
  O_min.
- The synthesis stops after ``iterations`` iterations (paper: 30) or after the first iteration
  that does not lower the ACE (3.4: "while the current error between them is reduced").

Written by hand: no maintained library does GLCM spin-flip synthesis. The flip loop of one pass
is a numba kernel built on :func:`paperlib.stipple.glcm.ace_change_kernel` and
:func:`~paperlib.stipple.glcm.flip_update_kernel`; all its randomness is drawn beforehand with
NumPy, so a seed fixes the texture bit for bit. The tests check the kernel against a pure
Python pass that recomputes the ACE from scratch for every candidate flip.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numba
import numpy as np

from paperlib._checks import as_generator, instance_of
from scipy.spatial import cKDTree
from skimage.measure import label, regionprops

from .spacing import nearest_neighbour_distances
from .glcm import (
    ace,
    ace_change_by_group_kernel,
    ace_change_kernel,
    _checked_bitonal,
    cooccurrence_counts,
    flip_update_kernel,
    normalized_glcms,
    offset_directions,
    pair_totals,
    paper_offsets,
)

__all__ = [
    "StippleGeometry",
    "SynthesisResult",
    "paper_radius_quantiles",
    "stipple_geometry",
    "synthesize_distribution",
]

# Probabilities of D's base offset O_min / O_max (section 3.4.2); O_avg takes the remaining 0.8.
P_MIN, P_MAX = 0.1, 0.1
#: How the stipple-region radius D may be drawn (see synthesize_distribution).
SPACINGS = ("matched", "paper")
#: Acceptance rules of a spin flip (section 3.4.1).
ACCEPTANCES = ("sum", "every_direction")
#: Steps of the matched radius quantile function (QUANTILE_STEPS + 1 knots, u = 0 .. 1).
QUANTILE_STEPS = 20
#: Corrections of the matched radius quantiles (CALIBRATION_ROUNDS + 1 trial syntheses).
CALIBRATION_ROUNDS = 3
#: Quantile of the example's nearest-neighbour distances used as the matched fallback radius.
FALLBACK_QUANTILE = 0.1
#: Share of the quantile miss corrected per round (a full step overshoots on dense tones).
CALIBRATION_STEP = 0.5
# A flip is kept only if it lowers ACE by more than this: the incremental ACE change of a
# neutral flip can come out as -1e-18 from rounding, and accepting it would be no improvement.
ACCEPT_TOLERANCE = 1e-12


# --------------------------------------------------------------------------------------------
# geometry of the example (section 3.2)


@dataclass(frozen=True)
class StippleGeometry:
    """Stipple size and nearest-neighbour offsets of an example texture (Kim et al. 2009, 3.2).

    Parameters
    ----------
    s_avg : float
        Average stipple size, in pixels (area of a connected component).
    o_min, o_avg, o_max : float
        Minimum, average and maximum distance (pixels) from a stipple centre to the centre of
        its nearest neighbour.
    count : int
        Number of stipples found.
    white_marks : bool
        True when the stipples are white marks on black (the paper's dark level).
    """

    s_avg: float
    o_min: float
    o_avg: float
    o_max: float
    count: int = 0
    white_marks: bool = False


def stipple_geometry(example, marks: str = "auto") -> StippleGeometry:
    """S_avg, O_min, O_avg and O_max of an example texture, from its connected components.

    Parameters
    ----------
    example : array_like, 2-D
        Bitonal texture, ``True`` / 1 = ink (an example stipple or distribution texture).
    marks : {"auto", "black", "white"}, optional
        Which level the stipples are. ``"black"``: ink marks on paper (light and merged levels);
        ``"white"``: paper marks on ink (dark level, section 3.2). ``"auto"`` (default) picks
        ``"white"`` when ink covers more than half of the texture.

    Returns
    -------
    StippleGeometry
        Stipples are the 8-connected components (section 3.2), their centres the component
        centroids (``skimage.measure.regionprops``), the offsets the distances from each centre
        to its nearest other centre (``scipy.spatial.cKDTree``), not periodic.

    Raises
    ------
    ValueError
        Non-bitonal input, an unknown ``marks``, or fewer than two stipples (no neighbour
        distance exists).

    References
    ----------
    Kim et al. 2009, section 3.2 (connected components with an 8-neighbourhood, centres,
    S_avg, O_min, O_max, O_avg), used by section 3.4.2.
    """
    ink = _checked_bitonal(example, "example")
    if not isinstance(marks, str) or marks not in ("auto", "black", "white"):
        raise ValueError(f"marks must be 'auto', 'black' or 'white', got {marks!r}")
    white_marks = marks == "white" or (marks == "auto" and ink.mean() > 0.5)
    stipples = label(~ink if white_marks else ink, connectivity=2)
    regions = regionprops(stipples)
    if len(regions) < 2:
        level = "white" if white_marks else "black"
        raise ValueError(f"the example has {len(regions)} {level} stipple(s): need at least 2 for neighbour offsets")
    centres = np.array([region.centroid for region in regions])
    distances, _ = cKDTree(centres).query(centres, k=2)
    nearest = distances[:, 1]
    return StippleGeometry(
        s_avg=float(np.mean([region.area for region in regions])),
        o_min=float(nearest.min()),
        o_avg=float(nearest.mean()),
        o_max=float(nearest.max()),
        count=len(regions),
        white_marks=bool(white_marks),
    )


# --------------------------------------------------------------------------------------------
# numba kernels of one pass (sections 3.4.1 and 3.4.2)


@numba.njit(cache=True)
def _stipple_radius(u, quantiles):
    """``D`` from one uniform ``u`` in [0, 1): the radius quantile function at ``u``.

    ``quantiles`` holds the quantile function of ``D`` at ``u = 0, 1/m, ..., 1`` (m + 1 values,
    non-decreasing); it is interpolated linearly in between.
    """
    position = u * (quantiles.shape[0] - 1)
    index = min(int(position), quantiles.shape[0] - 2)
    return quantiles[index] + (position - index) * (quantiles[index + 1] - quantiles[index])


@numba.njit(cache=True)
def _mark_considered(considered, y, x, radius):
    """Mark every pixel closer than ``radius`` to (y, x) (Euclidean) as considered.

    The disc is open: a stipple may sit at exactly ``radius`` from another, as the example's
    own nearest pair sits at exactly O_min (on the pixel grid many distances tie; a closed disc
    of radius O_min would forbid the example's most common distance in dense tones).
    """
    height, width = considered.shape
    reach = int(math.floor(radius))
    squared = radius * radius
    for row in range(max(0, y - reach), min(height, y + reach + 1)):
        for col in range(max(0, x - reach), min(width, x + reach + 1)):
            if (row - y) * (row - y) + (col - x) * (col - x) < squared:
                considered[row, col] = True


@numba.njit(cache=True)
def _mark_stipple_regions(considered, texture, regions, fixed_radius):
    """Start of a pass: only the stipple regions of the existing stipples are considered.

    Every ink pixel's region is the disc of its own radius ``regions[y, x]`` (``fixed_radius``
    instead when >= 0: the O_min fallback); the stipple pixels themselves stay free, so a
    stipple can still be flipped off.
    """
    considered[:, :] = False
    height, width = texture.shape
    for y in range(height):
        for x in range(width):
            if texture[y, x]:
                _mark_considered(considered, y, x, fixed_radius if fixed_radius >= 0 else regions[y, x])
    for y in range(height):
        for x in range(width):
            if texture[y, x]:
                considered[y, x] = False


@numba.njit(cache=True)
def _flip_lowers_error(texture, counts, y, x, offsets, target, totals, groups, changes):
    """The acceptance rule of 3.4.1: does flipping (y, x) lower the error?

    With one group (``changes`` of length 1) the summed ACE of eq. (5) must drop; with several,
    the error of every group of offsets (every direction) must drop, by more than
    ``ACCEPT_TOLERANCE`` each.
    """
    if changes.shape[0] == 1:
        return ace_change_kernel(texture, counts, y, x, offsets, target, totals) < -ACCEPT_TOLERANCE
    ace_change_by_group_kernel(texture, counts, y, x, offsets, target, totals, groups, changes)
    for g in range(changes.shape[0]):
        if changes[g] >= -ACCEPT_TOLERANCE:
            return False
    return True


@numba.njit(cache=True)
def _spin_flip_pass(texture, counts, offsets, target, totals, groups, changes, order, uniforms, quantiles,
                    fixed_radius, considered, regions):
    """One pass of Metropolis spin flips with considered pixels; returns (attempts, accepted).

    ``order`` is a permutation of the flat pixel indices; ``uniforms[t]`` draws ``D`` from the
    radius quantile function ``quantiles`` if the pixel ``order[t]`` is flipped;
    ``fixed_radius >= 0`` replaces the draw (the O_min fallback, or 0 when the geometric
    constraint is off). ``regions`` holds the radius ``D`` of every stipple placed so far
    (updated here); the pass starts with their regions considered (:func:`_mark_stipple_regions`).
    ``groups`` and ``changes`` select the acceptance rule (:func:`_flip_lowers_error`).
    """
    width = texture.shape[1]
    _mark_stipple_regions(considered, texture, regions, fixed_radius)
    attempts = 0
    accepted = 0
    for t in range(order.shape[0]):
        y = order[t] // width
        x = order[t] % width
        if considered[y, x]:
            continue
        attempts += 1
        considered[y, x] = True
        if _flip_lowers_error(texture, counts, y, x, offsets, target, totals, groups, changes):
            flip_update_kernel(texture, counts, y, x, offsets)
            accepted += 1
            radius = fixed_radius if fixed_radius >= 0 else _stipple_radius(uniforms[t], quantiles)
            regions[y, x] = radius if texture[y, x] else 0.0
            _mark_considered(considered, y, x, radius)
    return attempts, accepted


# --------------------------------------------------------------------------------------------
# public driver


@dataclass(frozen=True)
class SynthesisResult:
    """Outcome of :func:`synthesize_distribution`.

    Parameters
    ----------
    texture : numpy.ndarray of bool
        The synthesized distribution texture, ``True`` = ink.
    ace_history : numpy.ndarray of float, shape (iterations_run + 1,)
        ACE (eq. 5) of the seed, then after each iteration (recomputed from the counts).
    accepted_flips, attempts : numpy.ndarray of int, shape (iterations_run,)
        Flips kept and pixels tried (not considered when visited) per iteration.
    fallback_passes : numpy.ndarray of bool, shape (iterations_run,)
        Whether the iteration ran the extra smallest-radius pass of section 3.4.2.
    converged : bool
        True when the synthesis stopped because an iteration no longer lowered the ACE.
    seconds : float
        Wall-clock time of the synthesis, calibration runs included (numba compilation
        excluded once cached).
    counts : numpy.ndarray of int64, shape (k, 2, 2)
        Co-occurrence counts of ``texture`` for ``offsets``, maintained incrementally.
    offsets : numpy.ndarray of int64, shape (k, 2)
        The displacement vectors used.
    geometry : StippleGeometry or None
        The example's geometry (section 3.2), None when the constraint was off.
    spacing : str
        ``"matched"``, ``"paper"`` or ``"off"``: how the stipple-region radius D was drawn.
    acceptance : str
        ``"sum"`` or ``"every_direction"``: the acceptance rule of the spin flips.
    radius_quantiles : numpy.ndarray or None
        Quantile function of D used by the final run, at ``u = 0 .. 1`` in equal steps.
    trials : int
        Syntheses run (several with ``spacing="matched"``, which returns the best).
    """

    texture: np.ndarray
    ace_history: np.ndarray
    accepted_flips: np.ndarray
    attempts: np.ndarray
    fallback_passes: np.ndarray
    converged: bool
    seconds: float
    counts: np.ndarray
    offsets: np.ndarray
    geometry: StippleGeometry | None
    spacing: str = "paper"
    acceptance: str = "sum"
    radius_quantiles: np.ndarray | None = None
    trials: int = 1

    @property
    def final_ace(self) -> float:
        """ACE between the example and the synthesized texture at the end."""
        return float(self.ace_history[-1])


def _output_shape(size, example_shape) -> tuple[int, int]:
    """The synthesized texture's shape from ``size`` (None, an int, or (height, width))."""
    if size is None:
        return example_shape
    sides = (size, size) if np.ndim(size) == 0 else tuple(size)
    if len(sides) != 2 or not all(
        isinstance(side, (int, np.integer)) and not isinstance(side, (bool, np.bool_)) for side in sides
    ):
        raise ValueError(f"size must be an int or a (height, width) pair of ints, got {size!r}")
    if min(sides) < 2:
        raise ValueError(f"size must be at least 2 pixels per side, got {size!r}")
    return int(sides[0]), int(sides[1])


def _checked_iterations(iterations) -> int:
    if isinstance(iterations, (bool, np.bool_)) or not isinstance(iterations, (int, np.integer)):
        raise ValueError(f"iterations must be a positive integer, got {iterations!r}")
    if iterations < 1:
        raise ValueError(f"iterations must be >= 1 (paper: 30), got {iterations}")
    return int(iterations)


def _checked_geometry(geometry, example, spacing: str) -> StippleGeometry | None:
    """The geometry to use: given, measured on the example, or None (constraint off)."""
    if geometry is False:
        return None
    if geometry is None:
        try:
            return stipple_geometry(example)
        except ValueError:  # fewer than two stipples: no offsets to constrain with
            return None
    if not isinstance(geometry, StippleGeometry):
        raise ValueError(f"geometry must be None, False or a StippleGeometry, got {type(geometry).__name__}")
    if spacing != "paper":
        raise ValueError(
            f"a given geometry sets the radii of spacing='paper'; spacing={spacing!r} draws them from the "
            "example's nearest-neighbour distances: pass spacing='paper' with it"
        )
    values = (geometry.o_min, geometry.o_avg, geometry.o_max)
    if not all(math.isfinite(value) and value >= 0 for value in values):
        raise ValueError(f"geometry offsets must be finite and >= 0, got {values}")
    if not geometry.o_min <= geometry.o_avg <= geometry.o_max:
        raise ValueError(f"geometry needs O_min <= O_avg <= O_max, got {values}")
    return geometry


def _checked_choice(value, name: str, allowed: tuple) -> str:
    if not isinstance(value, str) or value not in allowed:
        raise ValueError(f"{name} must be one of {allowed}, got {value!r}")
    return value


def paper_radius_quantiles(geometry: StippleGeometry) -> np.ndarray:
    """Quantile function of the stipple-region radius D of section 3.4.2, at ``u = 0, 0.1 .. 1``.

    ``D = O + R``: with probability 0.1 ``O = O_min`` and ``R`` uniform in
    ``[0, O_avg - O_min)``, with 0.8 ``D = O_avg``, with 0.1 ``O = O_max`` and ``R`` uniform in
    ``(O_avg - O_max, 0]``. So D is uniform on ``[O_min, O_avg)`` for ``u < 0.1``, ``O_avg``
    up to ``u = 0.9`` and uniform on ``(O_avg, O_max]`` beyond: piecewise linear in ``u``,
    exact at these eleven knots.

    Parameters
    ----------
    geometry : StippleGeometry
        The example's ``O_min``, ``O_avg`` and ``O_max`` (pixels).

    Returns
    -------
    ndarray of float64, shape (11,)
        D at ``u = 0, 0.1, ..., 1``, pixels, non-decreasing.
    """
    instance_of(geometry, StippleGeometry, "geometry")
    knots = np.linspace(0.0, 1.0, 11)
    return np.interp(knots, [0.0, P_MIN, 1.0 - P_MAX, 1.0],
                     [geometry.o_min, geometry.o_avg, geometry.o_avg, geometry.o_max])


def _distance_quantiles(texture) -> np.ndarray:
    """Nearest-neighbour distance quantiles of a distribution texture at ``u = 0 .. 1``."""
    return np.quantile(nearest_neighbour_distances(texture), np.linspace(0.0, 1.0, QUANTILE_STEPS + 1))


@dataclass
class _Run:
    """One spin-flip synthesis: the state it ends in and its per-iteration records."""

    texture: np.ndarray
    counts: np.ndarray
    history: list
    accepted: list
    attempts: list
    fallbacks: list
    converged: bool


def _run_synthesis(seed_texture, target, offsets, totals, groups, quantiles, fallback, iterations, target_ink,
                   generator) -> _Run:
    """Iterations of spin-flip passes from ``seed_texture`` (section 3.4): radii D drawn from
    ``quantiles`` (None: no geometric constraint), ``fallback`` the radius of the fallback pass."""
    texture = seed_texture.copy()
    counts = cooccurrence_counts(texture, offsets)
    run = _Run(texture, counts, [ace(target, normalized_glcms(counts))], [], [], [], False)
    changes = np.zeros(int(groups.max()) + 1)
    considered = np.zeros(texture.shape, dtype=np.bool_)
    table = np.zeros(2) if quantiles is None else quantiles
    # radius D of every stipple's region; the seed texture's own stipples get the fallback's
    regions = np.where(texture, fallback, 0.0)
    for _ in range(iterations):
        # all randomness of the iteration drawn here, in a fixed order, for bit-for-bit repeats
        order = generator.permutation(texture.size).astype(np.int64)
        uniforms = generator.random(texture.size)
        fixed = 0.0 if quantiles is None else -1.0
        common = (texture, counts, offsets, target, totals, groups, changes, order, uniforms, table)
        tried, kept = _spin_flip_pass(*common, fixed, considered, regions)
        short_of_ink = quantiles is not None and kept > 0 and np.count_nonzero(texture) < target_ink
        if short_of_ink:
            more_tried, more_kept = _spin_flip_pass(*common, fallback, considered, regions)
            tried, kept = tried + more_tried, kept + more_kept
        run.accepted.append(kept)
        run.attempts.append(tried)
        run.fallbacks.append(short_of_ink)
        run.history.append(ace(target, normalized_glcms(counts)))
        if run.history[-1] >= run.history[-2]:
            run.converged = True
            break
    return run


def _matched_run(example, run_with) -> tuple[_Run, np.ndarray, int]:
    """The synthesis whose nearest-neighbour distances come closest to the example's.

    The radius quantiles start as the example's own distance quantiles; after each trial they
    move by ``CALIBRATION_STEP`` times the example's minus the trial's distance quantiles (kept
    non-decreasing and >= the example's O_min). The fallback pass uses the example's
    ``FALLBACK_QUANTILE`` distance quantile rather than its minimum, a single pair: on dense
    tones the minimum is 1 px, and a fallback at 1 px packed a fifth of the stipples against
    another (nearest-neighbour KS 0.33 against the example). Of the
    ``CALIBRATION_ROUNDS + 1`` trials, the one with the smallest mean absolute quantile
    difference is returned, with its quantiles and the number of trials run.
    """
    wanted = _distance_quantiles(example)
    fallback = float(np.quantile(nearest_neighbour_distances(example), FALLBACK_QUANTILE))
    quantiles = wanted.copy()
    best = None
    for trial in range(CALIBRATION_ROUNDS + 1):
        run = run_with(quantiles, fallback)
        if np.count_nonzero(run.texture) < 2:  # no distances to compare: nothing to calibrate
            return run, quantiles, trial + 1
        got = _distance_quantiles(run.texture)
        miss = float(np.mean(np.abs(got - wanted)))
        if best is None or miss < best[0]:
            best = (miss, run, quantiles)
        quantiles = np.maximum.accumulate(np.maximum(quantiles + CALIBRATION_STEP * (wanted - got), wanted[0]))
    return best[1], best[2], CALIBRATION_ROUNDS + 1


def synthesize_distribution(
    example,
    size=None,
    seed_texture=None,
    *,
    iterations: int = 30,
    offsets=None,
    geometry=None,
    spacing: str = "matched",
    acceptance: str = "sum",
    rng=None,
) -> SynthesisResult:
    """Synthesize a bitonal distribution texture whose GLCMs match the example's (Kim 2009, 3.4).

    Starting from the seed texture, each iteration visits the pixels in a new random order and
    skips the "considered" ones. A visited pixel becomes considered and is flipped (black <->
    white) if and only if the flip lowers the error between the example's and the synthesis'
    normalised GLCMs (``acceptance``), by more than ``1e-12``; otherwise it stays (the paper's
    Metropolis spin flip keeps improving flips only and gives no probability for worse ones,
    3.4.1). After a kept flip, the pixels within radius ``D`` of it become considered (its
    stipple region, which stays considered in later passes; ``spacing`` says how D is drawn,
    3.4.2). When all pixels are considered while the synthesis still holds less ink than the
    example, the iteration makes one more pass with the smallest radius for every region (3.4.2's
    fallback, "we arbitrarily assign O_min to D"). The synthesis stops after ``iterations``
    iterations or at the first iteration that does not lower the ACE (3.4).

    Parameters
    ----------
    example : array_like, 2-D
        Example distribution texture, bitonal, ``True`` / 1 = ink.
    size : int or (int, int), optional
        Shape of the synthesized texture; default the example's. Ignored if ``seed_texture`` is
        given (which must then agree with it).
    seed_texture : array_like, 2-D, optional
        Starting texture; default an empty white texture (3.3.2). Not modified.
    iterations : int, optional
        Maximum number of iterations, >= 1 (paper: 30).
    offsets : array_like of int, shape (k, 2), optional
        Displacements ``(dy, dx)``; default ``paper_offsets(n)`` with ``n`` the shortest side of
        the example and the synthesis: the 3 (n - 1) offsets of section 3.3.2.
    geometry : StippleGeometry, None or False, optional
        None (default): measured on the example with :func:`stipple_geometry`; if the example
        has fewer than two stipples the constraint is off. False: off (every pixel is visited
        once per iteration, plain spin flips). A StippleGeometry sets O_min, O_avg, O_max of
        ``spacing="paper"``.
    spacing : {"matched", "paper"}, optional
        How the region radius D is drawn. ``"paper"``: the rule of 3.4.2 with the example's
        O_min, O_avg, O_max (:func:`paper_radius_quantiles`). ``"matched"`` (default): D is drawn
        from a quantile function calibrated so that the synthesis' nearest-neighbour distances
        follow the example's: it starts from the example's distance quantiles, is corrected
        after each of ``CALIBRATION_ROUNDS + 1`` trial syntheses by half the quantile miss, and
        the trial closest to the example is returned (our reading of "the offset information
        is updated whenever new stipple distribution is placed into the synthesized texture").
        See Notes for why.
    acceptance : {"sum", "every_direction"}, optional
        ``"sum"`` (default): a flip is kept when the ACE of eq. (5) over all offsets drops.
        ``"every_direction"``: when the error over the offsets of every direction (horizontal,
        vertical, diagonal for the paper's offsets; :func:`~paperlib.stipple.glcm.offset_directions`)
        drops, the paper's literal "lower ... for all displacement offset vectors" (3.4.1).
    rng : None, int or numpy.random.Generator, optional
        Random source; a seed fixes the output bit for bit.

    Returns
    -------
    SynthesisResult

    Raises
    ------
    ValueError
        Non-bitonal example or seed, a seed whose shape disagrees with ``size``, a texture
        smaller than an offset (or with a side < 2), malformed offsets, ``iterations`` < 1 or not
        an integer, an invalid geometry, an unknown ``spacing`` or ``acceptance``.

    Notes
    -----
    Why ``spacing="matched"`` is the default. For a sparse distribution texture the GLCMs along
    three lines of offsets hardly constrain the spacing: without the geometric constraint the
    synthesis' nearest-neighbour distances are as far from the example's as complete spatial
    randomness (KS statistic 0.45-0.76 on our 256 x 256 tones). The spacing comes from the
    regions of 3.4.2, and the paper's rule makes them mostly ``O_avg`` wide: since a new stipple
    may not fall inside an earlier one's region, most nearest-neighbour distances end up just
    above ``O_avg``, a narrower distribution than the example's, whose *mean* is ``O_avg``
    (KS 0.33-0.44 on light and dark tones). Drawing D from calibrated quantiles keeps the rule's
    mechanism (random regions, O_min fallback) and reaches the example's distances.

    Deviation: the paper updates O_min, O_avg and O_max "whenever new stipple distribution is
    placed" without saying how; ``spacing="paper"`` keeps the example's values, ``"matched"``
    updates the whole radius distribution between trial runs. S_avg is measured but not used:
    the formula of 3.4.2 involves the offsets only.

    References
    ----------
    Kim et al. 2009, section 3.4 (stopping rule), 3.4.1 and eq. (5) (ACE, Metropolis spin
    flips, acceptance), 3.4.2 (radius D, considered pixels, O_min fallback), 3.3.2 (offsets,
    white seed).
    """
    target_texture = _checked_bitonal(example, "example")
    if min(target_texture.shape) < 2:
        raise ValueError(f"example of shape {target_texture.shape} is too small: need at least 2 x 2 pixels")
    if seed_texture is None:
        texture = np.zeros(_output_shape(size, target_texture.shape), dtype=np.bool_)
    else:
        texture = _checked_bitonal(seed_texture, "seed_texture").copy()
        if size is not None and _output_shape(size, target_texture.shape) != texture.shape:
            raise ValueError(f"seed_texture has shape {texture.shape} but size asks for {size!r}")
        if min(texture.shape) < 2:
            raise ValueError(f"seed_texture of shape {texture.shape} is too small: need at least 2 x 2 pixels")
    iterations = _checked_iterations(iterations)
    spacing = _checked_choice(spacing, "spacing", SPACINGS)
    acceptance = _checked_choice(acceptance, "acceptance", ACCEPTANCES)
    if offsets is None:
        offsets = paper_offsets(min(*target_texture.shape, *texture.shape))
    pair_totals(target_texture.shape, offsets)  # validates the offsets against both shapes
    totals = pair_totals(texture.shape, offsets).astype(np.float64)
    offsets = np.ascontiguousarray(offsets, dtype=np.int64)
    groups = offset_directions(offsets) if acceptance == "every_direction" else np.zeros(len(offsets), np.int64)
    target = np.ascontiguousarray(normalized_glcms(cooccurrence_counts(target_texture, offsets)))
    constraint = _checked_geometry(geometry, target_texture, spacing)
    generator = as_generator(rng)
    target_ink = target_texture.mean() * texture.size

    def run_with(quantiles, fallback):
        return _run_synthesis(texture, target, offsets, totals, groups, quantiles, fallback, iterations, target_ink,
                              generator)

    start = time.perf_counter()
    quantiles, trials = None, 1
    if constraint is not None and spacing == "matched":
        run, quantiles, trials = _matched_run(target_texture, run_with)
    else:
        quantiles = None if constraint is None else paper_radius_quantiles(constraint)
        run = run_with(quantiles, 0.0 if constraint is None else constraint.o_min)
    seconds = time.perf_counter() - start
    return SynthesisResult(
        texture=run.texture,
        ace_history=np.array(run.history),
        accepted_flips=np.array(run.accepted, dtype=np.int64),
        attempts=np.array(run.attempts, dtype=np.int64),
        fallback_passes=np.array(run.fallbacks, dtype=bool),
        converged=run.converged,
        seconds=seconds,
        counts=run.counts,
        offsets=offsets,
        geometry=constraint,
        spacing=spacing if constraint is not None else "off",
        acceptance=acceptance,
        radius_quantiles=quantiles,
        trials=trials,
    )
