"""Kim et al. 2009, stippling by example.

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
  stippling (:func:`weighted_voronoi_stipples`, :func:`render_stipples`);
- :mod:`.extraction`: section 3.2, light / merged / dark levels, distribution textures (component
  centres; constrained Lloyd inside merged blobs) and the mark library (:func:`extract_distribution`,
  :func:`extract_marks`);
- :mod:`.rendering`: section 4, tone grays by pre-simulation, probabilistic tone selection
  (Fig. 10), distribution images from randomly rotated tiles, black then white mark placement,
  small-chunk removal (Fig. 11), all chained by :func:`render_stippling`;
- :mod:`.library`: the system of Figure 2, from example tone textures to a renderable
  :class:`StippleLibrary` (:func:`learn_stipple_library`).

Notebooks ``kim2009_*`` re-run the figures; :func:`paperlib.widgets.stipple_explorer` explores
the parameters; ``benchmarks/bench_stipple.py`` times synthesis and rendering.
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
    offset_directions,
    paper_offsets,
    pair_totals,
    to_bitonal,
)
from .library import StippleLibrary, learn_stipple_library
from .rendering import (
    PURE_BLACK,
    PURE_WHITE,
    ChunkRemoval,
    StippleRendering,
    distribution_image,
    level_grays,
    place_marks,
    remove_small_chunks,
    render_stippling,
    render_tone,
    select_tones,
    tone_gray_levels,
)
from .spacing import (
    SpacingComparison,
    block_dispersion,
    compare_spacing,
    nearest_neighbour_distances,
    pair_correlation,
    stipple_pattern,
)
from .synthesis import (
    StippleGeometry,
    SynthesisResult,
    paper_radius_quantiles,
    stipple_geometry,
    synthesize_distribution,
)
from .tone_map import ToneMap, block_gray_levels, extract_tone_map, largest_rectangle, segment_blocks
from .voronoi_stippling import (
    VoronoiStipples,
    render_stipples,
    stipple_density,
    weighted_centroids,
    weighted_voronoi_stipples,
)

__all__ = [
    "ace", "ace_change_kernel", "block_dispersion", "block_gray_levels", "compare_spacing", "check_bitonal", "ChunkRemoval", "classify_level",
    "cooccurrence_counts", "distribution_image", "DistributionResult", "extract_distribution", "extract_marks",
    "extract_tone_map", "flip_update", "flip_update_kernel", "glcm_features", "GLCMFeatures", "largest_rectangle",
    "LEVELS", "learn_stipple_library", "level_grays", "offset_directions", "paper_radius_quantiles", "PURE_BLACK", "PURE_WHITE", "Mark", "nearest_neighbour_distances", "pair_correlation", "normalized_glcms", "pair_totals", "paper_offsets", "place_marks", "remove_small_chunks",
    "render_stipples", "render_stippling", "render_tone", "segment_blocks", "select_tones", "SpacingComparison", "stipple_density", "stipple_pattern",
    "stipple_geometry", "StippleGeometry", "StippleLibrary", "StippleRendering", "SynthesisResult", "synthesize_distribution",
    "to_bitonal", "tone_gray_levels", "ToneMap", "VoronoiStipples", "weighted_centroids",
    "weighted_voronoi_stipples"
]
