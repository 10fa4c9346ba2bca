"""Point processes: patterns, summary functions, Gibbs models, pseudolikelihood, MCMC.

The statistical core of Hurtut 2009 (sections 3.1-3.3, Figure 4), with spatstat's names
and conventions so that a statistician recognises every function:

- :class:`Window`, :class:`PointPattern` (spatstat's ``owin``, ``ppp``);
- summary functions :func:`Kest`, :func:`Lest`, :func:`Kcross`, :func:`Lcross`, :func:`pcf`,
  simulation :func:`envelope` and global goodness-of-fit tests :func:`dclf_test`,
  :func:`mad_test`;
- models :func:`Poisson`, :func:`Strauss`, :func:`StraussHard`, :class:`MultiStraussHard`;
- fitting: :func:`ppm` (maximum pseudolikelihood on a Berman-Turner :func:`quadscheme`) and
  Hurtut's three-step :func:`fit_strauss_hardcore` (h, r from L, then beta and gamma);
- simulation: :func:`rmh` (birth-death-shift Metropolis-Hastings in numba), :func:`rpoispp`,
  :func:`rMatClust`.
"""

from .envelope import envelope
from .gof import GlobalTest, dclf_test, mad_test
from .fit import (
    PPMFit,
    RadiusSelection,
    StraussHardcoreFit,
    csr_L_sd,
    fine_nd,
    fit_strauss_hardcore,
    hardcore_distances,
    interaction_radii,
    ppm,
    select_radius,
)
from .models import MultiStraussHard, PairDistance, Poisson, Strauss, StraussHard, interaction_counts, interaction_pairs
from .pattern import PointPattern
from .processes import rMatClust, rpoispp
from .quadrature import QuadratureScheme, default_nd, quadscheme
from .simulate import intensity_map_values, rmh
from .summary import Kcross, Kest, Lcross, Lest, pcf
from .window import Window

__all__ = [
    "GlobalTest", "Kcross", "Kest", "Lcross", "Lest", "MultiStraussHard", "PPMFit", "PairDistance", "PointPattern", "Poisson", "QuadratureScheme",
    "RadiusSelection", "Strauss", "StraussHard", "StraussHardcoreFit", "Window", "csr_L_sd", "dclf_test", "default_nd", "envelope", "fine_nd",
    "fit_strauss_hardcore", "hardcore_distances", "intensity_map_values", "interaction_counts", "interaction_pairs", "interaction_radii",
    "mad_test", "pcf", "ppm", "quadscheme", "rMatClust", "rmh", "rpoispp", "select_radius",
]
