"""Simhon 2001 sketch elaboration: training on 40 coastlines, then elaborating a 1,000-sample sketch.

"sketch: train": ``paperlib.sketch.train`` on the 40 largest GSHHS land masses (``coastlines(40)``, loaded
once, not timed) with the paper's settings, 5 scales and order 20 (uniform filter of width 9, 256 samples per
curve: 10,240 states). Target (issue 8): <= 2 s. Baseline, same run: the multi-scale analysis alone
(resampling, tangent angles, 5 scales of every curve), so the ratio shows what finding each state's most
similar states costs on top.

"sketch: elaborate": ``paperlib.sketch.elaborate`` of a smooth closed sketch (a three-lobed blob) at n
samples with the model above (trained once, not timed), the paper's maximum-probability instantiation.
Target (issue 8): <= 0.5 s for 1,000 samples; paper: "real time response" on a 1 GHz P3. Baseline, same
run: the sketch's preparation alone (validation, resampling, tangent angles), so the ratio is the chain's
cost over reading the sketch.

"sketch: elaborate a held-out coastline": the same at n samples for the coarse version of held-out coastline
48 (``coastlines(54)[48]``, the case whose detail crosses itself most often in the notebooks), so the time
includes untangling the crossings (issue 20: <= 0.5 s for 1,000 samples). Same baseline.
"""

from functools import cache

import numpy as np

from paperlib.datasets import coastlines
from paperlib.sketch import (
    check_curve,
    coarsen,
    elaborate,
    filter_weights,
    multiscale_angles,
    resample_curve,
    tangent_angles,
    train,
)
from registry import benchmark

SETTINGS = dict(order=20, scales=5, filter_width=9, samples_per_curve=256)


@cache
def training_curves(n):
    return coastlines(n)


@cache
def model():
    return train(training_curves(40), **SETTINGS)


def blob(points=400):
    t = np.linspace(0.0, 2.0 * np.pi, points, endpoint=False)
    radius = 1.0 + 0.2 * np.cos(3.0 * t)
    return np.column_stack([radius * np.cos(t), radius * np.sin(t)])


def analysis_only(n):
    curves, taps = training_curves(n), filter_weights(SETTINGS["filter_width"])

    def run():
        for curve in curves:
            points = resample_curve(check_curve(curve, closed=True), SETTINGS["samples_per_curve"], closed=True)
            multiscale_angles(tangent_angles(points, closed=True), SETTINGS["scales"], taps, closed=True)
    return run


@benchmark("sketch: train (n coastlines, 5 scales, order 20)", sizes=[40], baseline=analysis_only,
           baseline_name="multi-scale analysis alone")
def training(n):
    curves = training_curves(n)
    train(curves[:2], **SETTINGS)  # warm the numba kernels
    return lambda: train(curves, **SETTINGS)


def sketch_preparation(n):
    sketch = blob()
    return lambda: tangent_angles(resample_curve(check_curve(sketch, closed=True, min_points=20), n,
                                                 closed=True), closed=True)


@benchmark("sketch: elaborate (n sketch samples)", sizes=[1000], baseline=sketch_preparation,
           baseline_name="sketch validation, resampling and angles alone")
def elaboration(n):
    trained, sketch = model(), blob()
    elaborate(trained, sketch, n_samples=n)  # warm the numba kernel
    return lambda: elaborate(trained, sketch, n_samples=n)


@cache
def held_out_sketch():
    return coarsen(training_curves(54)[48], model())


def held_out_preparation(n):
    sketch = held_out_sketch()
    return lambda: tangent_angles(resample_curve(check_curve(sketch, closed=True, min_points=20), n,
                                                 closed=True), closed=True)


@benchmark("sketch: elaborate a held-out coastline (n samples, crossings untangled)", sizes=[1000],
           baseline=held_out_preparation, baseline_name="sketch validation, resampling and angles alone")
def held_out_elaboration(n):
    trained, sketch = model(), held_out_sketch()
    result = elaborate(trained, sketch, n_samples=n)  # warm the numba kernel
    assert result.crossings == 0
    return lambda: elaborate(trained, sketch, n_samples=n)
