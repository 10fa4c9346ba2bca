"""From example tone textures to a renderable stipple library (Kim et al. 2009, Figure 2).

The paper's system (its Figure 2) runs once per artist: example textures of the tone map
(section 3.1) -> example distribution textures and mark libraries (3.2) -> synthesized
distribution textures (3.4) -> tone grays by pre-simulation (4.1). The result is all the
rendering of section 4 needs; the pure white and pure black tones that frame every tone map
(section 3.2, "Tone 0 and 9 are pure white and black respectively") need no learning and are
added by the rendering. :func:`learn_stipple_library` chains those steps, and
:class:`StippleLibrary` keeps every intermediate so that notebooks can show and measure them
(Figures 5, 7 and 8) and :meth:`StippleLibrary.render` can stipple any number of images.

Every tone gets its own random stream spawned from ``rng`` (:mod:`paperlib.parallel`), so
the library is the same bit for bit whether its tones are synthesized one after another or in
parallel processes.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import partial

import numpy as np

from ..parallel import progress_enabled, run_many, spawn_seeds
from .extraction import DistributionResult, Mark, classify_level, extract_distribution, extract_marks
from .glcm import _checked_bitonal
from .rendering import StippleRendering, level_grays, render_stippling, tone_gray_levels
from .synthesis import SynthesisResult, synthesize_distribution
from .tone_map import ToneMap

__all__ = ["StippleLibrary", "learn_stipple_library"]


@dataclass(frozen=True)
class StippleLibrary:
    """Everything learnt from one artist's tone textures, lightest tone first.

    Parameters
    ----------
    examples : list of ndarray of bool
        The example stipple textures (``True`` = ink).
    distributions : list of DistributionResult
        Their example distribution textures (section 3.2).
    syntheses : list of SynthesisResult
        The synthesized distribution textures (section 3.4), one square tile per tone.
    marks : list of list of Mark
        The mark library of every tone (section 3.2, used in 4.2).
    tone_grays : ndarray of float
        Gray of every stipple tone in [0, 1] (1 white), pre-simulated from its tile and marks
        (4.1). The pure white and black tones of the paper's tone maps (3.2) need no texture and
        are not listed; :attr:`level_grays` adds them, and :meth:`render` uses them.
    """

    examples: list
    distributions: list
    syntheses: list
    marks: list
    tone_grays: np.ndarray

    def __len__(self) -> int:
        return len(self.examples)

    @property
    def tiles(self) -> list[np.ndarray]:
        """The synthesized distribution tiles, as :func:`render_stippling` takes them."""
        return [synthesis.texture for synthesis in self.syntheses]

    @property
    def levels(self) -> list[str]:
        """Level of every tone: ``"light"``, ``"merged"`` or ``"dark"``."""
        return [distribution.level for distribution in self.distributions]

    @property
    def level_grays(self) -> np.ndarray:
        """Grays of the rendering's levels: pure white (tone 0), the stipple tones, pure black (3.2)."""
        return level_grays(self.tone_grays)

    def render(self, image, *, min_chunk: int = 1, pure_levels: bool = True, rng=None) -> StippleRendering:
        """Stipple a grayscale image (0 black .. 1 white) with this library (section 4).

        ``pure_levels`` (default True) renders with the paper's pure white and pure black tones
        around the library's stipple tones (section 3.2: "Tone 0 and 9 are pure white and black
        respectively"), so white stays paper and black is solid ink; False clamps every gray to
        the library's tones (:func:`paperlib.stipple.render_stippling`).

        Parameters
        ----------
        image : array_like of float, 2-D
            Input intensities in [0, 1] (0 black, 1 white).
        min_chunk : int, default 1
            :func:`remove_small_chunks`' ``min_size``; 1 is no removal.
        pure_levels : bool, default True
            Render with the pure white and pure black levels around the library's tones.
        rng : None, int or numpy.random.Generator, optional
            Random source; a seed fixes the output bit for bit.

        Returns
        -------
        StippleRendering
            The stipple image, its level map and distribution image.
        """
        return render_stippling(image, self.tiles, self.marks, tone_grays=self.tone_grays, min_chunk=min_chunk,
                                pure_levels=pure_levels, rng=rng)


def _example_textures(tone_textures) -> list[np.ndarray]:
    if not isinstance(tone_textures, ToneMap) and (
            isinstance(tone_textures, (str, bytes)) or not hasattr(tone_textures, "__iter__")):
        raise TypeError(f"tone_textures must be a ToneMap or a sequence of bitonal 2-D arrays, "
                        f"got {type(tone_textures).__name__}")
    textures = tone_textures.textures if isinstance(tone_textures, ToneMap) else list(tone_textures)
    if len(textures) < 2:
        raise ValueError(f"tone_textures must hold at least two tone textures (a stipple library needs them), "
                         f"got {len(textures)}")
    return [_checked_bitonal(texture, f"tone_textures[{index}]") for index, texture in enumerate(textures)]


def _tile_size(size, examples) -> int:
    if size is None:
        return min(min(texture.shape) for texture in examples)
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)) or size < 2:
        raise ValueError(f"size must be an integer >= 2 (the side of the square tiles), got {size!r}")
    return int(size)


def _resolved_levels(levels, examples) -> list[str]:
    levels = ["auto"] * len(examples) if levels is None else list(levels)
    if len(levels) != len(examples):
        raise ValueError(f"need one level per tone texture: {len(examples)} textures, {len(levels)} levels")
    return [classify_level(texture) if level == "auto" else level for level, texture in zip(levels, examples)]


def _light_reference(examples, levels) -> tuple[float | None, list[Mark] | None]:
    """S_avg and marks of the darkest light tone: the stipples before marks start to merge."""
    light = [texture for texture, level in zip(examples, levels) if level == "light"]
    if not light:
        return None, None
    return extract_distribution(light[-1], "light").s_avg, extract_marks(light[-1], "light")


def _learn_tone(task, *, size: int, iterations: int, rng) -> tuple[DistributionResult, SynthesisResult, list[Mark]]:
    """Sections 3.2 and 3.4 for one example texture; ``marks`` None: its own mark library."""
    texture, level, s_avg, marks = task
    distribution = extract_distribution(texture, level, s_avg=s_avg)
    synthesis = synthesize_distribution(distribution.distribution, size=size, iterations=iterations, rng=rng)
    return distribution, synthesis, extract_marks(texture, distribution.level) if marks is None else marks


def learn_stipple_library(
    tone_textures, *, size=None, iterations: int = 30, levels=None, gray_repeats: int = 1, workers: int = 1, rng=None,
    progress=None,
) -> StippleLibrary:
    """Learn a stipple library from example tone textures (Kim et al. 2009, sections 3.2-4.1).

    Parameters
    ----------
    tone_textures : ToneMap or sequence of array_like
        The example stipple textures, lightest tone first, bitonal (``True`` / 1 = ink), e.g.
        :func:`paperlib.stipple.extract_tone_map`'s result. At least two.
    size : int, optional
        Side of the square synthesized tiles; default the shortest side of the examples (the
        paper synthesizes 256 x 256 tiles from 256 x 256 examples). A tile larger than an
        example is allowed, but its GLCM offsets stop at the example's side, so density
        variations at larger scales are not constrained: from a 96 px example, a 256 px tile's
        32 px block counts had a variance-to-mean ratio of 3.2 against the example's 0.24.
    iterations : int, optional
        Maximum synthesis iterations per tone (paper: 30).
    levels : sequence of str, optional
        Level of every tone (``"light"``, ``"merged"``, ``"dark"`` or ``"auto"``); default all
        ``"auto"`` (:func:`paperlib.stipple.classify_level`).
    gray_repeats : int, optional
        Pre-simulations averaged per tone gray (:func:`tone_gray_levels`).
    workers : int, optional
        Processes synthesizing tones in parallel (default 1, this process); the result does not
        depend on it.
    rng : None, int or numpy.random.Generator, optional
        Random source; a seed fixes the library bit for bit.
    progress : bool or None, optional
        Show a tqdm bar over the tones (learning took 3 s for eight 128 px tones and 24 s at
        the paper's 256 px on one core); default None shows it only when stderr is a terminal
        (:func:`paperlib.parallel.progress_enabled`). The bar never changes the result.

    Returns
    -------
    StippleLibrary

    Raises
    ------
    ValueError
        Fewer than two textures, non-bitonal or empty textures, a tile side < 2, a wrong
        number of levels, ``iterations`` < 1, and the errors of the steps.
    TypeError
        ``progress`` neither a bool nor None.

    Notes
    -----
    Merged tones borrow the darkest light tone's S_avg (to split their blobs into stipples)
    and mark library (to draw them), when there is a light tone. The paper does not say where
    a merged level's stipple size and marks come from; its own separate dots are the smallest
    of its marks (the larger ones merged): their median size overcounts the stipples by up to
    57% on our synthetic tones, and drawing with them renders a 0.67-ink tone at 0.25 ink.
    Without a light tone, merged tones use their own dots.

    References
    ----------
    Kim et al. 2009, Figure 2 (the system), 3.2 (distributions, marks), 3.4 (synthesis), 4.1
    (tone grays by pre-simulation).
    """
    progress_enabled(progress)  # a wrong value fails before any work
    examples = _example_textures(tone_textures)
    size = _tile_size(size, examples)
    levels = _resolved_levels(levels, examples)
    # merged blobs are split into, and drawn with, the stipples a light tone shows (3.2): the
    # dots that stay separate in a merged texture are its smallest ones
    s_avg, light_marks = _light_reference(examples, levels)
    tasks = [
        (texture, level, *((s_avg, light_marks) if level == "merged" else (None, None)))
        for texture, level in zip(examples, levels)
    ]
    synthesis_seed, gray_seed = spawn_seeds(rng, 2)
    learn = partial(_learn_tone, size=size, iterations=iterations)
    learnt = run_many(learn, tasks, rng=synthesis_seed, workers=workers, progress=progress, desc="stipple tones")
    distributions, syntheses, marks = (list(column) for column in zip(*learnt))
    grays = tone_gray_levels(
        [synthesis.texture for synthesis in syntheses], marks, repeats=gray_repeats, rng=np.random.default_rng(gray_seed)
    )
    return StippleLibrary(examples, distributions, syntheses, marks, grays)
