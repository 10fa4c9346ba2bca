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

Most attempts are rejected (98-99 % at 256 x 256 and 512 x 512), so the pass decides them
without the O(k) exact ACE change: it tabulates every offset's change for the 18 possible
levels of a pixel and its two partners (refreshed after each kept flip) and, with the paper's
offsets, sums them along the pixel's row, column and diagonal from prefix sums plus one
correction per ink partner. That sum is in another float order than the exact one, so it
decides only when it is farther from the threshold than a proven bound of the rounding
difference; otherwise the exact kernel decides. The accepted flips, hence the textures, are the
exact kernel's bit for bit (tested on every attempt of passes at several tones and shapes);
512 x 512 with the paper's offsets went from 16.6 s to about 1.5-2 s.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numba
import numpy as np

from paperlib._checks import as_generator, budget, check_budget, instance_of
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


# --------------------------------------------------------------------------------------------
# fast acceptance test (section 3.4.1): a table of per-offset error changes
#
# A flip at p changes, for offset m, the error of eq. (5) by an amount that depends only on
# the counts of offset m and on three levels: p's own and those of p - o_m and p + o_m (each
# 0, 1 or outside the texture). The counts change only when a flip is kept (1-2 % of the
# attempts at 256 x 256 and 512 x 512), so every pass tabulates the 2 x 9 possible changes of
# every offset and refreshes the table after each kept flip; a rejected attempt then costs one
# table look-up per offset instead of four residuals and a division.
#
# Bit-identity with glcm.ace_change_kernel: its decision is ``fl(S / k) < -ACCEPT_TOLERANCE``
# with ``S`` its left-to-right float sum of the k per-offset changes. The table holds those
# changes to within 1.5 eps (a product with the reciprocal of the pair total instead of the
# division), and the fast tests sum them in another order (several accumulators, prefix sums),
# so their sum can differ from ``S`` by rounding. They
# decide only when they are farther than a rigorous bound of that difference from the
# threshold (see _decision_margin); in between the exact kernel decides. The decisions, hence
# the textures, are those of the plain kernel bit for bit.

# Index of an offset's configuration in the table: first * 3 + second, with first and second
# the levels of p - o and p + o (0, 1, or 2 = outside the texture, no pair); the level of p
# selects the table's first axis.
_OUTSIDE = 2


@numba.njit(cache=True)
def _fill_change_table(counts, target, totals, table):
    """``table[v, m, first * 3 + second]``: offset m's error change if a pixel of level v flips.

    The float operations are those of ``glcm._offset_error_change``: residuals
    ``count - target * total``, entry changes ``|r + delta| - |r|`` (``entries[e, delta + 2]``,
    delta in -2 .. 2) summed as ``((e00 + e01) + e10) + e11``; only the deltas come from the
    configuration instead of the texture. The division by the pair total of
    ``glcm._ace_change_kernel`` is a product with its reciprocal here (one division per offset
    instead of 18: the refresh after every kept flip costs 40 % less), which moves a change by at
    most 1.5 eps of its size; :func:`_decision_margin` covers it.
    """
    entries = np.empty((4, 5))
    for m in range(counts.shape[0]):
        total = totals[m]
        reciprocal = 1.0 / total
        for e in range(4):
            residual = counts[m, e >> 1, e & 1] - target[m, e >> 1, e & 1] * total
            for delta in range(-2, 3):
                entries[e, delta + 2] = abs(residual + delta) - abs(residual)
        for v in range(2):
            sign = -1 if v != 0 else 1
            for f in range(3):
                first_0 = 1 if f == 0 else 0
                first_1 = 1 if f == 1 else 0
                for s in range(3):
                    second_0 = 1 if s == 0 else 0
                    second_1 = 1 if s == 1 else 0
                    term = entries[0, 2 - sign * (first_0 + second_0)] + entries[1, 2 + sign * (first_0 - second_1)]
                    term = term + entries[2, 2 + sign * (second_0 - first_1)] + entries[3, 2 + sign * (first_1 + second_1)]
                    table[v, m, f * 3 + s] = term * reciprocal


@numba.njit(cache=True)
def _decision_margin(totals):
    """How far from the threshold a fast sum must be for its decision to be the exact kernel's.

    Every tabulated change is at most ``A_m = 8 / total_m`` in size (four entries, each moved by
    at most 2 counts, divided by the pair total); let ``A`` be their sum over the k offsets.
    Two float sums of the same k terms in any orders differ by less than ``2 k eps A``, the
    prefix sums and the differences of :func:`_line_decision` add at most as much again; the
    rounding of ``target * total`` (were it fused into the subtraction or not) moves a change by
    at most ``40 eps`` and the product with the reciprocal of the total by at most
    ``1.5 eps A_m``. The margin takes ``16 k eps A`` for the sums and the reciprocal (over twice
    what they need), ``64 k eps`` for the fused rounding and 1 % of the threshold
    ``k ACCEPT_TOLERANCE``, which also covers the final division by k and the comparison.
    """
    eps = 2.220446049250313e-16
    k = totals.shape[0]
    magnitude = 0.0
    for m in range(k):
        magnitude += 8.0 / totals[m]
    return 16.0 * k * eps * magnitude + 64.0 * k * eps + 0.01 * ACCEPT_TOLERANCE * k


@numba.njit(cache=True)
def _fast_flip_decision(texture, y, x, offsets, table, margin):
    """Whether flipping (y, x) lowers the ACE: 1 yes, 0 no, -1 undecided (too close to call).

    Sums the tabulated changes of the pixel's configurations with four accumulators and
    compares the sum with the threshold ``-ACCEPT_TOLERANCE * k`` (the ACE change is the sum
    divided by k), ``margin`` away from it (:func:`_decision_margin`).
    """
    height, width = texture.shape
    k = offsets.shape[0]
    row = table[1 if texture[y, x] != 0 else 0]
    acc_0 = 0.0
    acc_1 = 0.0
    acc_2 = 0.0
    acc_3 = 0.0
    for m in range(k):
        dy, dx = offsets[m, 0], offsets[m, 1]
        py, px = y - dy, x - dx
        first = _OUTSIDE
        if 0 <= py < height and 0 <= px < width:
            first = 1 if texture[py, px] != 0 else 0
        qy, qx = y + dy, x + dx
        second = _OUTSIDE
        if 0 <= qy < height and 0 <= qx < width:
            second = 1 if texture[qy, qx] != 0 else 0
        value = row[m, first * 3 + second]
        # four independent sums: the float additions need not wait for one another
        lane = m & 3
        if lane == 0:
            acc_0 += value
        elif lane == 1:
            acc_1 += value
        elif lane == 2:
            acc_2 += value
        else:
            acc_3 += value
    return _decided((acc_0 + acc_1) + (acc_2 + acc_3), -ACCEPT_TOLERANCE * k, margin)


@numba.njit(cache=True)
def _decided(total, threshold, margin):
    """1 when ``total`` is surely below ``threshold``, 0 surely not, -1 within ``margin``."""
    if total >= threshold + margin:
        return 0
    if total <= threshold - margin:
        return 1
    return -1


# --------------------------------------------------------------------------------------------
# fast acceptance test for the paper's offsets: sums along the three lines through p
#
# With the offsets of section 3.3.2 (horizontal, vertical and left-down diagonal, lengths
# 1 .. L), the partners p - o and p + o of every offset of one block lie on one line through p.
# Were every partner paper, the block's sum would be a difference of prefix sums of the
# tabulated changes of its "paper" configurations (both partners paper, or one outside the
# texture); each ink partner then corrects one offset. A pixel's test costs the ink on its
# three lines plus a scan of their bits 64 pixels at a time, instead of 3 L look-ups: at 512 x 512 the
# distribution textures hold about 2 % ink.



@numba.njit(cache=True)
def _paper_block_length(offsets):
    """L when ``offsets`` are ``paper_offsets(L + 1)`` (three blocks of lengths 1 .. L), else 0."""
    k = offsets.shape[0]
    if k % 3 != 0:
        return 0
    length = k // 3
    for d in range(1, length + 1):
        if not (offsets[d - 1, 0] == 0 and offsets[d - 1, 1] == d and offsets[length + d - 1, 0] == d
                and offsets[length + d - 1, 1] == 0 and offsets[2 * length + d - 1, 0] == d
                and offsets[2 * length + d - 1, 1] == -d):
            return 0
    return length


@numba.njit(cache=True)
def _line_of(block, y, x, height, width):
    """Line number, position of (y, x) on it and the first and last positions of the line.

    Block 0 (offsets (0, d)): row y, position x. Block 1 ((d, 0)): column x, position y.
    Block 2 ((d, -d)): anti-diagonal y + x, position y (its pixel at position u is
    (u, y + x - u)).
    """
    if block == 0:
        return y, x, 0, width - 1
    if block == 1:
        return height + x, y, 0, height - 1
    return height + width + y + x, y, max(0, y + x - width + 1), min(height - 1, y + x)


@numba.njit(cache=True)
def _set_line_pixel(line_bytes, line_bits, stride, words_per_line, height, width, y, x, value):
    """Write pixel (y, x) (``value`` 0 or 1) into the line copies of the texture: its row, column
    and anti-diagonal, as bytes (``stride`` per line, to read a partner) and as bits
    (``words_per_line`` uint64 per line, to find the ink 64 pixels at a time)."""
    for block in range(3):
        line, position, _, _ = _line_of(block, y, x, height, width)
        line_bytes[line * stride + position] = value
        word = line * words_per_line + (position >> 6)
        bit = np.uint64(1) << np.uint64(position & 63)
        if value:
            line_bits[word] |= bit
        else:
            line_bits[word] &= ~bit


# Index of the lowest set bit of a uint64 w: _BIT_INDEX[((w & -w) * _DE_BRUIJN) >> 58].
_DE_BRUIJN = np.uint64(0x03F79D71B4CB0A89)
_BIT_INDEX = np.array([0, 1, 48, 2, 57, 49, 28, 3, 61, 58, 50, 42, 38, 29, 17, 4, 62, 55, 59, 36, 53, 51, 43, 22,
                       45, 39, 33, 30, 24, 18, 12, 5, 63, 47, 56, 27, 60, 41, 37, 16, 54, 35, 52, 21, 44, 32, 23, 11,
                       46, 26, 40, 15, 34, 20, 31, 10, 25, 14, 19, 9, 13, 8, 7, 6], dtype=np.int64)


@numba.njit(cache=True)
def _fill_prefix_sums(table, length, prefix):
    """``prefix[v, c, b, d]``: sum of the changes of offsets 1 .. d of block b in paper configuration c.

    c = 0: both partners paper; 1: second outside the texture; 2: first outside (both outside
    changes nothing).
    """
    for v in range(2):
        for c in range(3):
            config = 0 if c == 0 else (_OUTSIDE if c == 1 else _OUTSIDE * 3)
            for block in range(3):
                running = 0.0
                prefix[v, c, block, 0] = 0.0
                for d in range(1, length + 1):
                    running += table[v, block * length + d - 1, config]
                    prefix[v, c, block, d] = running


@numba.njit(cache=True)
def _line_decision(line_bytes, line_bits, stride, words_per_line, height, width, y, x, level, length, table, prefix,
                   margin):
    """:func:`_fast_flip_decision` for the paper's offsets (1 yes, 0 no, -1 undecided).

    Per block: the prefix sums of the paper configurations up to where a partner leaves the
    texture, then, for each ink partner found on the line (:func:`_set_line_pixel`), its
    offset's change minus the paper configuration's. The float sum is in another order than
    the exact kernel's, hence the margin (see :func:`_decision_margin`).
    """
    total = 0.0
    row = table[level]
    one_bit = np.uint64(1)
    for block in range(3):
        line, here, first_position, last_position = _line_of(block, y, x, height, width)
        first_inside = here - first_position  # p - o inside the texture iff d <= first_inside
        second_inside = last_position - here  # p + o inside iff d <= second_inside
        both = min(first_inside, second_inside, length)
        one = min(max(first_inside, second_inside), length)
        total += prefix[level, 0, block, both]
        if one > both:
            c = 1 if first_inside > second_inside else 2
            total += prefix[level, c, block, one] - prefix[level, c, block, both]
        start = line * stride
        low = max(first_position, here - length)
        high = min(last_position, here + length)
        base = block * length - 1
        for word in range(low >> 6, (high >> 6) + 1):
            bits = line_bits[line * words_per_line + word]
            if word == low >> 6:  # drop the positions before low
                bits &= ~((one_bit << np.uint64(low & 63)) - one_bit)
            if word == high >> 6 and (high & 63) != 63:  # and after high
                bits &= (one_bit << np.uint64((high & 63) + 1)) - one_bit
            while bits != 0:
                lowest = bits & (~bits + one_bit)
                bits ^= lowest
                position = word * 64 + _BIT_INDEX[(lowest * _DE_BRUIJN) >> np.uint64(58)]
                if position == here:
                    continue
                if position < here:  # ink first partner of offset d
                    d = here - position
                    if d <= second_inside:
                        second = 1 if line_bytes[start + here + d] != 0 else 0
                        total += row[base + d, 3 + second] - row[base + d, 0]
                    else:
                        total += row[base + d, 3 + _OUTSIDE] - row[base + d, _OUTSIDE]
                else:  # ink second partner of offset d
                    d = position - here
                    if d <= first_inside:
                        if line_bytes[start + here - d] == 0:  # both ink: counted with the first
                            total += row[base + d, 1] - row[base + d, 0]
                    else:
                        total += row[base + d, _OUTSIDE * 3 + 1] - row[base + d, _OUTSIDE * 3]
    return _decided(total, -ACCEPT_TOLERANCE * 3 * length, margin)

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
    ``groups`` and ``changes`` select the acceptance rule (:func:`_flip_lowers_error`). With one
    group (the ACE of eq. 5) the rule is evaluated by :func:`_fast_flip_decision` on a table of
    per-offset changes, refreshed after every kept flip, and by :func:`_flip_lowers_error` when
    the fast test cannot decide: the same decisions, so the same texture bit for bit.
    """
    width = texture.shape[1]
    k = offsets.shape[0]
    _mark_stipple_regions(considered, texture, regions, fixed_radius)
    fast = changes.shape[0] == 1
    table = np.empty((2, k if fast else 0, 9))
    margin = _decision_margin(totals)
    if fast:
        _fill_change_table(counts, target, totals, table)
    # the paper's offsets: the texture's rows, columns and anti-diagonals as byte lines
    height = texture.shape[0]
    length = _paper_block_length(offsets) if fast else 0
    prefix = np.zeros((2, 3, 3, length + 1))
    stride = max(height, width)
    words_per_line = (stride + 63) // 64
    lines = 2 * (height + width) - 1 if length > 0 else 0
    line_bytes = np.zeros(lines * stride, dtype=np.uint8)
    line_bits = np.zeros(lines * words_per_line, dtype=np.uint64)
    if length > 0:
        _fill_prefix_sums(table, length, prefix)
        for row in range(height):
            for col in range(width):
                if texture[row, col]:
                    _set_line_pixel(line_bytes, line_bits, stride, words_per_line, height, width, row, col, 1)
    attempts = 0
    accepted = 0
    for t in range(order.shape[0]):
        y = order[t] // width
        x = order[t] % width
        if considered[y, x]:
            continue
        attempts += 1
        considered[y, x] = True
        if fast:
            if length > 0:
                level = 1 if texture[y, x] != 0 else 0
                decision = _line_decision(line_bytes, line_bits, stride, words_per_line, height, width, y, x, level,
                                          length, table, prefix, margin)
            else:
                decision = _fast_flip_decision(texture, y, x, offsets, table, margin)
            if decision < 0:  # too close to the threshold for the reordered sum: the exact rule
                keep = _flip_lowers_error(texture, counts, y, x, offsets, target, totals, groups, changes)
            else:
                keep = decision == 1
        else:
            keep = _flip_lowers_error(texture, counts, y, x, offsets, target, totals, groups, changes)
        if keep:
            flip_update_kernel(texture, counts, y, x, offsets)
            if fast:  # every offset's counts moved: its changes with them
                _fill_change_table(counts, target, totals, table)
                if length > 0:
                    _fill_prefix_sums(table, length, prefix)
                    _set_line_pixel(line_bytes, line_bits, stride, words_per_line, height, width, y, x,
                                    1 if texture[y, x] else 0)
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


#: Default budget of :func:`synthesize_distribution`: the most pixels of the synthesized texture (2**24, a
#: 4096 x 4096 texture; the paper's are 256 x 256). Raise it with the ``max_pixels`` keyword.
MAX_SYNTHESIS_PIXELS = 2**24


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
    max_pixels: int = MAX_SYNTHESIS_PIXELS,
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
    max_pixels : int, optional
        Budget: the most pixels of the synthesized texture (default :data:`MAX_SYNTHESIS_PIXELS`,
        2**24, a 4096 x 4096 texture), checked before anything is allocated.

    Returns
    -------
    SynthesisResult

    Raises
    ------
    ValueError
        Non-bitonal example or seed, a seed whose shape disagrees with ``size``, a texture
        smaller than an offset (or with a side < 2) or larger than ``max_pixels``, malformed
        offsets, ``iterations`` < 1 or not an integer, an invalid geometry, an unknown ``spacing``
        or ``acceptance``.

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
        shape = _output_shape(size, target_texture.shape)
        check_budget(shape[0] * shape[1], budget(max_pixels, "max_pixels"), "max_pixels", "texture pixels")
        texture = np.zeros(shape, dtype=np.bool_)
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
