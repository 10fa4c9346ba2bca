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
from scipy.spatial import cKDTree
from skimage.measure import label, regionprops

from .glcm import (
    ace,
    ace_change_kernel,
    check_bitonal,
    cooccurrence_counts,
    flip_update_kernel,
    normalized_glcms,
    pair_totals,
    paper_offsets,
)

__all__ = ["StippleGeometry", "SynthesisResult", "stipple_geometry", "synthesize_distribution"]

# Probabilities of D's base offset O_min / O_max (section 3.4.2); O_avg takes the remaining 0.8.
P_MIN, P_MAX = 0.1, 0.1
# A flip is kept only if it lowers ACE by more than this: the incremental ACE change of a
# neutral flip can come out as -1e-18 from rounding, and accepting it would be no improvement.
ACCEPT_TOLERANCE = 1e-12


# --------------------------------------------------------------------------------------------
# geometry of the example (section 3.2)


@dataclass(frozen=True)
class StippleGeometry:
    """Stipple size and nearest-neighbour offsets of an example texture (Kim et al. 2009, 3.2).

    Attributes
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
    ink = check_bitonal(example)
    if marks not in ("auto", "black", "white"):
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
def _stipple_radius(choice, spread, o_min, o_avg, o_max):
    """``D = O + R`` of section 3.4.2 from two uniforms in [0, 1)."""
    if choice < P_MIN:
        return o_min + spread * (o_avg - o_min)
    if choice < P_MIN + P_MAX:
        return o_max + spread * (o_avg - o_max)
    return o_avg


@numba.njit(cache=True)
def _mark_considered(considered, y, x, radius):
    """Mark every pixel within Euclidean distance ``radius`` of (y, x) as considered."""
    height, width = considered.shape
    reach = int(math.floor(radius))
    squared = radius * radius
    for row in range(max(0, y - reach), min(height, y + reach + 1)):
        for col in range(max(0, x - reach), min(width, x + reach + 1)):
            if (row - y) * (row - y) + (col - x) * (col - x) <= squared:
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
def _spin_flip_pass(texture, counts, offsets, target, totals, order, choices, spreads, radii, fixed_radius,
                    considered, regions):
    """One pass of Metropolis spin flips with considered pixels; returns (attempts, accepted).

    ``order`` is a permutation of the flat pixel indices; ``choices[t]`` and ``spreads[t]`` are
    the uniforms that draw ``D`` if the pixel ``order[t]`` is flipped; ``radii`` holds
    ``(O_min, O_avg, O_max)``; ``fixed_radius >= 0`` replaces the draw (the O_min fallback, or
    0 when the geometric constraint is off). ``regions`` holds the radius ``D`` of every
    stipple placed so far (updated here); the pass starts with their regions considered
    (:func:`_mark_stipple_regions`).
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
        if ace_change_kernel(texture, counts, y, x, offsets, target, totals) < -ACCEPT_TOLERANCE:
            flip_update_kernel(texture, counts, y, x, offsets)
            accepted += 1
            radius = fixed_radius
            if radius < 0:
                radius = _stipple_radius(choices[t], spreads[t], radii[0], radii[1], radii[2])
            regions[y, x] = radius if texture[y, x] else 0.0
            _mark_considered(considered, y, x, radius)
    return attempts, accepted


# --------------------------------------------------------------------------------------------
# public driver


@dataclass(frozen=True)
class SynthesisResult:
    """Outcome of :func:`synthesize_distribution`.

    Attributes
    ----------
    texture : numpy.ndarray of bool
        The synthesized distribution texture, ``True`` = ink.
    ace_history : numpy.ndarray of float, shape (iterations_run + 1,)
        ACE (eq. 5) of the seed, then after each iteration (recomputed from the counts).
    accepted_flips, attempts : numpy.ndarray of int, shape (iterations_run,)
        Flips kept and pixels tried (not considered when visited) per iteration.
    fallback_passes : numpy.ndarray of bool, shape (iterations_run,)
        Whether the iteration ran the extra ``D = O_min`` pass of section 3.4.2.
    converged : bool
        True when the synthesis stopped because an iteration no longer lowered the ACE.
    seconds : float
        Wall-clock time of the synthesis (numba compilation excluded once cached).
    counts : numpy.ndarray of int64, shape (k, 2, 2)
        Co-occurrence counts of ``texture`` for ``offsets``, maintained incrementally.
    offsets : numpy.ndarray of int64, shape (k, 2)
        The displacement vectors used.
    geometry : StippleGeometry or None
        The geometric constraint used, None when it was off.
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


def _checked_geometry(geometry, example) -> StippleGeometry | None:
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
    values = (geometry.o_min, geometry.o_avg, geometry.o_max)
    if not all(math.isfinite(value) and value >= 0 for value in values):
        raise ValueError(f"geometry offsets must be finite and >= 0, got {values}")
    if not geometry.o_min <= geometry.o_avg <= geometry.o_max:
        raise ValueError(f"geometry needs O_min <= O_avg <= O_max, got {values}")
    return geometry


def synthesize_distribution(
    example,
    size=None,
    seed_texture=None,
    *,
    iterations: int = 30,
    offsets=None,
    geometry=None,
    rng=None,
) -> SynthesisResult:
    """Synthesize a bitonal distribution texture whose GLCMs match the example's (Kim 2009, 3.4).

    Starting from the seed texture, each iteration visits the pixels in a new random order and
    skips the "considered" ones. A visited pixel becomes considered and is flipped (black <->
    white) if and only if the flip lowers the ACE (eq. 5) between the example's and the
    synthesis' normalised GLCMs over all offsets, by more than ``1e-12``; otherwise it stays
    (the paper's Metropolis spin flip keeps improving flips only and gives no probability for
    worse ones, 3.4.1). After a kept flip, the pixels within radius ``D`` of it become
    considered (its stipple region, which stays considered in later passes), ``D = O + R`` with ``O`` = O_min / O_avg / O_max with probabilities
    0.1 / 0.8 / 0.1 and ``R`` uniform in ``[0, O_avg - O_min)`` / ``{0}`` /
    ``(O_avg - O_max, 0]`` (3.4.2). When all pixels are considered while the synthesis still
    holds less ink than the example, the iteration makes one more pass with ``D = O_min``
    for every region (3.4.2's fallback). The synthesis stops after ``iterations`` iterations or at the first
    iteration that does not lower the ACE (3.4).

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
        The geometric constraint of 3.4.2. None (default): measured on the example with
        :func:`stipple_geometry`; if the example has fewer than two stipples the constraint is
        off. False: off (every pixel is visited once per iteration, plain spin flips).
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
        an integer, an invalid geometry.

    Notes
    -----
    Deviation: the paper updates O_min, O_avg and O_max "whenever new stipple distribution is
    placed into the synthesized texture" without saying how; we keep the example's values,
    the target the constraint is meant to maintain. S_avg is measured but not used: the
    formula of 3.4.2 involves the offsets only.

    References
    ----------
    Kim et al. 2009, section 3.4 (stopping rule), 3.4.1 and eq. (5) (ACE, Metropolis spin
    flips), 3.4.2 (radius D, considered pixels, O_min fallback), 3.3.2 (offsets, white seed).
    """
    target_texture = check_bitonal(example)
    if min(target_texture.shape) < 2:
        raise ValueError(f"example of shape {target_texture.shape} is too small: need at least 2 x 2 pixels")
    if seed_texture is None:
        texture = np.zeros(_output_shape(size, target_texture.shape), dtype=np.bool_)
    else:
        texture = check_bitonal(seed_texture).copy()
        if size is not None and _output_shape(size, target_texture.shape) != texture.shape:
            raise ValueError(f"seed_texture has shape {texture.shape} but size asks for {size!r}")
        if min(texture.shape) < 2:
            raise ValueError(f"seed_texture of shape {texture.shape} is too small: need at least 2 x 2 pixels")
    iterations = _checked_iterations(iterations)
    if offsets is None:
        offsets = paper_offsets(min(*target_texture.shape, *texture.shape))
    pair_totals(target_texture.shape, offsets)  # validates the offsets against both shapes
    totals = pair_totals(texture.shape, offsets).astype(np.float64)
    offsets = np.ascontiguousarray(offsets, dtype=np.int64)
    target = np.ascontiguousarray(normalized_glcms(cooccurrence_counts(target_texture, offsets)))
    constraint = _checked_geometry(geometry, target_texture)
    generator = np.random.default_rng(rng)

    start = time.perf_counter()
    counts = cooccurrence_counts(texture, offsets)
    history = [ace(target, normalized_glcms(counts))]
    accepted, attempts, fallbacks = [], [], []
    target_ink = target_texture.mean() * texture.size
    radii = np.zeros(3) if constraint is None else np.array([constraint.o_min, constraint.o_avg, constraint.o_max])
    considered = np.zeros(texture.shape, dtype=np.bool_)
    # radius D of every stipple's region; the seed texture's own stipples get O_min
    regions = np.where(texture, radii[0], 0.0)
    converged = False
    for _ in range(iterations):
        # all randomness of the iteration drawn here, in a fixed order, for bit-for-bit repeats
        order = generator.permutation(texture.size).astype(np.int64)
        choices, spreads = generator.random(texture.size), generator.random(texture.size)
        fixed = 0.0 if constraint is None else -1.0
        tried, kept = _spin_flip_pass(
            texture, counts, offsets, target, totals, order, choices, spreads, radii, fixed, considered, regions
        )
        fallback = constraint is not None and kept > 0 and np.count_nonzero(texture) < target_ink
        if fallback:
            more_tried, more_kept = _spin_flip_pass(
                texture, counts, offsets, target, totals, order, choices, spreads, radii, constraint.o_min, considered,
                regions,
            )
            tried, kept = tried + more_tried, kept + more_kept
        accepted.append(kept)
        attempts.append(tried)
        fallbacks.append(fallback)
        history.append(ace(target, normalized_glcms(counts)))
        if history[-1] >= history[-2]:
            converged = True
            break
    seconds = time.perf_counter() - start
    return SynthesisResult(
        texture=texture,
        ace_history=np.array(history),
        accepted_flips=np.array(accepted, dtype=np.int64),
        attempts=np.array(attempts, dtype=np.int64),
        fallback_passes=np.array(fallbacks, dtype=bool),
        converged=converged,
        seconds=seconds,
        counts=counts,
        offsets=offsets,
        geometry=constraint,
    )
