"""Kim et al. 2009, stippling by example.

Done so far (issue 5 in progress):

- :mod:`.tone_map`: section 3.1, tone maps extracted from a stipple drawing
  (:func:`extract_tone_map`: N x N block grays, regions within T1, tones within T2,
  largest rectangular textures);
- :mod:`.glcm`: sections 3.3 and 3.4.1, bitonal GLCMs of horizontal, vertical and diagonal
  offsets, contrast / energy / correlation (eqs. 2-4, checked against scikit-image), the
  average co-occurrence error ACE (eq. 5), and numba kernels that update the co-occurrence
  counts in O(offsets) per pixel flip for the synthesis of section 3.4.

Stipple extraction (3.2), synthesis (3.4), rendering (4) and the notebooks are to come.
"""

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
from .tone_map import ToneMap, block_gray_levels, extract_tone_map, largest_rectangle, segment_blocks

__all__ = [
    "GLCMFeatures", "ToneMap", "ace", "ace_change_kernel", "block_gray_levels", "check_bitonal",
    "cooccurrence_counts", "extract_tone_map", "flip_update", "flip_update_kernel", "glcm_features",
    "largest_rectangle", "normalized_glcms", "paper_offsets", "pair_totals", "segment_blocks", "to_bitonal",
]
