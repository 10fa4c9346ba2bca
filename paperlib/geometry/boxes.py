"""Oriented bounding boxes fitted by principal component analysis.

Barla et al. 2006 (section 2.1) fit an element with an oriented bounding box: the eigenvectors
of the covariance of the element's points give the two axes, and projecting the points on the
axes gives the size and the centre of the box. Hurtut et al. 2009 (section 2.1) estimate an
element's area, orientation and elongation on that box.

Which points
------------
PCA of the vertices would make the box depend on how densely each stroke happens to be
sampled (a curve digitised finely on one side and coarsely on the other tilts the axes). We use
instead the uniform measure along the strokes, unit mass per unit of arc length: the limit of
resampling the strokes uniformly, without a resampling step to choose. Its moments up to order
two are exact sums over the segments (Simpson's rule, see :func:`_arc_length_samples`), so the
fit is exact and vectorised. Elements whose strokes have no length at all (dots only) fall back
to equal weights on their vertices.

The extents are exact: the extreme projection of a polyline on an axis is at a vertex, so the
box is the smallest rectangle with the PCA axes containing every stroke. With
``include_width=True`` each stroke counts as the region its pen covers (the polyline dilated by
half the pen width, round caps), as Barla's option of fitting "the points of its contour"; its
extent along any axis is the skeleton's plus half the width at the extreme vertex. The axes stay
those of the skeleton: for strokes thinner than they are long the two agree, and a dot (a stroke
of zero length) then gets the square its pen draws.

Conventions and degenerate cases
--------------------------------
- ``axes`` holds unit column vectors ``[major, minor]``, the minor axis the major one turned by
  +90 degrees (a right-handed frame, so :meth:`OrientedBox.corners` run counter-clockwise).
- Major and minor are named by the box extents, not by the PCA variances (an 'L' shape can have
  its larger variance across its longer side), so ``half_lengths[0] >= half_lengths[1]`` and
  the elongation is at least 1.
- ``angle`` is the direction of the major axis in ``[0, pi)``: a box has no front, so an axis
  and its opposite are the same.
- When the covariance is isotropic (a circle, a square, a regular plus; relative tolerance
  ``1e-10``) PCA defines no direction and the x axis is taken, so such boxes are axis-aligned
  whatever the rotation of the shape: a property of PCA fitting, not a minimum-area rectangle.
- Half lengths below ``1e-12`` times the box's larger half length are set to exactly 0: a
  straight stroke has a box of zero width, elongation ``inf``, area 0; a single point has a box
  of zero size, elongation 1 (no direction is longer than another) and angle 0.

References
----------
.. [1] P. Barla, S. Breslav, J. Thollot, F. Sillion, L. Markosian, "Stroke Pattern Analysis and
   Synthesis", Computer Graphics Forum (Eurographics) 25(3), 2006, section 2.1 (element fitting).
.. [2] T. Hurtut, P.-E. Landes, J. Thollot, Y. Gousseau, R. Drouilhet, J.-F. Coeurjolly,
   "Appearance-guided Synthesis of Element Arrangements by Example", NPAR 2009, section 2.1.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._checks import check_flag, finite_array, float_array
from .strokes import Element, StackedStrokes, as_points, stack_strokes

__all__ = ["OrientedBox", "OrientedBoxes", "oriented_bounding_box", "oriented_bounding_boxes"]

#: Covariances whose anisotropy is below this fraction of their trace have no principal direction.
_ISOTROPY_TOLERANCE = 1e-10
_TIE_TOLERANCE = 1e-9  # relative difference of two extents below which they are equal
#: Half lengths below this fraction of the larger one are rounding noise of a zero extent.
_ZERO_EXTENT_TOLERANCE = 1e-12
#: Corners of the unit box in the (major, minor) frame, counter-clockwise from (-, -).
_UNIT_CORNERS = np.array([(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)])


# --------------------------------------------------------------------------- box types


def _rotation(angle):
    """Rotation matrices ``[[cos, -sin], [sin, cos]]`` for an angle or an array of angles."""
    cos, sin = np.cos(angle), np.sin(angle)
    return np.stack([np.stack([cos, -sin], axis=-1), np.stack([sin, cos], axis=-1)], axis=-2)


def _elongation(half_lengths) -> np.ndarray:
    """Major over minor half length: ``inf`` for a segment, 1 for a point."""
    major, minor = half_lengths[..., 0], half_lengths[..., 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(major == 0, 1.0, major / minor)


def _corners(centers, axes, half_lengths) -> np.ndarray:
    """Box corners ``(..., 4, 2)``, counter-clockwise, from the (-major, -minor) corner."""
    local = _UNIT_CORNERS * half_lengths[..., None, :]
    return centers[..., None, :] + local @ np.swapaxes(axes, -1, -2)


def _read_only(array) -> np.ndarray:
    array = np.array(array, dtype=np.float64)
    array.setflags(write=False)
    return array


@dataclass(frozen=True, eq=False)
class OrientedBox:
    """A rectangle with arbitrary orientation, as fitted by :func:`oriented_bounding_box`.

    Parameters
    ----------
    center : array_like, shape (2,)
        Centre of the rectangle.
    axes : array_like, shape (2, 2)
        Unit column vectors ``[major, minor]``; must equal the rotation by ``angle``, so the
        minor axis is the major one turned by +90 degrees.
    half_lengths : array_like, shape (2,)
        Half extents along the major and the minor axis, ``major >= minor >= 0``.
    angle : float
        Direction of the major axis, in ``[0, pi)``.

    See Also
    --------
    OrientedBox.from_angle : build a box from its centre, half lengths and angle.
    """

    center: np.ndarray
    axes: np.ndarray
    half_lengths: np.ndarray
    angle: float

    def __post_init__(self):
        center = _read_only(finite_array(self.center, "box center", shape=(2,)))
        half_lengths = _read_only(finite_array(self.half_lengths, "box half_lengths", shape=(2,)))
        angle = float(finite_array(self.angle, "box angle", ndim=0))
        if not 0.0 <= angle < np.pi:
            raise ValueError(f"box angle must lie in [0, pi), got {angle!r}")
        if not half_lengths[0] >= half_lengths[1] >= 0:
            raise ValueError(f"box half_lengths must satisfy major >= minor >= 0, got {half_lengths.tolist()}")
        axes = _read_only(finite_array(self.axes, "box axes"))
        if axes.shape != (2, 2) or not np.allclose(axes, _rotation(angle), rtol=0, atol=1e-9):
            raise ValueError("box axes must be the unit columns [major, minor] of the rotation by angle")
        for name, value in (("center", center), ("axes", axes), ("half_lengths", half_lengths), ("angle", angle)):
            object.__setattr__(self, name, value)

    @classmethod
    def from_angle(cls, center, half_lengths, angle) -> "OrientedBox":
        """The box with the given centre, ``(major, minor)`` half lengths and major-axis angle.

        The angle is reduced modulo pi.

        Parameters
        ----------
        center : array_like, shape (2,)
            Centre of the rectangle.
        half_lengths : array_like, shape (2,)
            Half extents along the major and the minor axis, ``major >= minor >= 0``.
        angle : float
            Direction of the major axis, in radians (any value; reduced to ``[0, pi)``).

        Returns
        -------
        OrientedBox
            The box, with ``axes`` the rotation by the reduced angle.
        """
        angle = float(np.mod(angle, np.pi))
        return cls(center, _rotation(angle), half_lengths, angle)

    @property
    def area(self) -> float:
        """Area of the rectangle, ``4 * major * minor``."""
        return float(4.0 * self.half_lengths.prod())

    @property
    def elongation(self) -> float:
        """Major over minor extent; ``inf`` for a segment, 1 for a point."""
        return float(_elongation(self.half_lengths))

    @property
    def diagonal(self) -> float:
        """Length of the rectangle's diagonal."""
        return float(2.0 * np.hypot(*self.half_lengths))

    def corners(self) -> np.ndarray:
        """The four corners, shape ``(4, 2)``, counter-clockwise.

        Returns
        -------
        ndarray, shape (4, 2)
            The corners, counter-clockwise.
        """
        return _corners(self.center, self.axes, self.half_lengths)


@dataclass(frozen=True, eq=False)
class OrientedBoxes:
    """Many oriented boxes as arrays, one row per box (see :class:`OrientedBox`).

    Parameters
    ----------
    centers : ndarray, shape (n, 2)
        Centre of each box.
    axes : ndarray, shape (n, 2, 2)
        Unit column vectors ``[major, minor]`` of each box.
    half_lengths : ndarray, shape (n, 2)
        Half extents along the major and the minor axis of each box.
    angles : ndarray, shape (n,)
        Direction of each box's major axis, in ``[0, pi)``.
    """

    centers: np.ndarray
    axes: np.ndarray
    half_lengths: np.ndarray
    angles: np.ndarray

    def __post_init__(self):
        for name in ("centers", "axes", "half_lengths", "angles"):
            object.__setattr__(self, name, _read_only(float_array(getattr(self, name), name)))

    def __len__(self) -> int:
        return self.angles.shape[0]

    def __getitem__(self, index) -> OrientedBox:
        return OrientedBox(self.centers[index], self.axes[index], self.half_lengths[index], self.angles[index])

    def __iter__(self):
        return (self[i] for i in range(len(self)))

    @property
    def areas(self) -> np.ndarray:
        """Areas of the rectangles, shape ``(n,)``."""
        return 4.0 * self.half_lengths.prod(axis=1)

    @property
    def elongations(self) -> np.ndarray:
        """Major over minor extents, shape ``(n,)`` (``inf`` for segments, 1 for points)."""
        return _elongation(self.half_lengths)

    @property
    def diagonals(self) -> np.ndarray:
        """Diagonal lengths, shape ``(n,)``."""
        return 2.0 * np.hypot(self.half_lengths[:, 0], self.half_lengths[:, 1])

    def corners(self) -> np.ndarray:
        """Corners of every box, shape ``(n, 4, 2)``, counter-clockwise.

        Returns
        -------
        ndarray, shape (n, 4, 2)
            The corners of each box, counter-clockwise.
        """
        return _corners(self.centers, self.axes, self.half_lengths)


# --------------------------------------------------------------------------- fitting


def _arc_length_samples(a, b):
    """Points and weights whose moments up to order 2 are those of the uniform measure on ``a -> b``.

    Simpson's rule (weights ``L/6, 2L/3, L/6`` at the start, middle and end of a segment of length
    ``L``) is exact for polynomials of degree 2, hence for the mass, mean and covariance.
    """
    length = np.hypot(*(b - a).T)
    points = np.concatenate([a, (a + b) / 2.0, b])
    weights = np.concatenate([length / 6.0, 2.0 * length / 3.0, length / 6.0])
    return points, weights


def _weighted_moments(points, weights, groups, n_groups):
    """Mass, centroid ``(g, 2)`` and central second moments ``[xx, xy, yy]`` ``(g, 3)`` per group."""
    mass = np.bincount(groups, weights=weights, minlength=n_groups)
    centroids = np.column_stack([np.bincount(groups, weights=weights * c, minlength=n_groups) for c in points.T])
    centroids /= mass[:, None]
    # Moments about the centroid, not the origin: no cancellation far from the origin.
    dx, dy = (points - centroids[groups]).T
    second = np.column_stack(
        [np.bincount(groups, weights=weights * term, minlength=n_groups) for term in (dx * dx, dx * dy, dy * dy)]
    )
    return mass, centroids, second


def _principal_angles(second_central) -> np.ndarray:
    """Direction of the largest eigenvector of each covariance ``[xx, xy, yy]``, 0 if isotropic."""
    xx, xy, yy = second_central.T
    anisotropy = np.hypot(xx - yy, 2.0 * xy)
    isotropic = anisotropy <= _ISOTROPY_TOLERANCE * (xx + yy)
    return np.where(isotropic, 0.0, 0.5 * np.arctan2(2.0 * xy, xx - yy))


def _fit_boxes(vertices, vertex_group, group_offsets, radii, mass, centroids, second_central) -> OrientedBoxes:
    """Boxes with PCA axes whose extents hold every vertex (dilated by its radius).

    ``second_central`` are the second moments about ``centroids``; ``vertex_group`` is
    non-decreasing with group ``g`` owning ``vertices[group_offsets[g]:group_offsets[g + 1]]``.
    """
    angles = _principal_angles(second_central / mass[:, None])
    axes = _rotation(angles)
    relative = vertices - centroids[vertex_group]
    projections = np.einsum("ni,nij->nj", relative, axes[vertex_group])
    starts = group_offsets[:-1]
    upper = np.maximum.reduceat(projections + radii[:, None], starts, axis=0)
    lower = np.minimum.reduceat(projections - radii[:, None], starts, axis=0)
    half_lengths = (upper - lower) / 2.0
    centers = centroids + np.einsum("nij,nj->ni", axes, (upper + lower) / 2.0)
    return _boxes_with_major_first(centers, half_lengths, angles)


def _boxes_with_major_first(centers, half_lengths, angles) -> OrientedBoxes:
    """Swap the axes where the minor PCA axis has the larger extent; snap noise extents to 0.

    Extents equal up to rounding (a square box, e.g. a symmetric '+') are a tie, not a swap:
    otherwise rounding alone would turn identical elements by 0 or pi/2.
    """
    swap = half_lengths[:, 1] > half_lengths[:, 0] * (1.0 + _TIE_TOLERANCE)
    half_lengths = np.where(swap[:, None], half_lengths[:, ::-1], half_lengths)
    half_lengths[half_lengths < _ZERO_EXTENT_TOLERANCE * half_lengths[:, :1]] = 0.0
    angles = np.mod(angles + np.where(swap, np.pi / 2.0, 0.0), np.pi)
    angles[angles >= np.pi] = 0.0  # mod can round up to pi itself
    return OrientedBoxes(centers, _rotation(angles), half_lengths, angles)


def oriented_bounding_boxes(elements, *, include_width: bool = False) -> OrientedBoxes:
    """Fit an oriented bounding box to each element by PCA of its strokes.

    Parameters
    ----------
    elements : sequence of Element or StackedStrokes
        At least one element (or their strokes stacked by :func:`stack_strokes`).
    include_width : bool, optional
        If true, fit the region the pen covers (each stroke dilated by half its width) instead
        of the skeleton; the axes are the skeleton's either way. Default false.

    Returns
    -------
    OrientedBoxes
        One box per element, in order.

    Notes
    -----
    The axes are the eigenvectors of the covariance of the uniform measure along the strokes
    (arc-length weighted, independent of the vertex density; elements of zero total length use
    their vertices); the extents and centre come from projecting the vertices on the axes, as
    Barla et al. [1]_ do. See the module docstring for the conventions and degenerate cases.

    References
    ----------
    .. [1] Barla et al. 2006, "Stroke Pattern Analysis and Synthesis", section 2.1.
    .. [2] Hurtut et al. 2009, "Appearance-guided Synthesis of Element Arrangements by
       Example", section 2.1 ("estimated on their fitted bounding box").
    """
    stack = elements if isinstance(elements, StackedStrokes) else stack_strokes(elements)
    vertices, vertex_element = stack.vertices, stack.vertex_element
    starts = stack.segment_starts
    points, weights = _arc_length_samples(vertices[starts], vertices[starts + 1])
    groups = np.tile(vertex_element[starts], 3)
    # Elements without length (dots only) are weighted by their vertices instead.
    dots_only = np.bincount(groups, weights=weights, minlength=stack.n_elements) == 0
    dot_vertices = dots_only[vertex_element]
    points = np.concatenate([points, vertices[dot_vertices]])
    weights = np.concatenate([weights, np.ones(dot_vertices.sum())])
    groups = np.concatenate([groups, vertex_element[dot_vertices]])
    moments = _weighted_moments(points, weights, groups, stack.n_elements)
    radii = stack.stroke_width[stack.vertex_stroke] / 2.0 if include_width else np.zeros(vertices.shape[0])
    return _fit_boxes(vertices, vertex_element, stack.element_vertex_offsets, radii, *moments)


def oriented_bounding_box(points_or_element, *, weights=None, include_width: bool = False) -> OrientedBox:
    """Fit an oriented bounding box by PCA to a point set or an element.

    Parameters
    ----------
    points_or_element : array_like, shape (n, 2), or Element
        The points (n >= 1), or an element: then the strokes are weighted by arc length, as in
        :func:`oriented_bounding_boxes`.
    weights : array_like, shape (n,), optional
        Non-negative weights of the points in the covariance (not a positive sum: error). The
        extents hold every point, weighted or not. Only for point sets: an element is weighted
        by arc length.
    include_width : bool, optional
        Elements only: fit the region the pen covers (see :func:`oriented_bounding_boxes`).

    Returns
    -------
    OrientedBox

    Raises
    ------
    ValueError
        On malformed points or weights, or ``weights``/``include_width`` given with the wrong
        kind of input.

    References
    ----------
    .. [1] Barla et al. 2006, "Stroke Pattern Analysis and Synthesis", section 2.1: "We first
       fit a gaussian distribution to the points to compute the two principal elongation
       directions [...] Each point is then projected onto each axis to compute the size and
       center c of the bounding box."
    .. [2] Hurtut et al. 2009, section 2.1.
    """
    include_width = check_flag(include_width, "include_width")
    if isinstance(points_or_element, Element):
        if weights is not None:
            raise ValueError("weights apply to point sets; an element is weighted by arc length")
        return oriented_bounding_boxes([points_or_element], include_width=include_width)[0]
    if include_width:
        raise ValueError("include_width applies to elements; a point set has no pen width")
    points = as_points(points_or_element, name="points_or_element")
    weights = _point_weights(weights, points.shape[0])
    group = np.zeros(points.shape[0], dtype=int)
    moments = _weighted_moments(points, weights, group, 1)
    return _fit_boxes(points, group, np.array([0, points.shape[0]]), np.zeros(points.shape[0]), *moments)[0]


def _point_weights(weights, n_points: int) -> np.ndarray:
    if weights is None:
        return np.ones(n_points)
    try:
        weights = np.asarray(weights, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"weights must be numeric: {exc}") from None
    if weights.shape != (n_points,):
        raise ValueError(f"weights must have shape ({n_points},), one per point, got {weights.shape}")
    if not np.isfinite(weights).all() or (weights < 0).any() or weights.sum() <= 0:
        raise ValueError("weights must be finite, non-negative and not all zero")
    return weights
