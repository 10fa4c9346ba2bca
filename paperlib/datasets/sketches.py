"""Synthetic leaf outlines and hand-drawn-like sketch curves (Simhon & Dudek 2001's inputs).

Simhon & Dudek (2001) train their Markov model on two classes of closed curves: 40 country borders
(we load real ones, :func:`paperlib.datasets.coastlines`) and "14 leaf outlines", a class "that
exhibits large-scale properties" (section 3.1, Figure 5), and they steer it with rough hand-drawn
sketches (Figures 3, 4 and 6). No installed package ships real leaf contours as coordinates, nor
anyone's hand-drawn curves, so the seeded generators here make SYNTHETIC stand-ins:

======================================  ==========================================================
generator                               what it makes (paper)
======================================  ==========================================================
:func:`leaf_outline`                    one leaf outline of a named kind (Figure 5)
:func:`leaf_outlines`                   the training class: ``n`` outlines cycling over
                                        :data:`LEAF_KINDS` (Figures 5 and 6)
:func:`hand_drawn_curve`                a smooth random blob or stroke with a small hand tremor,
                                        standing for a user's sketch (Figures 3, 4 and 6)
======================================  ==========================================================

Coarse sketches of real coastlines are not made here: the method's own low-pass filter makes them.

Leaf outlines
-------------
A leaf is built in *leaf coordinates*: the base (where the petiole joins the blade) at the origin,
the tip at ``(0, 1)``, the midrib along the ``y`` axis, so the leaf's length is 1. Five kinds imitate
five common leaf forms; each has features at fixed places along the outline (the petiole notch at the
base, the tip, the lobes), which is what makes the class "large-scale":

==============  ==========================================================  ==============
kind            large-scale structure (seeded ranges)                       imitates
==============  ==========================================================  ==============
``ovate``       egg-shaped, widest at 0.36-0.44 of the length, width        beech, birch,
                0.5-0.65, rounded base, acute tip; 13-19 teeth a side,      elm
                0.010-0.016 deep
``lanceolate``  long and narrow (width 0.17-0.23, widest at 0.42-0.5),      willow, peach
                narrow base, long tapering tip; 24-34 fine teeth a side,
                0.004-0.007 deep
``lobed``       obovate (widest at 0.55-0.65, width 0.52-0.62) with 4-5     white oak
                rounded, forward-leaning lobes a side, the sinuses cutting
                about 45-75 % of the way in; no teeth
``palmate``     five pointed lobes radiating from the petiole (middle, two  maple
                lateral at 52-62 degrees, two basal at 110-125 degrees),
                each lobe with one or two teeth a side, a flat notch at
                the petiole
``cordate``     broad heart: two rounded basal lobes around a deep sinus    linden,
                at the petiole, a drawn-out tip; 11-15 shallow teeth a      redbud
                side, 0.006-0.010 deep
==============  ==========================================================  ==============

Widths (of the smooth blade, before its teeth) and tooth depths are in units of the leaf's length.

*Construction.* A smooth, left-right symmetric blade is drawn first: for ovate, lanceolate and lobed
leaves as a half-width profile ``w(y) = W (y / m)^a ((1 - y) / (1 - m))^b`` over the midrib (``a``
shapes the base, ``b`` the tip, ``m = a / (a + b)`` is the widest place, ``W`` the half-width there);
for palmate and cordate leaves as a polar radius ``r(psi)`` around a point of the midrib (a soft
maximum of pointed lobes ``L exp(-|psi - psi_k| / w_k)`` and narrower side teeth, or an egg with a
drawn-out tip and a notch at the base). The margin is then cut along a fixed fan of rays (below):
lobes scale the distance to the fan, teeth push the margin out by a sawtooth of the arc-length
position (a rounded back and a pointed crest leaning towards the tip, as serrate teeth do), fading
out near the base and the tip, each tooth with its own seeded depth (+-20 %) on each side, and a
smooth seeded asymmetry (a relative change ``sin(2 pi s)^2 sum_k A_k sin(2 pi k s)`` of the
distance to the fan, ``s`` the arc-length position, ``k = 1..3``, ``|A_k| <= 0.02``, flat zero at
the base and the tip) breaks the symmetry a little as in real leaves. The outline is finally scaled
back to length 1 and resampled at equal arc length (:func:`paperlib.geometry.resample_closed_curve`),
starting at the base and running counter-clockwise, so that arc-length position ``t`` marks the same
feature on every leaf: ``t = 0`` the petiole, ``t`` near 0.5 the tip (within 0.03: the two halves
differ by the asymmetry and by their teeth and lobes).

*Why every outline is simple.* Each blade is built inside a *fan* around an axis segment from
``(0, y1)`` to ``(0, y2)`` (``y1 <= y2``, around the widest place; a single point for palmate and
cordate leaves): a point ``p`` is seen from its nearest point ``o(p)`` of that segment, so rays leave
the segment horizontally between ``y1`` and ``y2`` and radially from its ends beyond. These rays
never cross, and the blade meets each of them once (checked when it is built): the outline is a graph
over the fan. Lobes, teeth and asymmetry move each point along its own ray by a positive factor, so
the outline stays a graph, and so does any polygon through points taken along it in order (each
chord stays in the convex region between its two end rays, as long as no chord spans half the fan,
which no resampling at ``n_points >= 16`` comes near). Hence every outline is a simple closed curve;
the tests check it with shapely for many seeds and resolutions.

Hand-drawn curves
-----------------
:func:`hand_drawn_curve` draws what a user sketching a coastline or a leaf would: a smooth closed blob
or a smooth open stroke, with a small hand tremor.

- A blob is ``r(theta) = 1 + sum_k a_k sin(k theta + phi_k)`` over harmonics ``k = 2..5`` with
  amplitudes ``U(0.5, 1.5) / k`` scaled to the RMS ``wobble`` and random phases (shrunk, if need
  be, so the radius stays above 0.3): star-shaped around its centre, hence simple.
- A stroke follows a heading ``h(s) = sum_k a_k sin(pi k s + phi_k)`` over harmonics ``k = 1..4`` of
  its arc length ``s`` (amplitudes ``U(0.5, 1.5) / k``, centred, scaled to the RMS ``wobble`` in
  radians) and squashed to stay within 80 degrees of its mean direction: it never turns back, so its
  projection on that direction is strictly monotone and it cannot cross itself.
- The tremor is a smooth random perturbation of harmonics 6-30 with amplitudes ``1 / k`` (wiggles
  about 7-37 % of the size long): radial, relative to the radius, for a blob; sideways for a stroke,
  added to the heading as the slope of the sideways displacement, before the squashing. Its RMS
  displacement is about ``tremor * size``.

*Randomness.* ``rng`` is ``None``, an ``int`` seed or a :class:`numpy.random.Generator`; a seed fixes
the output bit for bit.

Written by hand: no library generates leaf outlines or sketches.

References
----------
Simhon, S., Dudek, G. (2001). On the elaboration of hand-drawn sketches. Section 3.1 (training on
"14 leaf outlines", a class with large-scale structure whose "features ... are well localized in
time", i.e. in arc length), Figure 5 (samples of the leaf training set), Figures 3, 4 and 6 (hand-drawn
sketches, left).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from paperlib._checks import as_generator, budget, check_budget, positive_number
from paperlib.geometry import resample_closed_curve, resample_open_curve

__all__ = ["LEAF_KINDS", "MAX_TREMOR", "MAX_WOBBLE", "hand_drawn_curve", "leaf_outline", "leaf_outlines"]

#: The leaf kinds, in the order :func:`leaf_outlines` cycles through them.
LEAF_KINDS = ("ovate", "lanceolate", "lobed", "palmate", "cordate")

#: Largest accepted ``tremor`` of :func:`hand_drawn_curve` (a fraction of its size): beyond it the
#: wiggles could push a blob's radius through zero; 1.5 % of the size is already a very shaky hand.
MAX_TREMOR = 0.015

#: Fewest points accepted for an output curve.
MIN_POINTS = 16

# Samples of the smooth blade per half-outline, before the final resampling: fine enough that the
# finest teeth (lanceolate, about 0.03 apart) get dozens of samples each.
_HALF_SAMPLES = 2048


# Harmonics of the hand tremor (wiggles per closed curve or per stroke) and of a sketch's large-scale
# shape (closed blobs start at 2: harmonic 1 would only shift the blob).
_TREMOR_HARMONICS = np.arange(6, 31)
_BLOB_HARMONICS = np.arange(2, 6)
_STROKE_HARMONICS = np.arange(1, 5)
# A stroke's tremor harmonics are those of a blob whose perimeter is this many stroke lengths: a circle's
# perimeter is 2.2 times its bounding diagonal, so tremor wiggles are equally long on blobs and strokes.
_STROKE_TREMOR_SPAN = 2.2
# A stroke's heading stays within this angle (80 degrees) of its mean direction, so it never turns back.
_MAX_HEADING = math.radians(80.0)

#: Largest accepted ``wobble`` of :func:`hand_drawn_curve` (RMS of a blob's relative radius or of a
#: stroke's heading in radians); with it and ``MAX_TREMOR`` a blob's radius provably stays positive.
MAX_WOBBLE = 0.5

# A blob's smooth radius never falls below this fraction of its mean (the harmonics are shrunk).
_BLOB_MIN_RADIUS = 0.3


#: Default budget of the generators here (``max_points``): points drawn by one call, 2**22 (~4.2 M).
MAX_POINTS = 2**22


def _check_n_points(n_points, max_points, curves: int = 1, drawn: int = 0) -> int:
    """``n_points`` checked, and ``curves`` curves of ``max(n_points, drawn)`` points against the budget
    (``drawn``: the points a curve is built from before its resampling)."""
    if isinstance(n_points, bool) or not isinstance(n_points, (int, np.integer)) or n_points < MIN_POINTS:
        raise ValueError(f"n_points must be an integer >= {MIN_POINTS}, got {n_points!r}")
    check_budget(curves * max(int(n_points), drawn), budget(max_points, "max_points"), "max_points", "curve points")
    return int(n_points)


def _check_kind(kind) -> str:
    if not isinstance(kind, str) or kind not in LEAF_KINDS:
        raise ValueError(f"unknown leaf kind {kind!r}; valid kinds: {', '.join(LEAF_KINDS)}")
    return kind


@dataclass(frozen=True)
class _Margin:
    """How a smooth blade's margin is cut (see the module docstring).

    Positions are ``sigma``, the arc-length position along one half of the outline: 0 at the base,
    1 at the tip. ``tooth_depths`` and ``lobe_depths`` have one row per side (right, left); tooth
    depths are in units of the leaf's length, lobe depths are fractions of the distance to the fan
    (how far a sinus cuts towards the midrib).
    """

    tooth_depths: np.ndarray = field(default_factory=lambda: np.zeros((2, 0)))
    tooth_span: tuple[float, float] = (0.1, 0.9)
    lobe_depths: np.ndarray = field(default_factory=lambda: np.zeros((2, 0)))
    lobe_start: float = 0.2


def _teeth(rng, counts, depths, starts, ends) -> _Margin:
    """A serrate margin: a seeded tooth count and mean depth, each tooth +-20 % on each side."""
    count = int(rng.integers(counts[0], counts[1] + 1))
    depth = rng.uniform(*depths)
    span = (rng.uniform(*starts), rng.uniform(*ends))
    return _Margin(tooth_depths=depth * rng.uniform(0.8, 1.2, size=(2, count)), tooth_span=span)


# --------------------------------------------------------------------------------------------
# Smooth blades: the right half from the base (0, 0) to the tip (0, 1), and the fan's segment
# --------------------------------------------------------------------------------------------


def _profile_half(half_width: float, widest: float, base_exponent: float, tip_exponent: float) -> np.ndarray:
    """Right half of a blade given by its half-width profile over the midrib."""
    # Cosine spacing crowds samples at the ends, where the margin turns towards the midrib.
    y = 0.5 - 0.5 * np.cos(np.linspace(0.0, np.pi, _HALF_SAMPLES))
    x = half_width * (y / widest) ** base_exponent * ((1.0 - y) / (1.0 - widest)) ** tip_exponent
    x[0] = x[-1] = 0.0
    return np.column_stack([x, y])


def _polar_half(radius) -> tuple[np.ndarray, float]:
    """Right half of a blade given by its radius ``radius(psi)`` around a point of the midrib.

    ``psi`` is measured from the tip direction (+y) towards +x; the half runs from ``psi = pi``
    (the base) to ``psi = 0`` (the tip). Returns the half in leaf coordinates and the height of
    the centre there.
    """
    psi = np.linspace(np.pi, 0.0, _HALF_SAMPLES)
    r = radius(psi)
    length = r[0] + r[-1]
    half = np.column_stack([r * np.sin(psi), r[0] + r * np.cos(psi)]) / length
    half[0, 0] = half[-1, 0] = 0.0
    return half, r[0] / length


def _profile_blade(widest: float, tip_exponent: float, half_width: float, spread: float):
    """Profile blade widest at height ``widest``, its fan horizontal over ``spread`` of the blade there."""
    base_exponent = tip_exponent * widest / (1.0 - widest)  # puts the maximum of w at ``widest``
    half = _profile_half(half_width, widest, base_exponent, tip_exponent)
    return half, (widest * (1.0 - spread), widest + spread * (1.0 - widest))


def _ovate(rng):
    widest, tip_exponent, half_width = rng.uniform(0.36, 0.44), rng.uniform(0.75, 0.9), rng.uniform(0.25, 0.325)
    half, fan = _profile_blade(widest, tip_exponent, half_width, 0.4)
    return half, fan, _teeth(rng, (13, 19), (0.010, 0.016), (0.08, 0.14), (0.90, 0.95))


def _lanceolate(rng):
    widest, tip_exponent, half_width = rng.uniform(0.42, 0.5), rng.uniform(1.1, 1.35), rng.uniform(0.085, 0.115)
    half, fan = _profile_blade(widest, tip_exponent, half_width, 0.7)
    return half, fan, _teeth(rng, (24, 34), (0.004, 0.007), (0.06, 0.12), (0.92, 0.97))


def _lobed(rng):
    widest, tip_exponent, half_width = rng.uniform(0.55, 0.65), rng.uniform(0.55, 0.7), rng.uniform(0.26, 0.31)
    half, fan = _profile_blade(widest, tip_exponent, half_width, 0.5)
    count = int(rng.integers(4, 6))
    depths = rng.uniform(0.5, 0.65) * rng.uniform(0.85, 1.15, size=(2, count))
    return half, fan, _Margin(lobe_depths=depths, lobe_start=rng.uniform(0.12, 0.2))


def _soft_max(values: np.ndarray, sharpness: float) -> np.ndarray:
    """Smooth maximum of positive rows (an L^p norm): rounds the sinuses between lobes."""
    return np.sum(values**sharpness, axis=0) ** (1.0 / sharpness)


def _palmate(rng):
    lateral, basal = math.radians(rng.uniform(52.0, 62.0)), math.radians(rng.uniform(110.0, 125.0))
    # (centre angle, length, angular width) of the middle, lateral and basal lobes: a pointed peak
    # length * exp(-|psi - centre| / width) each, and narrow side teeth standing out of its flanks.
    lobes = [
        (0.0, 1.0, rng.uniform(0.40, 0.46)),
        (lateral, rng.uniform(0.80, 0.92), rng.uniform(0.38, 0.44)),
        (basal, rng.uniform(0.45, 0.58), rng.uniform(0.30, 0.36)),
    ]
    peaks = []
    for centre, length, width in lobes:
        peaks.append((centre, length, width))
        # The middle lobe's left teeth are the mirror images of its right ones.
        for side in (1.0,) if centre == 0.0 else (-1.0, 1.0):
            for j in range(int(rng.integers(1, 3))):
                offset = width * (0.45 + 0.35 * j + rng.uniform(-0.05, 0.05))
                reach = length * math.exp(-offset / width) * rng.uniform(1.22, 1.32)
                peaks.append((centre + side * offset, reach, 0.09))
    notch = rng.uniform(0.07, 0.11)  # radius towards the petiole: the notch at the base

    def radius(psi):
        terms = [np.full_like(psi, notch)]
        for centre, length, width in peaks:
            # Mirror images (at -centre) reach the right half only near the middle lobe.
            for mirrored in (centre,) if centre == 0.0 else (centre, -centre):
                terms.append(length * np.exp(-np.abs(psi - mirrored) / width))
        return _soft_max(np.array(terms), 10.0)

    half, centre = _polar_half(radius)
    return half, (centre, centre), _Margin()


def _cordate(rng):
    down, side = rng.uniform(0.50, 0.60), rng.uniform(0.72, 0.82)
    drip, drip_width = rng.uniform(0.15, 0.28), rng.uniform(0.10, 0.16)
    sinus, sinus_width = rng.uniform(0.60, 0.75), rng.uniform(0.22, 0.30)

    def radius(psi):
        # An egg longer towards the tip, a drawn-out tip, a notch at the petiole.
        axial = np.where(np.cos(psi) >= 0.0, 1.0, down)
        egg = 1.0 / np.sqrt((np.sin(psi) / side) ** 2 + (np.cos(psi) / axial) ** 2)
        tip = 1.0 + drip * np.exp(-np.abs(psi) / drip_width)
        notch = 1.0 - sinus * np.exp(-(np.pi - np.abs(psi)) / sinus_width)
        return egg * tip * notch

    half, centre = _polar_half(radius)
    return half, (centre, centre), _teeth(rng, (11, 15), (0.006, 0.010), (0.05, 0.10), (0.88, 0.93))


_BLADES = {"ovate": _ovate, "lanceolate": _lanceolate, "lobed": _lobed, "palmate": _palmate, "cordate": _cordate}


# --------------------------------------------------------------------------------------------
# The fan, and cutting the margin along it
# --------------------------------------------------------------------------------------------


def _fan_origins(points: np.ndarray, fan: tuple[float, float]) -> np.ndarray:
    """Nearest point of the axis segment ``(0, fan[0])``-``(0, fan[1])`` to each point."""
    return np.column_stack([np.zeros(len(points)), np.clip(points[:, 1], *fan)])


def _fan_position(ring: np.ndarray, fan: tuple[float, float]) -> np.ndarray:
    """Where each point of a ring lies around the fan: increases once around a fan graph.

    Below the segment: the angle from straight down (right side) or its continuation (left side);
    beside it: the height; above it: the angle from the right. The pieces are joined end to end.
    """
    low, high = fan
    x, y = ring[:, 0], ring[:, 1]
    middle = high - low
    below = np.arctan2(x, low - y)  # 0 straight down, +pi/2 to the right, -pi/2 to the left
    above = np.arctan2(y - high, x)  # 0 to the right, pi to the left
    right = np.where(y < low, below, np.pi / 2 + (y - low))
    right = np.where(y > high, np.pi / 2 + middle + above, right)
    left = np.where(y < low, 2 * np.pi + 2 * middle + below, 3 * np.pi / 2 + middle + (high - y))
    left = np.where(y > high, np.pi / 2 + middle + above, left)
    return np.where(x > 0, right, np.where(x < 0, left, np.where(y < low, 0.0, right)))


def _symmetric_ring(half: np.ndarray) -> np.ndarray:
    """Closed counter-clockwise ring from the right half (base first, tip last) and its mirror image."""
    left = half[-2:0:-1] * np.array([-1.0, 1.0])
    return np.vstack([half, left])


def _smoothstep(x: np.ndarray) -> np.ndarray:
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3.0 - 2.0 * x)


# Where a tooth's crest lies within it (0 = the sinus on the base side, 1 = the next sinus): past
# the middle, so the crest leans towards the tip as serrate teeth do.
_TOOTH_CREST = 0.7


def _tooth_heights(sigma: np.ndarray, side: np.ndarray, margin: _Margin) -> np.ndarray:
    """Outward push of the margin by the teeth: a rounded back rising to a pointed crest."""
    count = margin.tooth_depths.shape[1]
    if count == 0:
        return np.zeros_like(sigma)
    start, end = margin.tooth_span
    xi = (sigma - start) / (end - start)
    phase = np.clip(xi, 0.0, 1.0) * count
    index = np.minimum(phase.astype(int), count - 1)
    u = phase - index
    shape = np.where(
        u <= _TOOTH_CREST,
        np.sin(0.5 * np.pi * u / _TOOTH_CREST),
        (1.0 - u) / (1.0 - _TOOTH_CREST),
    )
    # Teeth fade in over the first 15 % of the toothed span and out over the last 15 %.
    envelope = _smoothstep(xi / 0.15) * _smoothstep((1.0 - xi) / 0.15)
    return margin.tooth_depths[side, index] * shape * envelope


# How far a lobe's crest is moved towards the tip, as a fraction of the lobe (< 1 / pi keeps the
# warp u -> u - lean sin(pi u)^2 monotone), and where the crest then lies: the u in (0.5, 1) that the
# warp takes to 0.5 (a fixed-point iteration, contracting since lean * pi < 1).
_LOBE_LEAN = 0.12


def _warped_crest() -> float:
    crest = 0.5
    for _ in range(60):
        crest = 0.5 + _LOBE_LEAN * math.sin(math.pi * crest) ** 2
    return crest


_LOBE_CREST = _warped_crest()


def _lobe_factors(sigma: np.ndarray, side: np.ndarray, margin: _Margin) -> np.ndarray:
    """Scale of the distance to the fan: 1 on the lobes, down to 1 - depth at the sinuses."""
    count = margin.lobe_depths.shape[1]
    if count == 0:
        return np.ones_like(sigma)
    # Lobe crests at u = c, c + 1, ..., c + count (c = _LOBE_CREST; the first at lobe_start, the
    # terminal lobe's at the tip), sinuses at u = 1, ..., count; no cut below the first crest.
    u = _LOBE_CREST + count * np.clip((sigma - margin.lobe_start) / (1.0 - margin.lobe_start), 0.0, 1.0)
    sinus = np.clip(np.floor(u - _LOBE_CREST).astype(int) + 1, 1, count) - 1  # changes at crests
    # The warp leans each lobe towards the tip (its crest past the middle, sinuses staying put);
    # the power above 1 makes the sinuses broad and round and the lobes narrower.
    warped = u - _LOBE_LEAN * np.sin(np.pi * u) ** 2
    cut = 1.0 - np.abs(np.sin(np.pi * warped)) ** 1.5
    return 1.0 - margin.lobe_depths[side, sinus] * cut


def _cut_margin(ring: np.ndarray, tip: int, fan, margin: _Margin, asymmetry: np.ndarray) -> np.ndarray:
    """Move each point of the smooth ring (tip at index ``tip``) along its fan ray: lobes, teeth, asymmetry."""
    closed = np.vstack([ring, ring[:1]])
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))])[:-1]
    s = arc / (2.0 * arc[tip])  # 0 at the base, 0.5 at the tip (the halves are mirror images)
    side = (np.arange(len(ring)) > tip).astype(int)
    sigma = np.where(side == 0, 2.0 * s, 2.0 * (1.0 - s))
    # Odd in the mirror (s -> 1 - s) and zero at the base and the tip, which stay on the midrib;
    # the even factor sin^2 flattens it there, so the tip stays the leaf's top.
    harmonics = np.arange(1, len(asymmetry) + 1)
    skew = np.sin(2.0 * np.pi * np.outer(s, harmonics)) @ asymmetry * np.sin(2.0 * np.pi * s) ** 2
    origins = _fan_origins(ring, fan)
    rays = ring - origins
    distance = np.hypot(rays[:, 0], rays[:, 1])
    # Positive: lobe factors stay above 0.25, the skew within +-0.06 and teeth only push outwards.
    scale = _lobe_factors(sigma, side, margin) * (1.0 + skew) + _tooth_heights(sigma, side, margin) / distance
    return origins + rays * scale[:, None]


def _leaf(kind: str, rng: np.random.Generator, n_points: int) -> np.ndarray:
    half, fan, margin = _BLADES[kind](rng)
    half = resample_open_curve(half, _HALF_SAMPLES)  # even spacing along the margin for the teeth
    ring = _symmetric_ring(half)
    position = _fan_position(ring, fan)
    if not np.all(np.diff(position) > 0):
        raise RuntimeError(f"internal error: the {kind} blade is not a graph over its fan")
    asymmetry = np.clip(rng.normal(0.0, 0.012, size=3) / np.arange(1, 4), -0.02, 0.02)
    tip = len(half) - 1
    cut = _cut_margin(ring, tip, fan, margin, asymmetry)
    # Base and tip lie on the midrib (x = 0 exactly: their rays run along it).
    leaf = (cut - cut[0]) / (cut[tip, 1] - cut[0, 1])
    return resample_closed_curve(leaf, n_points)


def leaf_outline(kind: str, *, rng=None, n_points: int = 512, max_points: int = MAX_POINTS) -> np.ndarray:
    """One SYNTHETIC leaf outline of the given kind, a stand-in for the paper's leaf training set.

    The outline imitates a real leaf form (see the table in :mod:`paperlib.datasets.sketches`):
    ``"ovate"`` (beech, birch: egg-shaped, serrate), ``"lanceolate"`` (willow: long, narrow, finely
    serrate), ``"lobed"`` (white oak: rounded lobes), ``"palmate"`` (maple: five pointed, toothed
    lobes) or ``"cordate"`` (linden: heart-shaped base). It is generated, not measured.

    Parameters
    ----------
    kind : str
        One of :data:`LEAF_KINDS`.
    rng : None, int or numpy.random.Generator, optional
        Seed of the leaf's variation (proportions, tooth and lobe counts and depths, asymmetry).
    n_points : int, optional
        Number of points (>= 16), equally spaced in arc length. Default 512.
    max_points : int, optional
        Budget: the largest ``n_points`` (default :data:`MAX_POINTS`).

    Returns
    -------
    ndarray, shape (n_points, 2), float64
        A simple closed curve without a repeated end point, counter-clockwise, starting at the
        base of the leaf (where the petiole joins it) at ``(0, 0)``, the tip at ``(0, 1)`` (the
        leaf's length is 1, the midrib along +y). The tip lies within half a point spacing of
        ``(0, 1)`` (the resampling may cut it) and near arc-length position 0.5 (within 0.03;
        palmate and cordate basal lobes reach below ``y = 0``).

    Raises
    ------
    ValueError
        If ``kind`` is unknown or ``n_points`` is not an integer >= 16.

    Notes
    -----
    Every outline is a graph over a fan of non-crossing rays (module docstring), so it and every
    resampling of it are simple polygons.

    References
    ----------
    Simhon & Dudek (2001), section 3.1 and Figure 5: a training set of "14 leaf outlines", a class
    whose features are "well localized in time" (arc length).
    """
    kind = _check_kind(kind)
    n_points = _check_n_points(n_points, max_points, drawn=2 * _HALF_SAMPLES)
    return _leaf(kind, as_generator(rng), n_points)


def leaf_outlines(n: int = 14, *, rng=None, n_points: int = 512, max_points: int = MAX_POINTS) -> list[np.ndarray]:
    """A SYNTHETIC leaf training set: ``n`` outlines cycling over :data:`LEAF_KINDS`.

    Outline ``i`` is ``leaf_outline(LEAF_KINDS[i % 5], rng=children[i], n_points=n_points)``, where
    ``children = as_generator(rng).spawn(n)``, so every leaf has its own seeded variation
    and leaves of the same kind differ.

    Parameters
    ----------
    n : int, optional
        Number of outlines (>= 1). Default 14, the size of the paper's set.
    rng : None, int or numpy.random.Generator, optional
        Seed of the whole set.
    n_points : int, optional
        Points per outline (>= 16). Default 512.
    max_points : int, optional
        Budget: the most points of the whole set, ``n * max(n_points, 4096)`` (each outline is drawn
        with 4096 points before its resampling; default :data:`MAX_POINTS`), checked before drawing.

    Returns
    -------
    list of ndarray, shape (n_points, 2)
        See :func:`leaf_outline`.

    Raises
    ------
    ValueError
        If ``n`` is not an integer >= 1 or ``n_points`` is not an integer >= 16.

    References
    ----------
    Simhon & Dudek (2001), section 3.1 ("The set consisted of 14 leaf outlines") and Figures 5-6.
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n must be an integer >= 1, got {n!r}")
    n_points = _check_n_points(n_points, max_points, int(n), drawn=2 * _HALF_SAMPLES)
    children = as_generator(rng).spawn(int(n))
    return [_leaf(LEAF_KINDS[i % len(LEAF_KINDS)], child, n_points) for i, child in enumerate(children)]


# --------------------------------------------------------------------------------------------
# Hand-drawn-like sketches
# --------------------------------------------------------------------------------------------


def _random_series(rng, harmonics: np.ndarray, rms: float, decay: float) -> tuple[np.ndarray, np.ndarray]:
    """Amplitudes ``U(0.5, 1.5) / k**decay`` and random phases, scaled to ``rms``."""
    amplitudes = rng.uniform(0.5, 1.5, size=len(harmonics)) / harmonics**decay
    phases = rng.uniform(0.0, 2.0 * np.pi, size=len(harmonics))
    amplitudes *= rms / math.sqrt(0.5 * np.sum(amplitudes**2)) if rms > 0 else 0.0
    return amplitudes, phases


def _evaluate(t: np.ndarray, frequencies, amplitudes, phases, derivative: bool = False) -> np.ndarray:
    """``sum_k a_k sin(f_k t + phi_k)`` (or its derivative in ``t``), one harmonic at a time to keep
    memory at the size of ``t``."""
    total = np.zeros_like(t)
    for frequency, amplitude, phase in zip(frequencies, amplitudes, phases):
        if derivative:
            total += amplitude * frequency * np.cos(frequency * t + phase)
        else:
            total += amplitude * np.sin(frequency * t + phase)
    return total


def _tremor_series(rng) -> tuple[np.ndarray, np.ndarray]:
    """Unit-RMS tremor: harmonics 6-30 of the whole curve with ``1/k`` amplitudes, random phases."""
    amplitudes = 1.0 / _TREMOR_HARMONICS
    amplitudes /= math.sqrt(0.5 * np.sum(amplitudes**2))
    return amplitudes, rng.uniform(0.0, 2.0 * np.pi, size=len(_TREMOR_HARMONICS))


def _bounding_diagonal(points: np.ndarray) -> float:
    return float(np.hypot(*np.ptp(points, axis=0)))


def _blob(rng, n_samples: int, wobble: float, tremor: float) -> np.ndarray:
    theta = np.linspace(0.0, 2.0 * np.pi, n_samples, endpoint=False)
    amplitudes, phases = _random_series(rng, _BLOB_HARMONICS, wobble, 1.0)
    bumps = _evaluate(theta, _BLOB_HARMONICS, amplitudes, phases)
    if bumps.min() < _BLOB_MIN_RADIUS - 1.0:  # keep the radius positive: shrink the harmonics
        bumps *= (1.0 - _BLOB_MIN_RADIUS) / -bumps.min()
    radius = 1.0 + bumps
    smooth = np.column_stack([radius * np.cos(theta), radius * np.sin(theta)])
    # Tremor relative to the radius, scaled so that it is about tremor * (bounding diagonal):
    # 1 + relative > 0 always, since the unit tremor peaks below 6.3, the diagonal of a blob with
    # wobble <= 0.5 is below 6.9 and tremor <= 0.015.
    amplitudes, phases = _tremor_series(rng)
    relative = tremor * _bounding_diagonal(smooth) * _evaluate(theta, _TREMOR_HARMONICS, amplitudes, phases)
    return smooth * (1.0 + relative)[:, None]


def _integrate_heading(s: np.ndarray, heading: np.ndarray) -> np.ndarray:
    """Polyline with the given heading (squashed below +-80 degrees) over arc lengths ``s``."""
    bounded = _MAX_HEADING * np.tanh(heading[:-1] / _MAX_HEADING)
    steps = np.diff(s)[:, None] * np.column_stack([np.cos(bounded), np.sin(bounded)])
    return np.vstack([np.zeros((1, 2)), np.cumsum(steps, axis=0)])


def _stroke(rng, n_samples: int, wobble: float, tremor: float) -> np.ndarray:
    s = np.linspace(0.0, 1.0, n_samples)
    amplitudes, phases = _random_series(rng, _STROKE_HARMONICS, 1.0, 1.0)
    heading = _evaluate(np.pi * s, _STROKE_HARMONICS, amplitudes, phases)
    heading -= heading.mean()
    heading *= wobble / float(np.sqrt(np.mean(heading**2)))
    sideways = tremor * _bounding_diagonal(_integrate_heading(s, heading))  # in stroke lengths
    # The tremor moves the stroke sideways by sideways * n(s): it turns the heading by the slope n'(s).
    amplitudes, phases = _tremor_series(rng)
    frequencies = 2.0 * np.pi * _TREMOR_HARMONICS / _STROKE_TREMOR_SPAN
    slope = _evaluate(s, frequencies, amplitudes, phases, derivative=True)
    stroke = _integrate_heading(s, heading + sideways * slope)
    angle = rng.uniform(0.0, 2.0 * np.pi)
    rotation = np.array([[math.cos(angle), math.sin(angle)], [-math.sin(angle), math.cos(angle)]])
    return stroke @ rotation


def hand_drawn_curve(
    n_points: int = 1000,
    *,
    closed: bool = True,
    size: float = 1.0,
    rng=None,
    tremor: float = 0.004,
    wobble: float = 0.2,
    max_points: int = MAX_POINTS,
) -> np.ndarray:
    """A SYNTHETIC hand-drawn-like sketch: a smooth random blob or stroke with a slight hand tremor.

    Stands for the rough curves a user draws to steer the synthesis. A closed curve is a blob
    ``r(theta) = 1 + sum_k a_k sin(k theta + phi_k)`` over harmonics ``k = 2..5`` (amplitudes
    decaying as ``1/k``, random phases), star-shaped around its centre; an open one is a stroke
    whose heading (harmonics 1-4 of its arc length) stays within 80 degrees of its mean direction,
    turned by a random angle. The tremor adds harmonics 6-30 (amplitudes ``1/k``, random phases):
    radially to a blob, sideways to a stroke. Both constructions keep the curve simple whatever
    the seed (see the module docstring).

    Parameters
    ----------
    n_points : int, optional
        Number of points (>= 16), equally spaced in arc length. Default 1000.
    closed : bool, optional
        A closed blob (default) or an open stroke.
    size : float, optional
        Diagonal of the curve's bounding box (> 0), exactly. Default 1.
    rng : None, int or numpy.random.Generator, optional
        Seed.
    tremor : float, optional
        RMS of the tremor's displacement as a fraction of ``size`` (for a blob, of the displacement
        relative to the radius, times the diagonal), in ``[0, MAX_TREMOR]`` = ``[0, 0.015]``.
        Default 0.004, a steady hand; 0 gives a perfectly smooth curve.
    wobble : float, optional
        How far the curve departs from a circle or a straight line, in ``[0, MAX_WOBBLE]`` =
        ``[0, 0.5]``: for a blob the RMS of the radius relative to its mean (the harmonics are
        shrunk where they would take the radius below 0.3 of the mean), for a stroke the RMS of
        its heading about its mean direction, in radians. Default 0.2; 0 gives a circle or a
        straight segment (plus the tremor).
    max_points : int, optional
        Budget: the largest ``n_points`` (default :data:`MAX_POINTS`).

    Returns
    -------
    ndarray, shape (n_points, 2), float64
        Points at equal arc length, the centre of the bounding box at the origin, no repeated
        points. A closed curve has no repeated end point, runs counter-clockwise and starts at its
        point on the +x ray from the blob's centre (before re-centring).

    Raises
    ------
    ValueError
        If ``n_points`` is not an integer >= 16, ``size`` is not positive and finite, ``tremor``
        or ``wobble`` is outside its range, or ``closed`` is not a bool.

    References
    ----------
    Simhon & Dudek (2001), Figures 3, 4 and 6 (left: "hand drawn sketches").
    """
    n_points = _check_n_points(n_points, max_points)
    if not isinstance(closed, (bool, np.bool_)):
        raise ValueError(f"closed must be True or False, got {closed!r}")
    size = positive_number(size, "size")
    tremor = positive_number(tremor, "tremor", allow_zero=True)
    if tremor > MAX_TREMOR:
        raise ValueError(f"tremor must be at most {MAX_TREMOR} (a fraction of the size), got {tremor!r}")
    wobble = positive_number(wobble, "wobble", allow_zero=True)
    if wobble > MAX_WOBBLE:
        raise ValueError(f"wobble must be at most {MAX_WOBBLE}, got {wobble!r}")
    rng = as_generator(rng)
    n_samples = max(4 * n_points, 8192)  # dense enough that resampling loses nothing visible
    if closed:
        curve = resample_closed_curve(_blob(rng, n_samples, wobble, tremor), n_points)
    else:
        curve = resample_open_curve(_stroke(rng, n_samples, wobble, tremor), n_points)
    lower, upper = curve.min(axis=0), curve.max(axis=0)
    return (curve - 0.5 * (lower + upper)) * (size / float(np.hypot(*(upper - lower))))
