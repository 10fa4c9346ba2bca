"""Barla et al. 2006, stroke pattern analysis and synthesis: vector strokes in, vector strokes out.

- :mod:`.analysis` (section 2): element fitting by oriented boxes, greedy clustering by proximity and
  continuation at the user scale epsilon, distribution (chain or unskewed Delaunay) and shift vectors.
- :mod:`.measures` (section 3.1): the shape, parallelism, overlapping, superimposition and colour measures and
  the rule ``col and (shape or (par and ov and sup))``.
- :mod:`.synthesis` (section 3.2, Algorithm 1): Lloyd seeds along a path or in a region, growth from the
  centre, k-ring neighbourhood matching.
- :mod:`.variation` (section 3.3): parameter exchange and position variation.
- :mod:`.render`: drawing strokes with matplotlib and writing SVG.
"""

from .analysis import (
    PatternAnalysis,
    analyze,
    as_region,
    chain_edges,
    cluster_strokes,
    continuation,
    fit_elements,
    graph_edges,
    proximity,
    shift_vectors,
    unskewed_delaunay_edges,
)
from .measures import MEASURES, Thresholds, measure_tables, rule_score
from .synthesis import (
    Seeds,
    Synthesis,
    growth_order,
    ring_neighbourhoods,
    seeds_1d,
    seeds_2d,
    synthesize,
    target_count,
)
from .render import plot_boxes, plot_graph, plot_strokes
from .variation import exchange_parameters, vary_positions

__all__ = [
    "MEASURES",
    "PatternAnalysis",
    "Seeds",
    "Synthesis",
    "Thresholds",
    "analyze",
    "as_region",
    "chain_edges",
    "cluster_strokes",
    "continuation",
    "exchange_parameters",
    "fit_elements",
    "graph_edges",
    "growth_order",
    "plot_boxes",
    "plot_graph",
    "plot_strokes",
    "measure_tables",
    "proximity",
    "ring_neighbourhoods",
    "rule_score",
    "seeds_1d",
    "seeds_2d",
    "shift_vectors",
    "synthesize",
    "target_count",
    "unskewed_delaunay_edges",
    "vary_positions",
]
