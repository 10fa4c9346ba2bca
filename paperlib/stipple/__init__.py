"""Kim et al. 2009, stippling by example.

Done so far (issue 5 in progress):

- :mod:`.tone_map`: section 3.1, tone maps extracted from a stipple drawing
  (:func:`extract_tone_map`: N x N block grays, regions within T1, tones within T2,
  largest rectangular textures);
- :mod:`.glcm`: sections 3.3 and 3.4.1, bitonal GLCMs of horizontal, vertical and diagonal
  offsets, contrast / energy / correlation (eqs. 2-4, checked against scikit-image), the
  average co-occurrence error ACE (eq. 5), and numba kernels that update the co-occurrence
  counts in O(offsets) per pixel flip for the synthesis of section 3.4;
- :mod:`.synthesis`: section 3.4, spin-flip minimisation of ACE under the geometric constraint
  of 3.4.2 (:func:`synthesize_distribution`), with the stipple geometry of 3.2
  (:func:`stipple_geometry`: S_avg, O_min, O_avg, O_max);
- :mod:`.voronoi_stippling`: the baseline of the comparisons, Secord's (2002) weighted Voronoi
  stippling (:func:`weighted_voronoi_stipples`, :func:`render_stipples`).

- :mod:`.extraction`: section 3.2, light / merged / dark levels, distribution textures (component
  centres; constrained Lloyd inside merged blobs) and the mark library (:func:`extract_distribution`,
  :func:`extract_marks`).

Rendering (4), the notebooks and the widget are to come.
"""

from .extraction import LEVELS, DistributionResult, Mark, classify_level, extract_distribution, extract_marks
from .glcm import (
    GLCMFeatures,
    ace,
    ace_change_kernel,
    check_bitonal,
    cooccurrence_counts,
    flip_update,
    flip_update_kernel,
    glcm_features,
    normalized_glcms,
    paper_offsets,
    pair_totals,
    to_bitonal,
)
from .synthesis import StippleGeometry, SynthesisResult, stipple_geometry, synthesize_distribution
from .tone_map import ToneMap, block_gray_levels, extract_tone_map, largest_rectangle, segment_blocks
from .voronoi_stippling import (
    VoronoiStipples,
    render_stipples,
    stipple_density,
    weighted_centroids,
    weighted_voronoi_stipples,
)

__all__ = [
    "LEVELS", "DistributionResult", "GLCMFeatures", "Mark", "classify_level", "extract_distribution", "extract_marks", "StippleGeometry", "SynthesisResult", "ToneMap", "VoronoiStipples", "ace", "ace_change_kernel", "block_gray_levels", "check_bitonal",
    "cooccurrence_counts", "extract_tone_map", "flip_update", "flip_update_kernel", "glcm_features",
    "largest_rectangle", "normalized_glcms", "paper_offsets", "pair_totals", "render_stipples", "segment_blocks", "stipple_density", "stipple_geometry",
    "synthesize_distribution", "to_bitonal", "weighted_centroids", "weighted_voronoi_stipples",
]
