"""Monte Carlo ground truth of Hurtut's estimator for the regular model of hurtut2009_ripley_L.

The notebook refits 40 simulations of StraussHard(beta 200, gamma 0.2, r 0.07, h 0.03) and
records mean estimates. How close those means must be to the truth depends on the
estimator's own spread and bias, which this script measures on 300 independent refits
(seed 20261122, unrelated to the notebook's) and writes to tests/oracle/recovery.json; the
tolerances in tests/expected_stats.toml cite it.

    .venv/bin/python tests/oracle/recovery_study.py        (about 1 minute on 2 cores)
"""

import json
import warnings
from pathlib import Path

import numpy as np

from paperlib.parallel import run_many
from paperlib.pointprocess import StraussHard, Window, fit_strauss_hardcore, ppm, rmh

TRUTH = StraussHard(200.0, 0.2, r=0.07, hc=0.03, closed=False)
REPLICATES, SEED = 300, 20261122


def refit(_, rng):
    warnings.simplefilter("ignore")
    pattern = rmh(TRUTH, Window.rectangle(), T=100_000, rng=rng)
    estimated, given = fit_strauss_hardcore(pattern), ppm(pattern, r=0.07, hc=0.03)
    return pattern.n, estimated.model.hc[0, 0], estimated.model.r[0, 0], estimated.model.gamma[0, 0], \
        given.model.gamma[0, 0]


def main():
    estimates = np.array(run_many(refit, range(REPLICATES), rng=SEED))
    names = ["n", "h", "r", "gamma", "gamma_given_r_h"]
    summary = {
        name: {"mean": float(column.mean()), "median": float(np.median(column)), "sd": float(column.std(ddof=1)),
               "min": float(column.min()), "max": float(column.max())}
        for name, column in zip(names, estimates.T)
    }
    result = {"model": "StraussHard(beta=200, gamma=0.2, r=0.07, hc=0.03), unit square, rmh T=1e5 from empty",
              "replicates": REPLICATES, "seed": SEED, "estimates": summary}
    path = Path(__file__).with_name("recovery.json")
    path.write_text(json.dumps(result, indent=1) + "\n")
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
