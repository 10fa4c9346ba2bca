"""ML-texture scripts: every hyper-parameter of a texture in one JSON document (Alvarez 2015, 4, 5.4).

"Each execution also produces a text file or script containing the image parameters. The same
script can be employed again with variations left to the user" (section 4). A :class:`Script`
holds the image size, the geometry seed ``Seed(L)``, the layers (:class:`Layer`) and the
rendering parameters of section 5.4 (:class:`RenderSettings`, with their own seed, so geometry and
colours change independently: Figs. 17 and 18). Scripts round-trip through JSON files
(:meth:`Script.save`, :meth:`Script.load`); unknown, missing and out-of-range keys are rejected
with a message naming them.

:func:`sample_script` is the paper's automatic mode: "ranges are fixed for each parameter, which
are then uniformly sampled in this range" (section 4). The ranges are ours (the paper does not
list its own) and are the module constants below; the palette image is the user's choice.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field
from pathlib import Path


from .._atomic import atomic_path
from .._checks import as_generator, load_json, positive_number
from .layers import Layer, check_exact_keys, checked_layers
from ..datasets import photograph_names
from .texels import TEXELS

__all__ = ["RenderSettings", "Script", "sample_script", "SCRIPT_VERSION"]

SCRIPT_VERSION = 1

# ---- ranges of the automatic mode (uniform draws; sizes relative to the image's shorter side)
LAYER_COUNT_RANGE = (2, 5)  # N_L, counting the image rectangle
TEXELS_PER_LAYER_RANGE = (1, 3)
MAX_OBJECTS_RANGE = (2, 40)  # per father; the first drawn layer gets up to 4x more (one father only)
ASPECT_RATIO_RANGE = (1.0, 6.0)
DIAMETER_RANGE = (0.03, 0.6)  # of the shorter image side, for the first drawn layer
CHILD_DIAMETER_RANGE = (0.1, 0.7)  # of the father layer's diameter
MAX_TRIALS_RANGE = (5, 40)
SIZE_REDUCTION_RANGE = (0.5, 0.95)
MAX_REDUCTIONS_RANGE = (0, 8)
VANISHING_RANGE = (0.0, 1.5)
OBJECTS_PER_LAYER = 4000  # Max_O is capped so that no layer tries more objects (the paper: ~3,000 in all)
FINITE_POINT_PROBABILITY = 0.3  # orientation points at a finite position, else at infinity
TRANSPARENCY_RANGE = (0.0, 0.8)  # upper bound of the objects' random transparency
LIGHT_PROBABILITY = 0.5
LIGHT_DISTANCE_RANGE = (0.2, 2.0)  # of the shorter image side
TESSELLATION_PROBABILITY = 0.2
KEEP_FATHER_PROBABILITY = 0.3


def _flag(value, name: str) -> bool:
    if not isinstance(value, bool):
        raise ValueError(f"{name} must be true or false, got {value!r}")
    return value


def _seed(value, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value < 2**63:
        raise ValueError(f"{name} must be an integer in [0, 2**63), got {value!r}")
    return value


@dataclass(frozen=True)
class RenderSettings:
    """Rendering parameters of section 5.4 (besides the image size, which the script holds).

    Parameters
    ----------
    palette : str
        The palette image (5.1): a bundled scikit-image photograph name
        (:func:`paperlib.datasets.photograph_names`), checked on creation. A script shared as JSON
        cannot make its reader fetch a URL or read a file; to colour with a local image, pass
        ``palette=load_palette(pathlib.Path(...))`` to :func:`paperlib.mlts.render`.
    seed : int
        "Seed to initiate random assignment of palette colors to objects" (and transparencies,
        light points): colours change, geometry stays (Fig. 18).
    transparency : float
        Objects draw their transparency uniformly in ``[0, transparency]`` (5.2: 0 opaque, 1
        invisible); 0 makes every object opaque.
    light_distance : float
        Height of each object's light spot above its light point, in pixels (5.3); 0 turns the
        light spot effect off.
    tessellation : bool
        Colour the connected components of the arrangement of object boundaries instead of the
        objects (Fig. 15).
    keep_father_inclusion : bool
        Draw every object only inside its father (the second inclusion mode of section 3).
    samples : int
        Anti-aliasing: samples x samples points per pixel.
    """

    palette: str = "chelsea"
    seed: int = 0
    transparency: float = 0.0
    light_distance: float = 0.0
    tessellation: bool = False
    keep_father_inclusion: bool = False
    samples: int = 4

    def __post_init__(self):
        if not isinstance(self.palette, str) or self.palette not in photograph_names():
            raise ValueError(f"palette must name a bundled photograph ({', '.join(photograph_names())}), got "
                             f"{self.palette!r:.100}; pass a local image to render(..., palette=) instead")
        _seed(self.seed, "render seed")
        transparency = positive_number(self.transparency, "transparency", allow_zero=True)
        if transparency > 1:
            raise ValueError(f"transparency must lie in [0, 1], got {self.transparency!r}")
        object.__setattr__(self, "transparency", transparency)
        object.__setattr__(self, "light_distance", positive_number(self.light_distance, "light_distance",
                                                                   allow_zero=True))
        _flag(self.tessellation, "tessellation")
        _flag(self.keep_father_inclusion, "keep_father_inclusion")
        if isinstance(self.samples, bool) or not isinstance(self.samples, int) or not 1 <= self.samples <= 16:
            raise ValueError(f"samples must be an integer in [1, 16], got {self.samples!r}")


@dataclass(frozen=True)
class Script:
    """Everything that determines an ML-texture image (sections 4 and 5.4).

    Parameters
    ----------
    width, height : int
        Image size in pixels.
    seed : int
        ``Seed(L)``, the seed of the geometry.
    layers : tuple of Layer
        Layers 2..N_L (the first, the image rectangle, is implicit); at least one.
    render : RenderSettings
    """

    width: int = 512
    height: int = 512
    seed: int = 0
    layers: tuple = (Layer(),)
    render: RenderSettings = field(default_factory=RenderSettings)

    def __post_init__(self):
        for name in ("width", "height"):
            _pixels(getattr(self, name), name)
        _seed(self.seed, "seed")
        layers = checked_layers(self.layers)
        if not layers:
            raise ValueError("layers: a script needs at least one layer besides the image rectangle (N_L >= 2)")
        object.__setattr__(self, "layers", layers)
        if not isinstance(self.render, RenderSettings):
            raise ValueError(f"render must be RenderSettings, got {type(self.render).__name__}")

    # ------------------------------------------------------------------ JSON

    def to_dict(self) -> dict:
        """The script as plain JSON-ready values, with the format's version.

        Returns
        -------
        dict
            ``version``, ``width``, ``height``, ``seed``, ``layers`` (a list of
            :meth:`Layer.to_dict` mappings) and ``render`` (the :class:`RenderSettings` fields).
        """
        return {
            "version": SCRIPT_VERSION,
            "width": self.width,
            "height": self.height,
            "seed": self.seed,
            "layers": [layer.to_dict() for layer in self.layers],
            "render": asdict(self.render),
        }

    def to_json(self) -> str:
        """The script as JSON text (:meth:`to_dict`, indented by one space).

        Returns
        -------
        str
            The JSON text, readable by :meth:`from_json`.
        """
        return json.dumps(self.to_dict(), indent=1)

    @classmethod
    def from_dict(cls, values) -> "Script":
        """A script from :meth:`to_dict`'s mapping; unknown, missing or bad keys raise ValueError.

        Parameters
        ----------
        values : dict
            A mapping as :meth:`to_dict` gives: ``version`` equal to the current script version, and
            exactly the keys ``width``, ``height``, ``seed``, ``layers``, ``render``.

        Returns
        -------
        Script
            The validated script.
        """
        if not isinstance(values, dict):
            raise ValueError(f"a script must be a JSON object, got {type(values).__name__}")
        values = dict(values)
        version = values.pop("version", None)
        if version != SCRIPT_VERSION:
            raise ValueError(f"script version must be {SCRIPT_VERSION}, got {version!r}")
        check_exact_keys(values, cls, "script")
        check_exact_keys(values["render"], RenderSettings, "render")
        if not isinstance(values["layers"], list):
            raise ValueError("script 'layers' must be a list of layer objects")
        layers = tuple(_layer_from_dict(index, layer) for index, layer in enumerate(values["layers"]))
        return cls(values["width"], values["height"], values["seed"], layers, RenderSettings(**values["render"]))

    @classmethod
    def from_json(cls, text: str) -> "Script":
        """A script from JSON text; bad syntax, nesting too deep and bad keys raise ValueError.

        Parameters
        ----------
        text : str
            JSON text of a :meth:`to_dict` mapping.

        Returns
        -------
        Script
            The validated script.
        """
        return cls.from_dict(load_json(text, "a JSON script"))

    def save(self, path) -> Path:
        """Write the script as JSON (atomically: no half-written file).

        Parameters
        ----------
        path : str or os.PathLike
            The file to write (missing folders are created).

        Returns
        -------
        pathlib.Path
            ``path``, as written.
        """
        path = Path(path)
        with atomic_path(path) as temporary:
            temporary.write_text(self.to_json() + "\n")
        return path

    @classmethod
    def load(cls, path) -> "Script":
        """Read a script written by :meth:`save`.

        Parameters
        ----------
        path : str or os.PathLike
            The JSON file.

        Returns
        -------
        Script
            The validated script.

        Raises
        ------
        ValueError
            When the file cannot be read, or its JSON is not a valid script.
        """
        try:
            text = Path(path).read_text()
        except OSError as exc:
            raise ValueError(f"cannot read script {path}: {exc.strerror or exc}") from None
        return cls.from_json(text)


def _layer_from_dict(index: int, values) -> Layer:
    """Layer ``index`` of a script's JSON, its errors prefixed with where they are."""
    try:
        return Layer.from_dict(values)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"script layer {index}: {exc}") from None


# ---------------------------------------------------------------------------- automatic mode


def _uniform(rng, bounds) -> float:
    return float(rng.uniform(*bounds))


def _integer(rng, bounds) -> int:
    return int(rng.integers(bounds[0], bounds[1] + 1))


def _orientation_point(rng, width: int, height: int) -> tuple:
    """A random projective point: at infinity in a uniform direction, or finite near the image."""
    if rng.random() < FINITE_POINT_PROBABILITY:
        x = rng.uniform(-0.5, 1.5) * width
        y = rng.uniform(-0.5, 1.5) * height
        return (float(x), float(y), 1.0)
    theta = rng.uniform(0, math.pi)
    return (float(math.cos(theta)), float(math.sin(theta)), 0.0)


def _random_layer(rng, diameter: float, max_objects: int, width: int, height: int) -> Layer:
    n_texels = _integer(rng, TEXELS_PER_LAYER_RANGE)
    texels = tuple(str(kind) for kind in rng.choice(TEXELS, size=n_texels, replace=False))
    return Layer(
        texels=texels,
        max_objects=max_objects,
        aspect_ratio=_uniform(rng, ASPECT_RATIO_RANGE),
        max_diameter=diameter,
        max_trials=_integer(rng, MAX_TRIALS_RANGE),
        size_reduction=_uniform(rng, SIZE_REDUCTION_RANGE),
        max_reductions=_integer(rng, MAX_REDUCTIONS_RANGE),
        inclusion=bool(rng.random() < 0.5),
        exclusion=bool(rng.random() < 0.5),
        v0=_orientation_point(rng, width, height),
        v1=_orientation_point(rng, width, height),
        vanishing=_uniform(rng, VANISHING_RANGE),
    )


def _pixels(value, name: str) -> int:
    """``value`` unchanged if it is an int in [1, 16384] (an image side in pixels), else a ValueError naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= 16384:
        raise ValueError(f"{name} must be an integer number of pixels in [1, 16384], got {value!r:.80}")
    return value


def sample_script(rng=None, *, width: int = 512, height: int = 512, palette: str = "chelsea") -> Script:
    """A random script: every hyper-parameter drawn uniformly in its range (section 4, automatic mode).

    Parameters
    ----------
    rng : None, int or numpy.random.Generator
        Source of the hyper-parameters (and of the script's two seeds).
    width, height : int, optional
        Image size.
    palette : str, optional
        The palette image, the one choice the paper leaves to the user.

    Returns
    -------
    Script

    Notes
    -----
    Ranges (module constants): ``N_L`` in 2..5; 1-3 texel kinds per layer; ``Max_O`` in 2..40 per
    father (x 4 for the first drawn layer, whose only father is the image), capped so that no
    layer tries more than 4,000 objects (the paper's textures hold about 3,000); aspect ratio in
    [1, 6]; ``Max_D`` in [0.03, 0.6] of the shorter side for the first drawn layer, then [0.1,
    0.7] of the father layer's; ``Max_T`` in 5..40; ``s_R`` in [0.5, 0.95]; ``Max_DR`` in 0..8;
    inclusion and exclusion each on with probability 1/2; orientation points finite (uniform in
    the image enlarged by half its size) with probability 0.3, else at infinity in a uniform
    direction; ``rF`` in [0, 1.5]; transparency bound in [0, 0.8]; light spot with probability
    1/2 at a distance in [0.2, 2] shorter sides; tessellation with probability 0.2; "keep father
    inclusion" with probability 0.3.

    References
    ----------
    Alvarez et al. 2015, section 4 (automatic mode, ranges "compatible with image size, the
    sampling rate, and our perception accuracy") and 5.4 (rendering parameters).
    """
    rng = as_generator(rng)
    width, height = _pixels(width, "width"), _pixels(height, "height")
    short = min(width, height)
    n_layers = _integer(rng, LAYER_COUNT_RANGE) - 1
    layers, diameter = [], _uniform(rng, DIAMETER_RANGE) * short
    fathers = 1  # objects the previous layer may hold at most
    for number in range(n_layers):
        max_objects = _integer(rng, MAX_OBJECTS_RANGE) * (4 if number == 0 else 1)
        max_objects = max(1, min(max_objects, OBJECTS_PER_LAYER // fathers))
        layers.append(_random_layer(rng, diameter, max_objects, width, height))
        fathers *= max_objects
        diameter = max(2.0, diameter * _uniform(rng, CHILD_DIAMETER_RANGE))
    render = RenderSettings(
        palette=palette,
        seed=int(rng.integers(2**31)),
        transparency=_uniform(rng, TRANSPARENCY_RANGE),
        light_distance=_uniform(rng, LIGHT_DISTANCE_RANGE) * short if rng.random() < LIGHT_PROBABILITY else 0.0,
        tessellation=bool(rng.random() < TESSELLATION_PROBABILITY),
        keep_father_inclusion=bool(rng.random() < KEEP_FATHER_PROBABILITY),
    )
    return Script(width, height, int(rng.integers(2**31)), tuple(layers), render)
