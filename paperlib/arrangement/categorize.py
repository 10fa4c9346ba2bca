"""Appearance-based categorization of elements (Hurtut et al. 2009, section 2.2).

Two methods: the paper's recipe (``method="paper"``) and a recursive a contrario splitting
(``method="recursive"``, the default), which keeps the paper's mode test and its area-first order
but works on drawings whose elements vary within a type.

The paper's recipe
------------------
Hurtut et al. group the elements of a reference arrangement in two stages:

1. **Area.** The maximal meaningful modes (MM-modes, :func:`paperlib.acontrario.histogram_modes`)
   of the histogram of the normalised area feature are the *area categories*; "any connected
   interval of bins which does not belong to an MM-mode is considered as an outlier area
   category".
2. **Appearance.** "For each of these categories (including the possible outlier categories)",
   the four other features (orientation, elongation, extremities, crossings) are projected on
   their first robust principal component (:func:`~paperlib.arrangement.robpca.robust_pca`);
   the MM-modes of the histogram of the projections are *appearance categories*, and again every
   connected run of bins outside the MM-modes is an outlier appearance category. "If an area
   category contains less than 10 elements, we do not split it any further."

Why it is not the default. It works when the elements of a category are copies of one glyph (each
category one histogram bin). On a drawing, where every element of a type varies in size, rotation
and the wobble of the hand, it fails on two counts, measured on the test matrix of
:func:`paperlib.datasets.categorization_cases` (notebook ``hurtut2009_fig03_categorization``: 5 of
11 cases below an adjusted Rand index of 0.9, and the one-type control split in up to 4):

* 10 linear bins over the area domain ``[0, 1]`` are 0.5% of the surface each: every element
  smaller than that falls in the first bin, so types of sizes x2.5 apart are one area mode;
* the first robust component of the four appearance features follows what varies most *within*
  the types (the orientation of rotated elements, the elongation the hand gives them), not the
  crossing or the two extremities that separate the types, which the histogram then never sees.

The recursive method (default)
------------------------------
The paper's test, one feature at a time, recursively: a group of elements (at first, all of them)
is divided by the first feature, in the order area, crossings, extremities, elongation,
orientation (:data:`RECURSIVE_FEATURES`; area first, as the paper's "size is the first information
to be perceived"), whose histogram has at least two groups; each part is examined again, with all
the features, until no feature divides it (nor two features jointly, see *Joint splits* below)
or it holds fewer than ``min_category_size`` elements.
This is the hierarchy the paper itself uses (area, then appearance), made recursive and read
feature by feature as Delon, Desolneux, Lisani and Petro's *Automatic color palette* segments hue,
then saturation, then value, each by the a contrario modes of its 1-D histogram; no projection
decides which feature is looked at, so a feature that separates the types is never drowned by one
that varies within them. Histograms, with ``bins`` (10) as the paper's resolution:

* *area*: log10 of the paper's normalised area (capped at 1), bins of ``3 / (2 * bins)`` decades
  (a factor 1.41 in area, 1.19 in size, at the default) on a fixed grid, over the bins the group's
  values occupy, MM-modes. The uniform background is the group's own support, not a fixed range
  of 3 decades: against 3 decades, two sizes a factor 2 apart among 40 elements are one area mode
  and their empty bin no meaningful gap (the uniform density is too thin for either to stand out);
  against the stretch they occupy, both are;
* *crossings*: one bin per count, 0 to max(10, largest); each count held by meaningfully many
  elements (eq. (1) on that single bin, with the histogram's ``L (L + 1) / 2`` tests) is a mode
  of its own: a crossing is a topological event the hand does not blur, and one crossing is what
  divides the paper's Fig. 3 top row, so adjacent counts must not merge;
* *extremities*: one bin per count, MM-modes: points of strong curvature are a threshold on a
  continuous turn, which a hand moves across by one now and then, so adjacent counts merge. A
  mode is then cut where its counts are not one unimodal run (Delon et al.'s fine-to-coarse
  segmentation, :func:`paperlib.acontrario.unimodal_segments`, :data:`UNIMODAL_FEATURES`): drawn
  outlines of five- and six-petalled florettes and of shamrocks read 5-6 and 8-10 corners, every
  count denser than the uniform background and so one MM-mode, with a dip at 7 that one type alone
  would not make. (Cutting the continuous features' modes the same way over-splits single
  hand-drawn types: 62 case-seeds of the held-out families below 0.9 instead of 42.)
* *elongation*: ``bins`` bins over the paper's normalised ``[0, 1]``, MM-modes;
* *orientation*: the paper's bin width (a tenth of ``[0, 1]``) over the ``[0, 0.5)`` an axis
  occupies, unwrapped per group (below), MM-modes.

The groups of a histogram are its modes widened to the bins around them: between two modes, the
cut falls at the least filled bin (which goes to the nearer mode); the bins before the first mode
and after the last join it, unless an *empty* run of bins that is a meaningful gap (Desolneux et
al.) cuts them off, in which case they form an outlier group, the paper's outlier category. Sparse
but non-empty tails are not cut off: for the uniform background, the thin tails of any single
population are "gaps", and cutting them over-splits every group. Names record the path:
``"area1.crossings0"``, ``"crossings_outlier0"``; a group that is never divided is ``"all"``. The
report is :attr:`Categorization.splits`. The method draws no random numbers.

Gaps between values. A fixed bin grid can hide a gap: two sizes a factor 2 apart, each spread by
a hand over 0.3 decades of area, leave 0.28 decades empty, yet each of the two 0.15-decade bins
across it holds the edge of one population. So when the histogram of area or elongation does not
divide a group, its sorted values are searched for the widest spacing that leaves at least
``min_category_size`` elements on each side; the group divides there if the spacing is at least
one bin wide (the histogram's resolution: a narrower gap is not a difference the features are
read at) and meaningful, i.e. its expected number under the same background (``m`` values uniform
over their range ``L``: ``(m - 1) (1 - g / L)^(m - 2)`` spacings of length ``g`` or more) is
below ``epsilon``. Without the one-bin floor the test splits single hand-drawn types whose values
pile up against a bound (an elongation near 1), for which the uniform background is too weak.

Joint splits. Where no feature's histogram divides a group, two features may still agree on a cut
that neither shows alone: Greek pi and lambda read 4 and 3 extremities in every copy, one MM-mode,
and elongations of 0.40 and 0.66, which overlap in the histogram of the pair. So the group divides
at a candidate cut -- between two counts of crossings or extremities, or at the widest spacing of
the sorted areas, elongations or ink lengths, leaving ``min_category_size`` elements on each side
and the cut feature's medians on the two sides at least its resolution apart -- when another
feature of :data:`JOINT_FEATURES` (the *witness*) confirms it: the witness's medians on the two
sides differ by at least its resolution (one count; one bin of area or elongation;
:data:`INK_LENGTH_RESOLUTION` of ink length) and its Mann-Whitney rank-sum p-value, times the number
of (cut, witness) pairs tried, is an NFA below ``epsilon * JOINT_STRICTNESS`` (1e-3). The stricter
threshold is measured, not derived: within one type the hand correlates features (a narrower serif
'i' reads one serif corner more: NFA 3e-3 to 3e-2), so the test's null of exchangeable elements is
weaker than the real background, while types that differ jointly reach 1e-9 to 1e-4.
:attr:`Split.witness` and :attr:`Split.nfa` record it. This is a deviation from the paper, whose
joint reading of the features is the first robust component.

The ink's length is a sixth feature, read by joint splits only: ``log10`` of the length of an
element's strokes over the half perimeter of its box, how many times the line spans its box
(:func:`recursive_feature_values`). Types one corner apart and alike in the paper's five features
differ there: Times Greek kappa and omega, florettes of five and six petals, a knight and a bishop.
A count and the other count are one event where the hand makes two strokes touch (an overshooting
end is a crossing and an end), so one confirms a cut on the other only from two counts apart; and
two crossing modes one count apart stay apart only where a witness confirms them (a looped script
'f' whose loop the hand closes in some copies reads 0 or 1 crossing and nothing else differs).
Where nothing else divides a group, its ink lengths may still not be unimodal: two shapes that
span their boxes a few percent apart, each tightly (a chess king and pawn, 6% apart; cursive 'b' and
'x'), no resolution shows. The group then divides at their widest spacing when Hartigan's dip test
(the ``diptest`` package) gives an NFA below ``epsilon * JOINT_STRICTNESS``. Over the 3528 final
groups of one type (at most two stray copies) that the categorization leaves without it in the
families ``"main"`` to ``"held_out_11"`` and the outlines (seeds 0-19), the test's p-value is 0.015
or more; on those of two types tightly apart it reaches 3e-6.

Measured limits (fig03 notebook, seeds 0-19). The 57 cases of the first nine held-out families:
20 case-seeds below an ARI of 0.9 (42 before the ink's length, 113 without joint splits). The
outlines (hand-drawn DejaVu Sans dingbats, chess pieces and shapes of one size): 22 of 120 mixed
case-seeds (108 before the ink's length); king and pawn, 6% apart in ink length, merge at 16 seeds
(the dip test finds them at 4). Two families checked once: ``"held_out_10"`` (80 case-seeds below
0.9, 100 before the ink's length; then 60 once crossing modes needed a witness, which its looped
'f' control led to) fails on outlined regular polygons (a hexagon's 60-degree turns sit at the
corner threshold, the hand spreads its count over 1-6; the square, set apart by the dip test, is
the only one to span its box differently), on a telephone and a diamond (one corner apart, ink
lengths 0.02 apart, areas about one bin) and on serif 'n' and 'h' (elongations 0.12 apart, nothing
else a resolution apart); ``"held_out_11"`` (20 case-seeds, then 18 with the dip test) fails on
cursive 'b' and 'x' (ink lengths 0.038 apart, just under the resolution) and holds on its seven
other cases, controls included. Two more, each checked once: ``"held_out_12"`` (41 of 180
case-seeds) and ``"held_out_13"`` (42) fail where two types read counts one apart in every copy and
nothing else is a resolution apart (futural '2' and '5', 'E' and 'K'; Times 'r', 'v', 'y', whose
serifs give all three 5-6 corners), on looped cursive letters that lose a crossing in a few copies,
and a simplex Greek 'beta' control splits at 2 seeds of 20 (a joint split of features the hand
correlates within the type, NFA 3.7e-4). A type whose crossing the hand
unmakes in a few copies (a kana) sends those copies to the type that has none. A single copy drawn
with more bends than the rest of its type is set apart as the paper's outlier category. Drawings
made of parallel pen lines (Hershey's complex, duplex, triplex and bold faces) are read on the
centrelines of their ink (``topology="auto"``, :mod:`paperlib.arrangement.ink`). At epsilon >= 10
the orientation of near-round glyphs shows spurious modes.

The rest of this docstring describes the paper's recipe.

``method="paper"`` implements exactly that, with the choices the paper leaves open stated here.

Bins. "In all our experiments, the distribution of features is estimated on 10 bins": both
stages use ``L = 10`` bins by default (``bins`` changes it; the paper notes that more bins suit
more elements).

Histogram ranges. The paper does not say over which interval the ``L`` bins are laid. It
normalises every feature "on [0, 1]" so that the unit interval "covers enough visual variation",
which only matters if the histograms span that normalised domain, not the data's own range. So
by default (``histogram_range="domain"``):

* the area histogram spans ``[0, 1]``, the range of the normalised (capped) area: a bin is 0.5%
  of the reference surface, and elements of the same size fall in the same bin whatever else is
  in the drawing;
* the appearance histogram spans the projection of the normalised feature domain on the first
  component -- the interval of ``(x - center) . v`` over the box ``[0, 1]`` per feature (the
  circle of the orientation embedding below) -- widened to the scores if some lie outside it
  (counts of extremities or crossings above 10 are not capped). A bin is then about a tenth of
  a feature's full variation, as for the area.

``histogram_range="data"`` lays the bins over ``[min, max]`` of the values instead (what a
plain ``numpy.histogram`` does). With few elements that setting always fills the two end bins
and tends to cut a single population into a mode and outlier tails (over-categorization, the
paper's figure 9); it is offered for comparison.

Orientation. The orientation feature is an axis angle over 2 pi, in ``[0, 0.5)``, measured from
the drawing's x axis, and it is circular: axes just above 0 and just below pi are nearly the same,
yet a linear PCA sees them at the two ends of the feature, so near-horizontal hatching would be
cut in two. The origin of the angles is an accident of the drawing's frame, so by default
(``orientation="unwrap"``) we move it, separately for each area category, to the middle of the
widest empty arc between the category's axis angles: the feature keeps the paper's scale and
range (``theta / 2 pi`` in ``[0, 0.5)``), and elements with close axes get close values whichever
side of the x axis they lie on. This is a deviation from the paper (which keeps the x axis as the
origin); ``orientation="linear"`` is the paper's feature unchanged. ``orientation="circular"``
embeds the axis on a circle, ``(cos 2 theta, sin 2 theta) / (4 pi)`` (distances the paper's to
first order), a sixth-column alternative we do not recommend: projected on a line, elements of
uniformly random orientation pile up at both ends of the circle's shadow (an arcsine density)
and are split in two, while the unwrapped feature stays flat and is not split.

Degenerate categories. A category whose feature vectors are all equal is not split (one
appearance category: status ``"constant"``; equal to 1e-9 in every normalised feature, as
translated copies differ by rounding). When ROBPCA meets an exact fit otherwise (at least
h of the elements identical, or sharing one robust score: :class:`ExactFitError`), the robust
direction is undefined, so we project on the first *classical* principal component instead
(status ``"split"`` with ``pca_method="classical"``, the error message kept in ``note``): the
identical majority then falls in one bin and the differing elements are read off the same
histogram. A category of fewer than ``min_category_size`` elements is not split (status
``"too_few"``). A split that yields a single group (one MM-mode holding every element, or no
MM-mode and a single outlier run) leaves the category whole, with its area-stage name.

Small categories. Hurtut's model fit needs at least 3 elements per category (``MIN_FIT_SIZE``).
Outlier categories are often smaller (a single odd element). They are kept as the paper says
and reported in :attr:`Categorization.small_categories`, never merged silently.

Names. Area categories are ``"area0", "area1", ...`` (MM-modes by position) and
``"outlier0", ...`` (outlier runs by position); an area category that is split further gets
``".shape0", ".shape1", ...`` (appearance MM-modes) and ``".outlier0", ...`` suffixes. Labels
number the categories in that order: area modes (each with its appearance categories), then area
outliers.

Randomness. ROBPCA draws random directions for categories of more than 22 elements; each area
category gets its own generator spawned from ``rng`` (``Generator.spawn``), so the result is
the same, bit for bit, for the same seed.

The adjusted Rand index (Hubert and Arabie 1985), which measures agreement with ground-truth
categories, is written here with NumPy to avoid a scikit-learn dependency for one formula.
:func:`separability_ceiling` is its control: the index a classifier that knows the types reaches
on the same features (leave-one-out nearest neighbours in resolution units), which tells a miss
of the features (types that overlap at their resolution) from a miss of the method.

References
----------
.. [1] T. Hurtut, P.-E. Landes, J. Thollot, Y. Gousseau, R. Drouilhet, J.-F. Coeurjolly,
   "Appearance-guided Synthesis of Element Arrangements by Example", NPAR 2009, section 2.2
   (categorization algorithm, 10 bins, 10 elements) and figure 3.
.. [2] A. Desolneux, L. Moisan, J.-M. Morel, "A grouping principle and four applications",
   IEEE TPAMI 25(4), 2003 (maximal meaningful modes).
.. [3] M. Hubert, P. J. Rousseeuw, K. Vanden Branden, "ROBPCA: a new approach to robust
   principal component analysis", Technometrics 47(1), 2005.
.. [4] L. Hubert, P. Arabie, "Comparing partitions", Journal of Classification 2, 1985,
   193-218 (adjusted Rand index).
.. [5] J. Delon, A. Desolneux, J.-L. Lisani, A. B. Petro, "Automatic color palette", Inverse
   Problems and Imaging 1(2), 2007, 265-287 (hierarchical a contrario segmentation of 1-D
   histograms, one feature after another).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, fields, replace

import diptest
import numpy as np
import pandas as pd
from scipy.spatial import cKDTree
from scipy.stats import mannwhitneyu

from paperlib.acontrario import (
    MAX_SEGMENTED_BINS,
    HistogramModes,
    Interval,
    gap_log10_nfa,
    histogram_modes,
    interval_log10_nfa,
    outlier_intervals,
    unimodal_segments,
)
from paperlib._checks import (
    as_generator, check_choice, data_frame, finite_array, instance_of, integer_at_least, integer_in_range,
    positive_number,
)
from paperlib.geometry import as_elements

from .features import COUNT_SCALE, TOPOLOGY_READINGS, element_features
from .robpca import ExactFitError, RobustPCA, robust_pca

__all__ = [
    "DEFAULT_BINS",
    "INK_LENGTH_RESOLUTION",
    "JOINT_FEATURES",
    "JOINT_STRICTNESS",
    "METHODS",
    "UNIMODAL_FEATURES",
    "MIN_FIT_SIZE",
    "MIN_SPLIT_SIZE",
    "RECURSIVE_FEATURES",
    "AreaCategory",
    "Categorization",
    "FeatureHistogram",
    "Split",
    "adjusted_rand_index",
    "categorize",
    "recursive_feature_values",
    "separability_ceiling",
    "unwrapped_orientation",
]

#: Number of histogram bins the paper uses "in all our experiments" (section 2.2).
DEFAULT_BINS = 10
#: Area categories with fewer elements are not split further (section 2.2).
MIN_SPLIT_SIZE = 10
#: Fewest elements of a category the multitype model can be fitted on (section 3).
MIN_FIT_SIZE = 3
#: Radius of the circle the orientation is embedded on: distances match the paper's to first order.
ORIENTATION_RADIUS = 1.0 / (4.0 * np.pi)

#: ``categorize``'s methods: the recursive a contrario splitting (default) and the paper's recipe.
METHODS = ("recursive", "paper")
#: Features the recursive method reads, in the order it tries them at each node.
RECURSIVE_FEATURES = ("area", "crossings", "extremities", "elongation", "orientation")
#: The recursive method's area bins are ``AREA_DECADES / (2 * bins)`` decades of the normalised area wide.
AREA_DECADES = 3.0
#: Features that are counts: one histogram bin per count. Crossings are read count by count
#: (each meaningful count its own mode), extremities by MM-modes (adjacent counts merge).
_COUNT_FEATURES = ("crossings", "extremities")
#: Features whose mode groups are also cut where they are not one unimodal run of bins (Delon et al.'s FTC).
UNIMODAL_FEATURES = ("extremities",)
#: Continuous features whose groups may also divide at a meaningful gap between their values.
_GAP_FEATURES = ("area", "elongation")
#: Features a joint split cuts on and is confirmed by: four of the paper's and the ink's length
#: (:func:`recursive_feature_values`; not one of the paper's features). Orientation is left out: the
#: hand rotates the elements of a type, and a circular value has no rank order.
JOINT_FEATURES = ("area", "crossings", "extremities", "elongation", "ink_length")
#: The ink's length's resolution in a joint split, in ``log10``: a tenth of the length. A measured
#: calibration (held-out families 1-9 and the outlines, seeds 0-19): at 0.03 two one-type controls
#: split at 5 seeds (their two sides 0.030-0.037 apart), at 0.05 the heart and the spade (0.048-0.054
#: apart) merge at 11.
INK_LENGTH_RESOLUTION = 0.04
#: A joint split is accepted when its NFA is below ``epsilon`` times this. Measured on the held-out
#: families 1-8 (seeds 0-19): a hand correlates features within one type (a narrower serif 'i' reads
#: one serif corner more, NFA 3e-3 to 3e-2), so the rank test's null of exchangeable elements is too
#: weak a background; two types that differ jointly reach 1e-9 to 1e-4.
JOINT_STRICTNESS = 1e-3

_HISTOGRAM_RANGES = ("domain", "data")
_ORIENTATIONS = ("unwrap", "linear", "circular")
#: Feature vectors closer than this in every (normalised) feature are equal: translated copies
#: of one element differ by rounding only.
_EQUAL_FEATURES = 1e-9


def _read_only(array) -> np.ndarray:
    array = np.array(array)
    array.flags.writeable = False
    return array


# --------------------------------------------------------------------------- results


@dataclass(frozen=True)
class FeatureHistogram:
    """One histogram of section 2.2 with its a contrario reading and the groups it defines.

    Parameters
    ----------
    values : ndarray, shape (m,)
        The histogrammed values: normalised areas, or scores on the first robust component.
    edges : ndarray, shape (L + 1,)
        Bin edges; bins are half-open ``[e_i, e_{i+1})``, the last one closed.
    bins : ndarray of int, shape (m,)
        Bin of each value.
    analysis : HistogramModes
        Counts, MM-modes and outlier intervals (:func:`paperlib.acontrario.histogram_modes`).
    groups : ndarray of int, shape (m,)
        Group of each value, indexing ``group_names``: MM-modes by position, then outlier runs.
    group_names : tuple of str
        ``"mode0", ..., "outlier0", ...``; only groups holding at least one value.
    """

    values: np.ndarray
    edges: np.ndarray
    bins: np.ndarray
    analysis: HistogramModes
    groups: np.ndarray
    group_names: tuple[str, ...]

    def __post_init__(self):
        for field in fields(self):
            value = getattr(self, field.name)
            if isinstance(value, np.ndarray):
                value.flags.writeable = False

    @property
    def counts(self) -> np.ndarray:
        """Number of values in each bin, shape (L,)."""
        return self.analysis.counts

    @property
    def modes(self):
        """The MM-modes (:class:`paperlib.acontrario.Interval`), by position."""
        return self.analysis.modes

    @property
    def outliers(self) -> tuple[tuple[int, int], ...]:
        """Non-empty runs of bins outside every MM-mode, ``(start, end)`` inclusive."""
        return self.analysis.outliers


@dataclass(frozen=True)
class AreaCategory:
    """One category of the first (area) stage and what the second stage made of it.

    Parameters
    ----------
    name : str
        ``"area<i>"`` (an MM-mode of the area histogram) or ``"outlier<j>"`` (an outlier run).
    kind : str
        ``"mode"`` or ``"outlier"``.
    members : ndarray of int
        Indices of its elements in the input, increasing.
    status : str
        ``"split"`` (the appearance histogram was read; it may still give a single group),
        ``"too_few"`` (fewer than ``min_category_size`` elements) or ``"constant"`` (all
        feature vectors equal).
    pca_features : tuple of str
        The columns projected (empty unless ``status == "split"``).
    pca : RobustPCA or None
        The ROBPCA fit, or None when not split or after an exact fit.
    pca_method : str or None
        ``"ROBPCA"``, ``"classical"`` (after an exact fit) or None.
    component : ndarray or None, shape (p,)
        The direction projected on (the robust, or classical, first component).
    center : ndarray or None, shape (p,)
        The centre the scores are measured from.
    histogram : FeatureHistogram or None
        Histogram of the scores on ``component`` with its MM-modes (figure 3 c).
    categories : tuple of str
        The final categories it was divided into (itself alone when not divided).
    note : str
        Why the classical component was used (the ExactFitError message), else empty.
    """

    name: str
    kind: str
    members: np.ndarray
    status: str
    pca_features: tuple[str, ...] = ()
    pca: RobustPCA | None = None
    pca_method: str | None = None
    component: np.ndarray | None = None
    center: np.ndarray | None = None
    histogram: FeatureHistogram | None = None
    categories: tuple[str, ...] = ()
    note: str = ""

    def __post_init__(self):
        for field in fields(self):
            value = getattr(self, field.name)
            if isinstance(value, np.ndarray):
                value.flags.writeable = False


@dataclass(frozen=True)
class Split:
    """One node of the recursive categorization: a group of elements and how it was divided.

    Parameters
    ----------
    name : str
        ``"all"`` for the root, else the path of the groups it descends from, e.g.
        ``"area1.crossings0"``; outlier groups are ``"<feature>_outlier<j>"``.
    members : ndarray of int
        Indices of its elements in the input, increasing.
    feature : str or None
        The feature whose histogram divided it (one of :data:`RECURSIVE_FEATURES`), or None for a
        final category.
    histogram : FeatureHistogram or None
        That histogram, with its modes and the group of each member (None for a final category).
    children : tuple of str
        Names of the groups it was divided into (empty for a final category).
    status : str
        ``"split"``, ``"too_few"`` (fewer than ``min_category_size`` elements) or ``"one_mode"``
        (no feature divides it).
    witness : str or None
        For a joint split (no feature's histogram divided the group, but a cut on ``feature`` is
        confirmed by another feature, see :func:`categorize`), the confirming feature; else None.
    nfa : float or None
        For a joint split, or a split where the ink's lengths are not unimodal (``feature`` is
        ``"ink_length"`` and ``witness`` None), its number of false alarms (below ``epsilon`` x
        :data:`JOINT_STRICTNESS`); else None.
    """

    name: str
    members: np.ndarray
    feature: str | None
    histogram: FeatureHistogram | None
    children: tuple[str, ...]
    status: str
    witness: str | None = None
    nfa: float | None = None

    def __post_init__(self):
        instance_of(self.members, np.ndarray, "members").flags.writeable = False


@dataclass(frozen=True)
class Categorization:
    """Categories of the elements of an arrangement (Hurtut 2009, section 2.2).

    Parameters
    ----------
    labels : ndarray of int64, shape (n,)
        Category of each element, ``0 .. K-1``, indexing ``categories``.
    categories : tuple of str
        Category names, e.g. ``("area0", "area1.shape0", "area1.shape1", "outlier0")``.
    counts : ndarray of int64, shape (K,)
        Number of elements per category (all positive).
    features : pandas.DataFrame
        The element features (:func:`~paperlib.arrangement.element_features`), one row per
        element.
    area_histogram : FeatureHistogram
        Histogram of the normalised area over all elements, with its MM-modes (figure 3 b).
    area_categories : tuple of AreaCategory
        ``method="paper"``: per area category (modes, then outliers), the PCA and appearance
        histogram (figure 3 c). Empty for the recursive method.
    parameters : dict
        ``method``, ``bins``, ``epsilon``, ``min_category_size``, ``histogram_range``,
        ``orientation``, and ``topology``: where extremities and crossings were read
        (``"strokes"`` or ``"ink"``).
    splits : tuple of Split
        ``method="recursive"``: every node of the recursion, parents before children (the root
        first). Empty for the paper's method.
    """

    labels: np.ndarray
    categories: tuple[str, ...]
    counts: np.ndarray
    features: pd.DataFrame
    area_histogram: FeatureHistogram
    area_categories: tuple[AreaCategory, ...]
    parameters: dict
    splits: tuple[Split, ...] = ()

    def __post_init__(self):
        instance_of(self.labels, np.ndarray, "labels").flags.writeable = False
        instance_of(self.counts, np.ndarray, "counts").flags.writeable = False

    @property
    def n_categories(self) -> int:
        """K, the number of categories."""
        return len(self.categories)

    @property
    def small_categories(self) -> tuple[str, ...]:
        """Categories of fewer than ``MIN_FIT_SIZE`` (3) elements, too small to fit the model on."""
        return tuple(name for name, count in zip(self.categories, self.counts) if count < MIN_FIT_SIZE)

    @property
    def is_outlier(self) -> np.ndarray:
        """Whether each category is an outlier category (of either stage), shape (K,)."""
        return np.array(["outlier" in name for name in self.categories], dtype=bool)

    def members(self, category) -> np.ndarray:
        """Indices of the elements of a category, given by name or label.

        Parameters
        ----------
        category : str or int
            A category name (an entry of ``categories``) or its label (an index into ``categories``).

        Returns
        -------
        ndarray of int
            Indices of the elements of that category in the input, increasing.

        Raises
        ------
        KeyError
            When ``category`` is a name that is not one of ``categories``.
        """
        if isinstance(category, str):
            if category not in self.categories:
                raise KeyError(f"no category {category!r}; categories are {list(self.categories)}")
            category = self.categories.index(category)
        return np.flatnonzero(self.labels == category)


# --------------------------------------------------------------------------- categorization


def categorize(
    elements,
    reference_area,
    *,
    method: str = "recursive",
    bins=None,
    epsilon: float = 1.0,
    min_category_size: int = MIN_SPLIT_SIZE,
    histogram_range: str = "domain",
    orientation: str = "unwrap",
    topology: str = "auto",
    features=None,
    rng=None,
) -> Categorization:
    """Categorize elements by appearance: recursive a contrario splitting, or the paper's recipe.

    Parameters
    ----------
    elements : sequence of Element
        The elements of the reference arrangement (at least one). Their positions do not matter.
    reference_area : float
        Area of the reference arrangement's surface (> 0), in the elements' units: the area
        feature is the box area over 5% of it, capped at 1.
    method : {"recursive", "paper"}, optional
        ``"recursive"`` (default): split the elements on the a contrario modes of one feature's
        histogram at a time (area first, then crossings, extremities, elongation, orientation),
        and each group again, until no feature divides a group nor two features agree on a cut
        (a joint split). ``"paper"``: Hurtut's two stages,
        area MM-modes then MM-modes of the first robust principal component, on ``bins`` bins
        over the feature domain. See the module docstring for both, and why the default differs.
    bins : int, optional
        Number of histogram bins of the continuous features, at least 2; default 10, the paper's.
        (The recursive method gives counts one bin per count.)
    epsilon : float, optional
        Meaningfulness threshold of the a contrario mode detection (default 1, the paper's).
    min_category_size : int, optional
        Groups with fewer elements are not split further (default 10, the paper's rule for area
        categories); at least 3 (ROBPCA's minimum).
    histogram_range : {"domain", "data"}, optional
        ``method="paper"`` only: lay the bins over the normalised feature domain (default) or the
        values' own range; see the module docstring.
    orientation : {"unwrap", "linear", "circular"}, optional
        ``method="paper"`` only: how the orientation enters the PCA: the paper's feature with the
        origin of angles moved to the widest empty arc of each category's angles (default; a
        deviation from the paper), the paper's feature as is, or embedded on a circle. (The
        recursive method always unwraps.)
    topology : {"auto", "strokes", "ink"}, optional
        Where extremities and crossings are read, as for
        :func:`~paperlib.arrangement.element_features`: by default on the ink's centrelines when
        the elements are drawn with overlapping pen lines (bold, sketchy), else on the strokes.
    features : pandas.DataFrame, optional
        The elements' features, as :func:`~paperlib.arrangement.element_features` returns them
        for these elements and ``reference_area`` (e.g. a previous result's
        :attr:`Categorization.features`): the same elements are then categorized under other
        settings without being measured again, which is most of the cost. By default they are
        measured. ``topology`` must then be ``"auto"`` or the reading they record.
    rng : None, int or numpy.random.Generator
        Seed of ROBPCA's random directions (``method="paper"``; the recursive method draws none).

    Returns
    -------
    Categorization
        Labels, category names and counts, and the report of the splits (figure 3).

    Raises
    ------
    TypeError
        If ``elements`` is not a sequence of Element, or a parameter has the wrong type.
    ValueError
        If there are no elements, ``reference_area`` is not positive, a parameter is out of
        range, or ``features`` does not describe these elements (row count, reference area,
        topology reading).

    References
    ----------
    .. [1] Hurtut et al. 2009, section 2.2 ("Categorization Algorithm") and figure 3.
    .. [2] Delon, Desolneux, Lisani and Petro 2007, "Automatic color palette" (recursive
       a contrario segmentation of one histogram after another).
    """
    elements = as_elements(elements)
    if not elements:
        raise ValueError("elements must hold at least one element (categorize needs one), got none")
    check_choice(method, METHODS, "method")
    n_bins = _checked_bins(bins)
    epsilon = _checked_epsilon(epsilon)
    min_category_size = _checked_min_size(min_category_size)
    check_choice(histogram_range, _HISTOGRAM_RANGES, "histogram_range")
    check_choice(orientation, _ORIENTATIONS, "orientation")
    if features is None:
        features = element_features(elements, reference_area, topology=topology)
    else:
        _check_given_features(features, len(elements), reference_area, topology)
    parameters = {
        "method": method,
        "bins": n_bins,
        "epsilon": epsilon,
        "min_category_size": min_category_size,
        "histogram_range": histogram_range,
        "orientation": orientation,
        "topology": features.attrs["topology_read_on"],
    }
    if method == "recursive":
        return _categorize_recursively(features, parameters)
    return _categorize_as_the_paper(features, parameters, as_generator(rng))


def _check_given_features(features, n_elements: int, reference_area, topology: str) -> None:
    """Raise unless ``features`` is element_features' table for ``n_elements`` elements and ``reference_area``."""
    data_frame(features, "features", ("area", "orientation", "elongation", "extremities", "crossings",
                                      "crossings_raw", "extremities_raw"))
    if len(features) != n_elements:
        raise ValueError(f"features must hold one row per element ({n_elements}), got {len(features)} rows")
    given_area, read_on = features.attrs.get("reference_area"), features.attrs.get("topology_read_on")
    if given_area is None or read_on is None:
        raise ValueError("features must come from element_features (its attrs record reference_area and "
                         f"topology_read_on), got attrs {sorted(features.attrs)}")
    if not np.isclose(given_area, positive_number(reference_area, "reference_area"), rtol=1e-12, atol=0.0):
        raise ValueError(f"features were measured for reference_area={given_area!r}, not {reference_area!r}")
    check_choice(topology, TOPOLOGY_READINGS, "topology")
    if topology not in ("auto", read_on):
        raise ValueError(f"topology={topology!r} differs from the reading the features record ({read_on!r})")


def _categorize_as_the_paper(features: pd.DataFrame, parameters: dict, generator) -> Categorization:
    """Hurtut's two stages: area MM-modes, then MM-modes of the first robust component (section 2.2)."""
    n_bins, epsilon, histogram_range = parameters["bins"], parameters["epsilon"], parameters["histogram_range"]
    n = len(features)
    area = features["area"].to_numpy(dtype=float)
    area_domain = (0.0, 1.0) if histogram_range == "domain" else None
    area_histogram = _feature_histogram(area, n_bins, epsilon, area_domain)
    pca_table, pca_columns, domain_box, circle_columns = _appearance_matrix(
        features, parameters["orientation"] == "circular"
    )

    area_groups = _groups_in_order(area_histogram, "area", "outlier")
    children = generator.spawn(len(area_groups))
    labels = np.empty(n, dtype=np.int64)
    categories: list[str] = []
    reports: list[AreaCategory] = []
    for (name, kind, local), child in zip(area_groups, children):
        members = np.flatnonzero(area_histogram.groups == local)
        report = _split_by_appearance(
            name,
            kind,
            members,
            pca_table,
            pca_columns,
            domain_box,
            circle_columns,
            n_bins,
            epsilon,
            parameters["min_category_size"],
            histogram_range,
            parameters["orientation"] == "unwrap",
            child,
        )
        if report.histogram is None or len(report.categories) == 1:
            labels[members] = len(categories)
            categories.append(name)
        else:
            for sub_local, sub_name in enumerate(report.categories):
                labels[members[report.histogram.groups == sub_local]] = len(categories)
                categories.append(sub_name)
        reports.append(report)
    return _categorization(labels, categories, features, area_histogram, tuple(reports), parameters, ())


def _categorization(labels, categories, features, area_histogram, reports, parameters, splits) -> Categorization:
    counts = np.bincount(labels, minlength=len(categories)).astype(np.int64)
    return Categorization(
        labels=labels,
        categories=tuple(categories),
        counts=counts,
        features=features,
        area_histogram=area_histogram,
        area_categories=reports,
        parameters=parameters,
        splits=splits,
    )


# --------------------------------------------------------------------------- recursive method


def recursive_feature_values(features: pd.DataFrame) -> dict[str, np.ndarray]:
    """The values the recursive method histograms, per feature of :data:`RECURSIVE_FEATURES`.

    ``area``: log10 of the paper's normalised area (capped at 1, "large"); ``crossings`` and
    ``extremities``: the raw counts; ``elongation``: the paper's normalised elongation (capped at
    1, "very elongated"); ``orientation``: the paper's ``theta / 2 pi`` in ``[0, 0.5)`` (unwrapped
    per group when histogrammed); ``ink_length``: log10 of the strokes' length over the half
    perimeter of a box of the element's area and elongation (``area_raw = a b``, ``elongation_raw =
    a / b``), i.e. how many times the line spans its box (0 for a straight stroke, 0.2 for a circle,
    0.3 for a square's outline), read by joint splits only (:data:`JOINT_FEATURES`).

    Parameters
    ----------
    features : pandas.DataFrame
        Output of :func:`~paperlib.arrangement.element_features`.

    Returns
    -------
    dict of str to ndarray, shape (n,)
    """
    data_frame(features, "features", ("area", "crossings_raw", "extremities_raw", "elongation", "orientation",
                                      "area_raw", "elongation_raw", "length_raw"))
    area = features["area"].to_numpy(dtype=float)
    smallest = np.finfo(float).tiny
    box_area = features["area_raw"].to_numpy(dtype=float)
    box_elongation = features["elongation_raw"].to_numpy(dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        half_perimeter = np.sqrt(box_area) * (np.sqrt(box_elongation) + 1.0 / np.sqrt(box_elongation))
        spans = features["length_raw"].to_numpy(dtype=float) / half_perimeter
    spans = np.where(np.isfinite(half_perimeter) & (half_perimeter > 0), spans, 1.0)  # a bare straight stroke
    return {
        "area": np.log10(np.maximum(area, smallest)),
        "crossings": features["crossings_raw"].to_numpy(dtype=float),
        "extremities": features["extremities_raw"].to_numpy(dtype=float),
        "elongation": features["elongation"].to_numpy(dtype=float),
        "orientation": features["orientation"].to_numpy(dtype=float),
        "ink_length": np.log10(np.maximum(spans, smallest)),
    }


def _categorize_recursively(features: pd.DataFrame, parameters: dict) -> Categorization:
    """Split groups on one feature's a contrario modes at a time until none divides (module docstring)."""
    values = recursive_feature_values(features)
    n = len(features)
    labels = np.empty(n, dtype=np.int64)
    categories: list[str] = []
    splits: list[Split] = []
    root_area = _node_histogram("area", values["area"], parameters)
    pending = [("all", np.arange(n))]
    while pending:
        name, members = pending.pop(0)
        split = _split_node(name, members, values, parameters)
        splits.append(split)
        if split.status != "split":
            labels[members] = len(categories)
            categories.append(name)
            continue
        children = [(child, members[split.histogram.groups == k]) for k, child in enumerate(split.children)]
        pending = children + pending  # depth first: a group's categories stay together
    order = {name: k for k, name in enumerate(sorted(categories, key=_natural_key))}
    relabel = np.array([order[name] for name in categories], dtype=np.int64)
    return _categorization(relabel[labels], sorted(categories, key=_natural_key), features, root_area, (),
                           parameters, tuple(splits))


def _natural_key(name: str):
    """Sort key keeping the recursion's order: numbers compared as numbers, outliers after modes."""
    return [(1 if "outlier" in part else 0, [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", part)])
            for part in name.split(".")]


def _split_node(name: str, members: np.ndarray, values: dict, parameters: dict) -> Split:
    """The first feature, in :data:`RECURSIVE_FEATURES` order, whose histogram divides the group."""
    if len(members) < parameters["min_category_size"]:
        return Split(name, members, None, None, (), "too_few")
    prefix = "" if name == "all" else f"{name}."
    for feature in RECURSIVE_FEATURES:
        own = values[feature][members]
        if np.ptp(own) <= _EQUAL_FEATURES:
            continue
        histogram = _node_histogram(feature, own, parameters)
        if np.unique(histogram.groups).size == 1 and feature in _GAP_FEATURES:
            histogram = _split_at_value_gap(histogram, parameters)
        if feature == "crossings" and np.unique(histogram.groups).size > 1:
            histogram = _confirmed_crossing_groups(histogram, members, values, parameters)
        if np.unique(histogram.groups).size > 1:
            children = tuple(f"{prefix}{feature}{group[len('mode'):]}" if group.startswith("mode")
                             else f"{prefix}{feature}_{group}" for group in histogram.group_names)
            return Split(name, members, feature, histogram, children, "split")
    return (_joint_split(name, members, values, parameters) or _dip_split(name, members, values, parameters)
            or Split(name, members, None, None, (), "one_mode"))


def _joint_split(name: str, members: np.ndarray, values: dict, parameters: dict) -> Split | None:
    """A cut on one feature that another feature confirms, where no histogram divides the group.

    Candidate cuts: between every two counts present (crossings, extremities), and at the widest
    spacing of the sorted values (area, elongation, ink length), each leaving ``min_category_size``
    elements on either side and putting the cut feature's medians on the two sides at least its
    resolution apart (one count; one bin; :data:`INK_LENGTH_RESOLUTION`). A cut is confirmed by a
    *witness*, another feature of :data:`JOINT_FEATURES` whose medians differ by at least its
    resolution too and whose Mann-Whitney rank-sum p-value, times the number of (cut, witness) pairs
    tested, is an NFA below ``epsilon * JOINT_STRICTNESS``. The most meaningful confirmed cut divides
    the group, or None.
    """
    least = parameters["min_category_size"]
    resolution = _joint_resolutions(parameters)
    own = {feature: values[feature][members] for feature in JOINT_FEATURES}
    tests = []
    for feature in JOINT_FEATURES:
        for low in _candidate_cuts(feature, own[feature], least):
            if abs(np.median(own[feature][low]) - np.median(own[feature][~low])) < resolution[feature]:
                continue
            tests += [(p_value, apart, feature, witness, low)
                      for p_value, apart, witness in _witness_tests(own, low, feature, resolution)]
    confirmed = [test for test in tests if test[1]]
    if not confirmed:
        return None
    p_value, _, feature, witness, low = min(confirmed, key=lambda test: test[0])
    nfa = len(tests) * p_value
    if nfa >= parameters["epsilon"] * JOINT_STRICTNESS:
        return None
    histogram = _node_histogram(feature, values[feature][members], parameters)
    histogram = replace(histogram, groups=_read_only((~low).astype(np.int64)), group_names=("mode0", "mode1"))
    prefix = "" if name == "all" else f"{name}."
    return Split(name, members, feature, histogram, (f"{prefix}{feature}0", f"{prefix}{feature}1"), "split",
                 witness=witness, nfa=nfa)


def _dip_split(name: str, members: np.ndarray, values: dict, parameters: dict) -> Split | None:
    """Divide a group whose ink lengths are not unimodal, at their widest spacing, or None.

    Hartigan and Hartigan's dip test (the ``diptest`` package) gives the p-value of the ink lengths
    under the least favourable unimodal law; its NFA (one test) must be below ``epsilon *
    JOINT_STRICTNESS``. The cut is the widest spacing leaving ``min_category_size`` elements on each
    side: two shapes that span their boxes a few percent apart, each tightly (a chess king and pawn,
    6% apart), are two modes no resolution of one feature's histogram shows.
    """
    own = values["ink_length"][members]
    widest = _widest_spacing(own, parameters["min_category_size"])
    if widest is None or np.ptp(own) <= _EQUAL_FEATURES:
        return None
    nfa = float(diptest.diptest(own)[1])
    if nfa >= parameters["epsilon"] * JOINT_STRICTNESS:
        return None
    low = own <= widest[0]
    histogram = replace(_node_histogram("ink_length", own, parameters), groups=_read_only((~low).astype(np.int64)),
                        group_names=("mode0", "mode1"))
    prefix = "" if name == "all" else f"{name}."
    return Split(name, members, "ink_length", histogram, (f"{prefix}ink_length0", f"{prefix}ink_length1"), "split",
                 nfa=nfa)


def _joint_resolutions(parameters: dict) -> dict:
    """The smallest difference of medians by which each feature of :data:`JOINT_FEATURES` sets two sides apart."""
    return {"area": AREA_DECADES / (2 * parameters["bins"]), "elongation": 1.0 / parameters["bins"],
            "crossings": 1.0, "extremities": 1.0, "ink_length": INK_LENGTH_RESOLUTION}


def _witness_tests(own: dict, low: np.ndarray, feature: str, resolution: dict) -> list[tuple[float, bool, str]]:
    """(Mann-Whitney p-value, medians apart by the resolution, witness) for each feature but ``feature``.

    One count of crossings and one of extremities are one event, not two features agreeing: where
    the hand makes two strokes touch, an end that overshoots is a crossing and an end, one that
    stops short an end less. So a count confirms a cut on the other count from two counts apart.
    """
    tests = []
    for witness in JOINT_FEATURES:
        x = own[witness]
        if witness == feature or np.ptp(x) <= _EQUAL_FEATURES:
            continue
        needed = resolution[witness] * (2 if {feature, witness} <= set(_COUNT_FEATURES) else 1)
        difference = abs(np.median(x[low]) - np.median(x[~low]))
        tests.append((float(mannwhitneyu(x[low], x[~low]).pvalue), bool(difference >= needed), witness))
    return tests


def _confirmed_crossing_groups(histogram: FeatureHistogram, members: np.ndarray, values: dict,
                               parameters: dict) -> FeatureHistogram:
    """Merge crossing groups one count apart that no other feature sets apart.

    A hand makes or unmakes the near-touch of two strokes in some copies of a type (a looped
    script 'f', a kana), which moves the count by one and nothing else. Two groups whose counts
    are one apart stay apart only when a witness confirms them as in :func:`_joint_split` (medians
    a resolution apart, rank-sum NFA over the witnesses tried below ``epsilon * JOINT_STRICTNESS``);
    counts further apart are not the hand's doing and stay apart.
    """
    groups = histogram.groups
    present = {k: np.unique(histogram.values[groups == k]) for k in np.unique(groups)}
    clusters = []
    for k in sorted(present, key=lambda k: present[k][0]):
        if clusters and present[k][0] - present[clusters[-1][-1]][-1] <= 1:
            lower = np.isin(groups, clusters[-1])
            subset = lower | (groups == k)
            own = {feature: values[feature][members[subset]] for feature in JOINT_FEATURES}
            tests = _witness_tests(own, lower[subset], "crossings", _joint_resolutions(parameters))
            nfa = len(tests) * min((p for p, apart, _ in tests if apart), default=np.inf)
            if nfa >= parameters["epsilon"] * JOINT_STRICTNESS:
                clusters[-1].append(k)
                continue
        clusters.append([k])
    if len(clusters) == len(present):
        return histogram
    cluster_of = np.zeros(len(histogram.group_names), dtype=np.int64)
    names, numbered = [], {"mode": 0, "outlier": 0}
    for j, cluster in enumerate(clusters):
        cluster_of[cluster] = j
        kind = "mode" if any(histogram.group_names[k].startswith("mode") for k in cluster) else "outlier"
        names.append(f"{kind}{numbered[kind]}")
        numbered[kind] += 1
    return replace(histogram, groups=_read_only(cluster_of[groups]), group_names=tuple(names))


def _candidate_cuts(feature: str, own: np.ndarray, least: int) -> list[np.ndarray]:
    """Masks of the lower side of a joint split's candidate cuts on one feature (see _joint_split)."""
    if feature in _COUNT_FEATURES:
        sides = [own < count for count in np.unique(own)[1:]]
        return [low for low in sides if least <= low.sum() <= own.size - least]
    widest = _widest_spacing(own, least)
    return [own <= widest[0]] if widest is not None and widest[1] > 0 else []


def _widest_spacing(values: np.ndarray, least: int) -> tuple[float, float] | None:
    """The widest spacing between sorted values that leaves ``least`` values on each side.

    Returns (the value just below it, its length), or None when there are fewer than ``2 * least`` values.
    """
    m = values.size
    if m < 2 * least:
        return None
    ordered = np.sort(values)
    spacing = np.diff(ordered)[least - 1 : m - least]
    k = int(np.argmax(spacing))
    return float(ordered[least - 1 + k]), float(spacing[k])


def _node_histogram(feature: str, own: np.ndarray, parameters: dict) -> FeatureHistogram:
    """Histogram of one feature over a group, with the groups it divides the group into."""
    epsilon = parameters["epsilon"]
    if feature in _COUNT_FEATURES:
        n_bins = int(max(COUNT_SCALE, own.max())) + 1
        edges = np.arange(n_bins + 1) - 0.5
        index = own.astype(np.int64)
        counts = np.bincount(index, minlength=n_bins)
        exact = feature == "crossings"
        analysis = _meaningful_counts(counts, epsilon) if exact else histogram_modes(counts, epsilon=epsilon)
    else:
        if feature == "orientation":
            own = unwrapped_orientation(own)
        edges = _feature_edges(feature, own, parameters["bins"])
        n_bins = edges.size - 1
        index = np.clip(np.searchsorted(edges, own, side="right") - 1, 0, n_bins - 1)
        counts = np.bincount(index, minlength=n_bins)
        analysis = histogram_modes(counts, epsilon=epsilon)
    group_of_bin, names = _bin_groups(analysis, epsilon)
    if feature in UNIMODAL_FEATURES:
        group_of_bin, names = _cut_into_unimodal_segments(counts, group_of_bin, names, epsilon)
    return FeatureHistogram(
        values=_read_only(own),
        edges=_read_only(edges),
        bins=_read_only(index),
        analysis=analysis,
        groups=_read_only(group_of_bin[index]),
        group_names=names,
    )


def _feature_edges(feature: str, own: np.ndarray, bins: int) -> np.ndarray:
    """Bin edges of a continuous feature: fixed bins over its domain, at the paper's resolution.

    Elongation: ``bins`` bins over the normalised ``[0, 1]``, the paper's. Orientation: the paper's
    bin width (a tenth of ``[0, 1]``) over the ``[0, 0.5)`` an axis occupies, so ``bins // 2``
    bins. Area: ``2 * bins`` bins per :data:`AREA_DECADES` decades of the normalised area, on a
    grid aligned on 0 (the cap at 1), over the bins the values occupy (two at least): bins of a
    factor 1.41 in area at the default, where the paper's linear bins put every element smaller
    than 0.5% of the surface in the first bin. Ink length (drawn by joint splits only): bins of
    :data:`INK_LENGTH_RESOLUTION` on a grid aligned on 0, over the bins the values occupy.
    """
    if feature == "elongation":
        return np.linspace(0.0, 1.0, bins + 1)
    if feature == "orientation":
        return np.linspace(0.0, 0.5, max(bins // 2, 2) + 1)
    if feature == "ink_length":
        return _occupied_grid(own, INK_LENGTH_RESOLUTION, cap=np.inf)
    return _occupied_grid(own, AREA_DECADES / (2 * bins), cap=0.0)


def _occupied_grid(own: np.ndarray, width: float, cap: float) -> np.ndarray:
    """Edges of the bins of a grid of ``width`` aligned on 0 that the values occupy, none above ``cap``."""
    low = np.floor(float(own.min()) / width)
    high = min(np.floor(float(own.max()) / width) + 1, cap)
    low = min(low, high - 2)  # a histogram has at least two bins
    return np.arange(low, high + 0.5) * width


def _split_at_value_gap(histogram: FeatureHistogram, parameters: dict) -> FeatureHistogram:
    """The histogram's group divided at the most meaningful empty gap between its sorted values.

    Unbinned counterpart of the paper's meaningful gap: under the background model (the ``m``
    values uniform between the smallest and the largest, as the uniform histogram prior), the
    expected number of the ``m - 1`` spacings at least ``g`` long is ``(m - 1) (1 - g / L)^(m - 2)``
    (``L`` the range). A spacing whose expectation is below ``epsilon`` and that leaves at least
    ``min_category_size`` values on each side divides the group; otherwise it is returned as is.
    A fixed bin grid can hide such a gap: two populations a factor 2 apart in size, with a hand's
    spread, leave an empty stretch of 0.28 decades of area that no bin of 0.15 decades falls in.
    """
    values = histogram.values
    widest = _widest_spacing(values, parameters["min_category_size"])
    if widest is None:
        return histogram
    cut, length = widest
    m = values.size
    log10_nfa = np.log10(m - 1) + (m - 2) * np.log10(max(1.0 - length / np.ptp(values), np.finfo(float).tiny))
    if length < np.diff(histogram.edges).min() or log10_nfa >= np.log10(parameters["epsilon"]):
        return histogram
    return replace(histogram, groups=_read_only((values > cut).astype(np.int64)),
                               group_names=("mode0", "mode1"))


def _meaningful_counts(counts: np.ndarray, epsilon: float) -> HistogramModes:
    """Counts held by meaningfully many elements, each alone a mode (eq. (1) on one bin).

    Outliers are the runs of non-empty bins that are not meaningful counts.
    """
    single = np.diag(interval_log10_nfa(counts))
    meaningful = (counts > 0) & (single < np.log10(epsilon))
    modes = tuple(Interval(int(b), int(b), float(single[b])) for b in np.flatnonzero(meaningful))
    return HistogramModes(
        counts=_read_only(counts.astype(np.int64)),
        prior=_read_only(np.full(counts.size, 1.0 / counts.size)),
        epsilon=float(epsilon),
        modes=modes,
        outliers=tuple(outlier_intervals(counts, modes)),
    )


def _bin_groups(analysis: HistogramModes, epsilon: float) -> tuple[np.ndarray, tuple[str, ...]]:
    """Group of each bin: the MM-modes, widened to the bins around them.

    The bins between two consecutive modes are cut at the least filled of them (the middle one on
    a tie), which goes to the nearer mode (the left one on a tie). The bins before the first mode join it, those after the last join it,
    unless an *empty* run of bins that is a meaningful gap cuts off the elements beyond it: those
    are an outlier group (the paper's outlier category). Sparse but non-empty bins never cut: the
    thin tails of a single population are "gaps" for the uniform background.
    """
    counts = analysis.counts
    n_bins = counts.size
    group = np.full(n_bins, -1, dtype=np.int64)
    modes = analysis.modes
    if not modes:
        return np.zeros(n_bins, dtype=np.int64), ("mode0",)
    for k, mode in enumerate(modes):
        group[mode.start : mode.end + 1] = k
    for k, (left, right) in enumerate(zip(modes[:-1], modes[1:])):
        between = np.arange(left.end + 1, right.start)
        if between.size:
            lowest = np.flatnonzero(counts[between] == counts[between].min())
            cut = between[lowest[(lowest.size - 1) // 2]]
            group[left.end + 1 : cut] = k
            group[cut + 1 : right.start] = k + 1
            group[cut] = k if cut - left.end <= right.start - cut else k + 1
    names = [f"mode{k}" for k in range(len(modes))]
    empty_gap = _empty_gaps(counts, epsilon)
    tails = ((np.arange(modes[0].start)[::-1], 0), (np.arange(modes[-1].end + 1, n_bins), len(modes) - 1))
    for bins, nearest in tails:
        group[bins] = nearest
        beyond = _cut_off(counts[bins], empty_gap[np.ix_(bins, bins)])
        if beyond is not None:
            group[bins[beyond:]] = len(names)
            names.append(f"outlier{len(names) - len(modes)}")
    return group, tuple(names)


def _cut_into_unimodal_segments(counts, group_of_bin, names, epsilon):
    """Each mode group cut where its bins are not one unimodal run (:func:`~paperlib.acontrario.unimodal_segments`).

    Returns the new group of each bin and the group names: modes by position, then outliers.
    """
    runs = []  # (is_mode, first bin, last bin) of every group, by position
    for k, name in enumerate(names):
        bins = np.flatnonzero(group_of_bin == k)
        if bins.size == 0:
            continue
        filled = bins[counts[bins] > 0]
        first, last = bins[0], bins[-1]
        pieces = [(first, last)]
        if name.startswith("mode") and 2 <= filled[-1] - filled[0] + 1 <= MAX_SEGMENTED_BINS:
            # segmented over its filled stretch; the empty bins at either end join the first or last piece
            pieces = [(start + filled[0], end + filled[0]) for start, end in
                      unimodal_segments(counts[filled[0] : filled[-1] + 1], epsilon)]
            pieces[0], pieces[-1] = (first, pieces[0][1]), (pieces[-1][0], last)
        runs += [(name.startswith("mode"), start, end) for start, end in pieces]
    runs.sort(key=lambda run: (not run[0], run[1]))
    group = np.empty_like(group_of_bin)
    for k, (_, start, end) in enumerate(runs):
        group[start : end + 1] = k
    n_modes = sum(is_mode for is_mode, _, _ in runs)
    return group, tuple([f"mode{k}" for k in range(n_modes)] + [f"outlier{k}" for k in range(len(runs) - n_modes)])


def _empty_gaps(counts: np.ndarray, epsilon: float) -> np.ndarray:
    """``[a, b]`` true where bins ``a..b`` (or ``b..a``) are all empty and an epsilon-meaningful gap."""
    filled = np.concatenate([[0], np.cumsum(counts > 0)])
    upper = np.triu((filled[None, 1:] - filled[:-1, None]) == 0) & (gap_log10_nfa(counts) < np.log10(epsilon))
    return upper | upper.T


def _cut_off(counts: np.ndarray, gap: np.ndarray):
    """Where the elements cut off from a mode start, in a tail read from the mode outwards.

    ``counts`` are the tail's bins from the one next to the mode outwards; ``gap[i, j]`` says
    whether bins ``i..j`` of the tail (in that order) are empty and a meaningful gap. Returns the
    index of the first bin beyond the meaningful empty gap nearest the mode, or None.
    """
    for end in range(counts.size - 1):
        if gap[: end + 1, end].any() and counts[end + 1 :].any():
            return end + 1
    return None



def _split_by_appearance(
    name,
    kind,
    members,
    table,
    columns,
    domain_box,
    circle_columns,
    n_bins,
    epsilon,
    min_size,
    histogram_range,
    unwrap,
    rng,
) -> AreaCategory:
    """Second stage on one area category: first robust component, its histogram and MM-modes."""
    if len(members) < min_size:
        return AreaCategory(name, kind, members, "too_few", categories=(name,))
    X = table[members].copy()
    if unwrap:
        column = columns.index("orientation")
        X[:, column] = unwrapped_orientation(X[:, column])
    if np.all(np.ptp(X, axis=0) <= _EQUAL_FEATURES):
        return AreaCategory(name, kind, members, "constant", categories=(name,))
    note = ""
    pca = None
    try:
        pca = robust_pca(X, 1, rng=rng)
        center, component, method = pca.center, pca.components[:, 0], "ROBPCA"
    except ExactFitError as error:
        center, component, method = _classical_first_component(X)
        note = str(error)
    scores = (X - center) @ component
    domain = None
    if histogram_range == "domain":
        domain = _projected_domain(domain_box, circle_columns, center, component)
        domain = (min(domain[0], scores.min()), max(domain[1], scores.max()))
    histogram = _feature_histogram(scores, n_bins, epsilon, domain)
    names = tuple(
        f"{name}.{'shape' if group_kind == 'mode' else 'outlier'}{index}"
        for _, group_kind, index in _groups_in_order(histogram, "", "", numbered=True)
    )
    if len(names) == 1:
        names = (name,)
    return AreaCategory(
        name,
        kind,
        members,
        "split",
        pca_features=columns,
        pca=pca,
        pca_method=method,
        component=np.array(component),
        center=np.array(center),
        histogram=histogram,
        categories=names,
        note=note,
    )


def unwrapped_orientation(orientation) -> np.ndarray:
    """Normalised orientations measured from the middle of the widest empty arc between them.

    Parameters
    ----------
    orientation : array_like, shape (m,)
        Normalised orientations ``theta / 2 pi`` in ``[0, 0.5)`` (axis angles in ``[0, pi)``).

    Returns
    -------
    ndarray, shape (m,)
        ``((theta - cut) mod pi) / 2 pi`` in ``[0, 0.5)``, where ``cut`` is the middle of the
        widest gap between consecutive angles around the half circle (the first such gap on a
        tie). Differences between close axes are the paper's, and no two close axes straddle
        the origin.
    """
    values = finite_array(orientation, "orientation", ndim=1) % 0.5
    if values.size == 0:
        return values
    ordered = np.sort(values)
    gaps = np.diff(np.append(ordered, ordered[0] + 0.5))
    widest = int(np.argmax(gaps))
    cut = ordered[widest] + gaps[widest] / 2.0
    return (values - cut) % 0.5


def _classical_first_component(X: np.ndarray) -> tuple[np.ndarray, np.ndarray, str]:
    """Mean and first principal direction (sign: largest entry positive, as ROBPCA's)."""
    center = X.mean(axis=0)
    _, _, vt = np.linalg.svd(X - center, full_matrices=False)
    component = vt[0]
    if component[np.argmax(np.abs(component))] < 0:
        component = -component
    return center, component, "classical"


def _appearance_matrix(features: pd.DataFrame, circular: bool):
    """The four appearance features as the PCA sees them, with the domain of each column.

    Returns the (n, p) matrix, its column names, the (lo, hi) box of the non-circular columns
    (NaN for the circle's), and the indices of the two circle columns (or None).
    """
    count_domain = (0.0, 1.0)  # counts over 10; larger counts widen the range with the data
    elongation = features["elongation"].to_numpy(dtype=float)
    extremities = features["extremities"].to_numpy(dtype=float)
    crossings = features["crossings"].to_numpy(dtype=float)
    if circular:
        angle = 2.0 * np.pi * features["orientation"].to_numpy(dtype=float)  # theta in [0, pi)
        columns = ("elongation", "orientation_cos", "orientation_sin", "extremities", "crossings")
        table = np.column_stack(
            [
                elongation,
                ORIENTATION_RADIUS * np.cos(2.0 * angle),
                ORIENTATION_RADIUS * np.sin(2.0 * angle),
                extremities,
                crossings,
            ]
        )
        box = np.array([(0.0, 1.0), (np.nan, np.nan), (np.nan, np.nan), count_domain, count_domain])
        circle = (1, 2)
    else:
        columns = ("elongation", "orientation", "extremities", "crossings")
        orientation = features["orientation"].to_numpy(dtype=float)
        table = np.column_stack([elongation, orientation, extremities, crossings])
        box = np.array([(0.0, 1.0), (0.0, 0.5), count_domain, count_domain])
        circle = None
    return table, columns, box, circle


def _projected_domain(box: np.ndarray, circle, center: np.ndarray, component: np.ndarray) -> tuple[float, float]:
    """Interval of ``(x - center) . component`` over the feature domain (box times circle)."""
    linear = ~np.isnan(box[:, 0])
    ends = box[linear] * component[linear, None]
    low = ends.min(axis=1).sum()
    high = ends.max(axis=1).sum()
    if circle is not None:
        reach = ORIENTATION_RADIUS * np.hypot(component[circle[0]], component[circle[1]])
        low, high = low - reach, high + reach
    shift = float(center @ component)
    return float(low - shift), float(high - shift)


def _feature_histogram(values: np.ndarray, n_bins: int, epsilon: float, domain) -> FeatureHistogram:
    """Histogram of ``values`` on ``n_bins`` bins over ``domain`` (or the data range) and its MM-modes."""
    if domain is None:
        low, high = float(values.min()), float(values.max())
    else:
        low, high = domain
    if high <= low:  # a single value: numpy's convention, a unit interval around it
        low, high = low - 0.5, high + 0.5
    edges = np.linspace(low, high, n_bins + 1)
    index = np.searchsorted(edges, values, side="right") - 1
    index = np.clip(index, 0, n_bins - 1)  # the last bin is closed; values lie within the edges
    counts = np.bincount(index, minlength=n_bins)
    analysis = histogram_modes(counts, epsilon=epsilon)
    group_of_bin = np.full(n_bins, -1, dtype=np.int64)
    names: list[str] = []
    intervals = [("mode", mode.start, mode.end) for mode in analysis.modes]
    intervals += [("outlier", start, end) for start, end in analysis.outliers]
    n_modes = n_outliers = 0
    for kind, start, end in intervals:
        free = np.flatnonzero(group_of_bin[start : end + 1] == -1) + start  # overlaps: first listed wins
        if counts[free].sum() == 0:
            continue
        group_of_bin[free] = len(names)
        if kind == "mode":
            names.append(f"mode{n_modes}")
            n_modes += 1
        else:
            names.append(f"outlier{n_outliers}")
            n_outliers += 1
    groups = group_of_bin[index]
    if np.any(groups < 0):  # every non-empty bin is in a mode or an outlier run
        raise AssertionError("an element fell outside every mode and outlier interval")
    return FeatureHistogram(
        values=_read_only(values),
        edges=_read_only(edges),
        bins=_read_only(index),
        analysis=analysis,
        groups=_read_only(groups),
        group_names=tuple(names),
    )


def _groups_in_order(histogram: FeatureHistogram, mode_prefix: str, outlier_prefix: str, numbered: bool = False):
    """(name, kind, local index) of a histogram's groups: modes first, then outliers, by position."""
    result = []
    for local, group in enumerate(histogram.group_names):
        kind = "mode" if group.startswith("mode") else "outlier"
        number = int(group[len(kind) :])
        if numbered:
            result.append((group, kind, number))
        else:
            prefix = mode_prefix if kind == "mode" else outlier_prefix
            result.append((f"{prefix}{number}", kind, local))
    return result


# --------------------------------------------------------------------------- checks


def _checked_bins(bins) -> int:
    if bins is None:
        return DEFAULT_BINS
    if isinstance(bins, (bool, np.bool_)) or not isinstance(bins, (int, np.integer)):
        raise TypeError(f"bins must be an int (or None for {DEFAULT_BINS}), got {bins!r}")
    if bins < 2:
        raise ValueError(f"bins must be at least 2, got {bins}")
    return int(bins)


def _checked_epsilon(epsilon) -> float:
    try:
        value = float(epsilon)
    except (TypeError, ValueError):
        raise TypeError(f"epsilon must be a positive number, got {epsilon!r}") from None
    if not np.isfinite(value) or value <= 0:
        raise ValueError(f"epsilon must be a positive finite number, got {epsilon!r}")
    return value


def _checked_min_size(size) -> int:
    if isinstance(size, (bool, np.bool_)) or not isinstance(size, (int, np.integer)):
        raise TypeError(f"min_category_size must be an int, got {size!r}")
    if size < 3:
        raise ValueError(f"min_category_size must be at least 3 (robust PCA needs 3 elements), got {size}")
    return int(size)


# --------------------------------------------------------------------------- agreement


def separability_ceiling(features: pd.DataFrame, labels, *, bins: int = DEFAULT_BINS, neighbours: int = 5) -> float:
    """How well the true types can be told apart on the features the recursive method cuts on.

    A control for :func:`categorize`: a classifier that *knows* the types labels each element by
    a vote of its ``neighbours`` nearest other elements (leave-one-out k-nearest neighbours; a tie
    goes to the nearest), in the space of :data:`JOINT_FEATURES` measured in units of the
    resolution a joint split reads them at (one count; one histogram bin of area or elongation;
    :data:`INK_LENGTH_RESOLUTION`). The adjusted Rand index of those labels against the types is
    a ceiling in practice: where it is below 0.9, the types overlap at the features' resolution
    and no categorization on them can divide them; where it is high and :func:`categorize` is
    not, the information is there and the unsupervised rules (which must also leave a type the
    hand varies whole) are what fails. Orientation is left out, as in joint splits.

    Parameters
    ----------
    features : pandas.DataFrame
        Output of :func:`~paperlib.arrangement.element_features` (e.g. ``Categorization.features``).
    labels : array_like, shape (n,)
        The true type of each element.
    bins : int, optional
        Histogram bins of the recursive method (default :data:`DEFAULT_BINS`): sets the area and
        elongation resolutions.
    neighbours : int, optional
        Neighbours voting for each element (default 5), in ``[1, n - 1]``.

    Returns
    -------
    float
        Adjusted Rand index of the leave-one-out labels against ``labels``.

    Raises
    ------
    ValueError
        If ``features`` lacks a column or holds fewer than 2 elements, ``labels`` is not 1-D with
        one label per element, or ``bins`` or ``neighbours`` is not an integer in range.
    TypeError
        If ``features`` is not a DataFrame.
    """
    values = recursive_feature_values(features)
    truth = np.asarray(labels)
    if truth.ndim != 1 or truth.size != len(features):
        raise ValueError(f"labels must be 1-D with one label per element ({len(features)}), got shape {truth.shape}")
    if truth.size < 2:
        raise ValueError(f"features must hold at least 2 elements, got {truth.size}")
    bins = integer_at_least(bins, "bins", 1)
    neighbours = integer_in_range(neighbours, "neighbours", 1, truth.size - 1)
    resolution = _joint_resolutions({"bins": bins})
    points = np.column_stack([values[feature] / resolution[feature] for feature in JOINT_FEATURES])
    _, nearest = cKDTree(points).query(points, k=min(neighbours + 1, truth.size))
    voted = np.array([_vote(truth, [j for j in row if j != i][:neighbours]) for i, row in enumerate(nearest)])
    return adjusted_rand_index(voted, truth)


def _vote(truth: np.ndarray, neighbours: list):
    """The most frequent label among ``neighbours`` (nearest first); a tie goes to the nearest's."""
    kinds, counts = np.unique(truth[neighbours], return_counts=True)
    most = kinds[counts == counts.max()]
    return most[0] if most.size == 1 else truth[neighbours[0]]


def adjusted_rand_index(labels_a, labels_b) -> float:
    """Adjusted Rand index of two partitions of the same items (Hubert and Arabie 1985).

    ``(sum_ij C(n_ij, 2) - E) / ((sum_i C(a_i, 2) + sum_j C(b_j, 2)) / 2 - E)`` with
    ``E = sum_i C(a_i, 2) sum_j C(b_j, 2) / C(n, 2)``, where ``n_ij`` is the contingency table
    and ``a_i``, ``b_j`` its margins: 1 for identical partitions (up to renaming), about 0 for
    independent ones, negative below chance. When both partitions are trivial in the same way
    (one group each, or all singletons, or fewer than 2 items) the ratio is 0/0 and the
    partitions are identical: 1 is returned, as scikit-learn does.

    Parameters
    ----------
    labels_a, labels_b : array_like, shape (n,)
        Group labels of each item (any comparable values: ints, strings).

    Returns
    -------
    float

    Raises
    ------
    ValueError
        If the label arrays are not 1-D, have different lengths or are empty.

    References
    ----------
    .. [1] L. Hubert, P. Arabie, "Comparing partitions", Journal of Classification 2, 1985,
       193-218.
    """
    a = np.asarray(labels_a)
    b = np.asarray(labels_b)
    if a.ndim != 1 or b.ndim != 1:
        raise ValueError(f"labels_a and labels_b must be 1-D, got shapes {a.shape} and {b.shape}")
    if a.size != b.size:
        raise ValueError(f"labels_a and labels_b must have the same length, got {a.size} and {b.size}")
    if a.size == 0:
        raise ValueError("labels_a and labels_b must not be empty, got 0 labels")
    _, a_index = np.unique(a, return_inverse=True)
    _, b_index = np.unique(b, return_inverse=True)
    a_index, b_index = a_index.ravel(), b_index.ravel()
    n_b = int(b_index.max()) + 1
    table = np.bincount(a_index * n_b + b_index).astype(np.int64)

    def pairs(counts):
        counts = np.asarray(counts, dtype=np.int64)
        return int(np.sum(counts * (counts - 1) // 2))

    together = pairs(table)
    rows = pairs(np.bincount(a_index))
    cols = pairs(np.bincount(b_index))
    total = a.size * (a.size - 1) // 2
    expected = rows * cols / total if total else 0.0
    maximum = (rows + cols) / 2.0
    if maximum == expected:
        return 1.0
    return float((together - expected) / (maximum - expected))
