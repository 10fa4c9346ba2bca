"""Kim 2009 stippling: synthesis of one 256 x 256 tone texture, rendering of a 4096 x 4096 image.

Exemplars (made untimed) are synthetic: :func:`paperlib.datasets.stipple_tone_texture` and
:func:`paperlib.datasets.stipple_tone_sheet` (seeded; there are no public hand-drawn stipples).

1. "stipple: synthesize 256x256 distribution (<=30 its)": the paper's case (section 3.4). The
   example distribution texture is extracted (3.2) from a 256 x 256 synthetic tone texture of
   the given ink tone (sizes = tone in percent); :func:`synthesize_distribution` runs with the
   paper's maximum of 30 iterations and stops at the first iteration that no longer lowers the
   ACE. The default ``spacing="matched"`` runs up to four trial syntheses and keeps the one whose
   nearest-neighbour distances come closest to the example's. Paper: about 12 min for a 256 x 256
   texture; target (issues 5 and 18): <= 10 s. Baseline, same run: one synthesis with the
   paper's radius rule (``spacing="paper"``), so the ratio is the cost of the matched spacing.
1b. "stipple: synthesize 256x256, paper radius rule": that baseline against the same synthesis
   without the geometric constraint of 3.4.2 (``geometry=False``), the plain spin flips the
   paper accelerates.
1c. "stipple: synthesize NxN from NxN example, paper radius rule": how the cost grows with the
   side (3 (n - 1) offsets per flip, n^2 pixels: n^3 if the iterations stay the same); tone 50%.
2. "stipple: 256x256 raw texture, no constraint": the worst case for the 10 s target: the
   bitonal tone texture itself (marks, not their centres) as the example, without the geometric
   constraint, so every pixel is tried in every iteration; it stops by itself after about 16
   of the 30 iterations. Baseline, same run: 1 iteration of the same synthesis, so the ratio is
   the number of full-image iterations the timed run costs (30 would be the ceiling).
3. "stipple: render NxN image (section 4)": a stipple library learnt once, untimed, from the
   8-tone synthetic sheet (256 x 256 tiles, 30 iterations); the timed call renders scikit-image's
   camera, resized to N x N, with :meth:`StippleLibrary.render`: tone selection, the distribution
   image from rotated tiles, mark placement, and small-chunk removal (``min_chunk=3``). Paper:
   about 28 s at 4096 x 4096; target (issue 5): <= 5 s. Baseline, same run: 8 x 8 ordered
   (Bayer) dithering of the same image, the cheapest halftoning there is.
"""

from functools import cache

import numpy as np
from skimage.transform import resize

from paperlib.datasets import grayscale_image, stipple_tone_sheet, stipple_tone_texture
from paperlib.stipple import extract_distribution, extract_tone_map, learn_stipple_library, synthesize_distribution
from registry import benchmark

SIZE = 256


def distribution_example(tone_percent: int) -> np.ndarray:
    return extract_distribution(stipple_tone_texture(tone_percent / 100, SIZE, rng=1)).distribution


def synthesis(example, iterations=30, geometry=None, spacing="matched"):
    synthesize_distribution(example[:32, :32], iterations=1, rng=0)  # numba kernels loaded outside the timing
    return lambda: synthesize_distribution(example, iterations=iterations, geometry=geometry, spacing=spacing, rng=2)


@benchmark("stipple: synthesize 256x256 distribution (<=30 its)", sizes=[10, 50, 85],
           baseline=lambda tone: synthesis(distribution_example(tone), spacing="paper"),
           baseline_name="paper's radius rule, one run", reference={50: {"Kim 2009 (paper, 256x256)": 720.0}})
def synthesize_distribution_case(tone_percent):
    return synthesis(distribution_example(tone_percent))


@benchmark("stipple: synthesize 256x256, paper radius rule", sizes=[10, 50, 85],
           baseline=lambda tone: synthesis(distribution_example(tone), geometry=False),
           baseline_name="no geometric constraint (3.4.2)")
def synthesize_paper_rule(tone_percent):
    return synthesis(distribution_example(tone_percent), spacing="paper")


@benchmark("stipple: synthesize NxN from NxN example, paper radius rule", sizes=[128, 256, 512])
def synthesize_by_side(side):
    example = extract_distribution(stipple_tone_texture(0.5, side, rng=1)).distribution
    return synthesis(example, spacing="paper")


def raw_example(tone_percent: int) -> np.ndarray:
    return stipple_tone_texture(tone_percent / 100, SIZE, rng=1)


@benchmark("stipple: 256x256 raw texture, no constraint", sizes=[50],
           baseline=lambda tone: synthesis(raw_example(tone), iterations=1, geometry=False),
           baseline_name="1 iteration, same example")
def synthesize_unconstrained(tone_percent):
    return synthesis(raw_example(tone_percent), geometry=False)


@cache
def library():
    sheet, *_ = stipple_tone_sheet(n_tones=8, block=SIZE, rng=0)
    return learn_stipple_library(extract_tone_map(sheet, block_size=32), size=SIZE, rng=0, workers=2)


def camera(side: int) -> np.ndarray:
    return resize(grayscale_image("camera"), (side, side), order=1, anti_aliasing=False)


BAYER_8 = np.array([[0, 32, 8, 40, 2, 34, 10, 42], [48, 16, 56, 24, 50, 18, 58, 26],
                    [12, 44, 4, 36, 14, 46, 6, 38], [60, 28, 52, 20, 62, 30, 54, 22],
                    [3, 35, 11, 43, 1, 33, 9, 41], [51, 19, 59, 27, 49, 17, 57, 25],
                    [15, 47, 7, 39, 13, 45, 5, 37], [63, 31, 55, 23, 61, 29, 53, 21]])


def ordered_dither(side: int):
    image = camera(side)
    threshold = (np.tile(BAYER_8, (side // 8 + 1, side // 8 + 1))[:side, :side] + 0.5) / 64
    return lambda: image < threshold  # True = ink


@benchmark("stipple: render NxN image (section 4)", sizes=[1024, 4096],
           baseline=ordered_dither, baseline_name="8x8 ordered dithering",
           reference={4096: {"Kim 2009 (paper)": 28.0}})
def render_image(side):
    learnt, image = library(), camera(side)
    return lambda: learnt.render(image, min_chunk=3, rng=1)
