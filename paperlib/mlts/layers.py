"""Layer configuration of the multi-layer texture sampler (Alvarez et al. 2015, section 4).

A :class:`Layer` holds the parameters section 4 lists for one layer ``L_m`` (m >= 2; the first
layer is the image rectangle itself):

=======================  ==================  ====================================================
paper                    attribute           meaning
=======================  ==================  ====================================================
``T(L_m)``               ``texels``          texel kinds the layer's objects are drawn from
``Max_O(L_m)``           ``max_objects``     objects tried per father object
``AspRat_O(L_m)``        ``aspect_ratio``    length over width of every object (>= 1)
``Max_D(L_m)``           ``max_diameter``    object diameter before any reduction, pixels
``Max_T(L_m)``           ``max_trials``      placements tried at one diameter
``s_R(L_m)``             ``size_reduction``  factor applied to the diameter after Max_T failures
``Max_DR(L_m)``          ``max_reductions``  diameter reductions before the object is given up
``Incl(L_m)``            ``inclusion``       every object inside its father (not touching it)
``Excl(L_m)``            ``exclusion``       objects of the layer do not intersect
``V_0, V_1(L_m)``        ``v0``, ``v1``      orientation points, projective (X, Y, Z)
``rF(L_m)``              ``vanishing``       size reduction toward a finite orientation point
=======================  ==================  ====================================================

Projective points: ``(X, Y, Z)`` with ``Z != 0`` is the image point ``(X / Z, Y / Z)`` in pixels
(x right, y down); ``Z = 0`` is the point at infinity in the direction ``(X, Y)``, so
``(1, 0, 0)`` and ``(0, 1, 0)`` orient objects horizontally and vertically (section 3).

Choices the paper leaves open, documented here and in :func:`paperlib.mlts.sampler.sample_structure`:
every object of a layer has the layer's aspect ratio (objects of a layer "share properties",
section 3); the vanishing-point reduction scales the diameter by ``(d / d_far) ** rF`` with ``d``
the distance from the object's centre to its orientation point and ``d_far`` the largest
distance from that point to a corner of the image (linear perspective for ``rF = 1``, none for
``rF = 0``).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields

from .._checks import positive_number
from .texels import TEXELS

__all__ = ["Layer", "check_exact_keys", "check_projective_point", "check_texels"]


def check_projective_point(point, name: str) -> tuple[float, float, float]:
    """``point`` as a finite (X, Y, Z) triple, not (0, 0, 0)."""
    try:
        values = tuple(float(value) for value in point)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a projective point (X, Y, Z), got {point!r}") from None
    if len(values) != 3 or not all(math.isfinite(value) for value in values):
        raise ValueError(f"{name} must be three finite numbers (X, Y, Z), got {point!r}")
    if values == (0.0, 0.0, 0.0):
        raise ValueError(f"{name} = (0, 0, 0) is not a projective point")
    return values


def check_texels(texels) -> tuple[str, ...]:
    """A non-empty tuple of known texel kinds."""
    try:
        kinds = (texels,) if isinstance(texels, str) else tuple(texels)
    except TypeError:
        raise ValueError(f"texels must be a texel kind or a list of them, got {texels!r:.100}") from None
    if not kinds:
        raise ValueError("a layer needs at least one texel kind")
    unknown = [kind for kind in kinds if not isinstance(kind, str) or kind not in TEXELS]
    if unknown:
        raise ValueError(f"unknown texel kind(s) {unknown}; choose among {TEXELS}")
    return kinds


def checked_layers(layers, name: str = "layers") -> tuple:
    """``layers`` as a tuple of :class:`Layer` (the paper's ``L_2``, ``L_3``...), or an error naming ``name``.

    TypeError when ``layers`` is not a sequence; ValueError naming the first item that is not a Layer.
    """
    try:
        layers = tuple(layers)
    except TypeError:
        raise TypeError(f"{name} must be a sequence of paperlib.mlts.Layer, got {type(layers).__name__}") from None
    for index, layer in enumerate(layers):
        if not isinstance(layer, Layer):
            raise ValueError(f"{name}[{index}] (layer {index + 2}) must be a paperlib.mlts.Layer, got "
                             f"{type(layer).__name__}")
    return layers


def check_exact_keys(values, cls, what: str) -> None:
    """ValueError unless ``values`` is a mapping with exactly the fields of dataclass ``cls``."""
    if not isinstance(values, dict):
        raise ValueError(f"{what} must be a JSON object (a mapping), got {type(values).__name__}")
    names = [item.name for item in fields(cls)]
    unknown = sorted(set(values) - set(names))
    missing = [name for name in names if name not in values]
    if unknown:
        raise ValueError(f"unknown {what} key(s) {unknown}; known: {names}")
    if missing:
        raise ValueError(f"missing {what} key(s) {missing}")


def _count(value, name: str, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return value


def _flag(value, name: str) -> bool:
    if not isinstance(value, bool):
        raise ValueError(f"{name} must be true or false, got {value!r}")
    return value


@dataclass(frozen=True)
class Layer:
    """Parameters of one layer ``L_m`` of an ML-texture (section 4); validated on creation.

    Parameters
    ----------
    texels : str or tuple of str, default ("rectangle",)
        ``T(L_m)``: the texel kinds the layer's objects are drawn from (of :data:`TEXELS`).
    max_objects : int, default 10
        ``Max_O(L_m)``: objects tried per father object (>= 1).
    aspect_ratio : float, default 1
        ``AspRat_O(L_m)``: length over width of every object (>= 1).
    max_diameter : float, default 100
        ``Max_D(L_m)``: object diameter before any reduction, pixels (> 0).
    max_trials : int, default 20
        ``Max_T(L_m)``: placements tried at one diameter (>= 1).
    size_reduction : float, default 0.8
        ``s_R(L_m)``: factor applied to the diameter after ``max_trials`` failures, in (0, 1).
    max_reductions : int, default 5
        ``Max_DR(L_m)``: diameter reductions before the object is given up (>= 0).
    inclusion : bool, default False
        ``Incl(L_m)``: every object lies inside its father, not touching it.
    exclusion : bool, default False
        ``Excl(L_m)``: objects of the layer do not intersect.
    v0, v1 : tuple of 3 float, default (1, 0, 0) and (0, 1, 0)
        ``V_0, V_1(L_m)``: the orientation points, projective ``(X, Y, Z)`` (not all zero).
    vanishing : float, default 0
        ``rF(L_m)``: size reduction toward a finite orientation point (>= 0; 0 for none, 1 for
        linear perspective).
    """

    texels: tuple = ("rectangle",)
    max_objects: int = 10
    aspect_ratio: float = 1.0
    max_diameter: float = 100.0
    max_trials: int = 20
    size_reduction: float = 0.8
    max_reductions: int = 5
    inclusion: bool = False
    exclusion: bool = False
    v0: tuple = (1.0, 0.0, 0.0)
    v1: tuple = (0.0, 1.0, 0.0)
    vanishing: float = 0.0

    def __post_init__(self):
        set_ = object.__setattr__  # frozen: store the validated, normalised values
        set_(self, "texels", check_texels(self.texels))
        _count(self.max_objects, "max_objects (Max_O)", 1)
        aspect = positive_number(self.aspect_ratio, "aspect_ratio (AspRat_O)")
        if aspect < 1:
            raise ValueError(f"aspect_ratio (AspRat_O) must be >= 1 (length over width), got {self.aspect_ratio!r}")
        set_(self, "aspect_ratio", aspect)
        set_(self, "max_diameter", positive_number(self.max_diameter, "max_diameter (Max_D)"))
        _count(self.max_trials, "max_trials (Max_T)", 1)
        reduction = positive_number(self.size_reduction, "size_reduction (s_R)")
        if reduction >= 1:
            raise ValueError(f"size_reduction (s_R) must lie in (0, 1), got {self.size_reduction!r}")
        set_(self, "size_reduction", reduction)
        _count(self.max_reductions, "max_reductions (Max_DR)", 0)
        _flag(self.inclusion, "inclusion (Incl)")
        _flag(self.exclusion, "exclusion (Excl)")
        set_(self, "v0", check_projective_point(self.v0, "v0 (V_0)"))
        set_(self, "v1", check_projective_point(self.v1, "v1 (V_1)"))
        set_(self, "vanishing", positive_number(self.vanishing, "vanishing (rF)", allow_zero=True))

    def to_dict(self) -> dict:
        """Plain JSON-ready values (lists for tuples).

        Returns
        -------
        dict
            ``{field: value}`` for every field of the layer, tuples as lists.
        """
        return {key: list(value) if isinstance(value, tuple) else value for key, value in asdict(self).items()}

    @classmethod
    def from_dict(cls, values: dict) -> "Layer":
        """A layer from :meth:`to_dict`'s mapping; unknown or missing keys are errors.

        Parameters
        ----------
        values : dict
            ``{field: value}`` with exactly the fields of :class:`Layer` (lists accepted for tuples).

        Returns
        -------
        Layer
            The validated layer.
        """
        check_exact_keys(values, cls, "layer parameter")
        return cls(**{name: tuple(value) if isinstance(value, list) else value for name, value in values.items()})
