"""The baselines of benchmarks/bench_pointprocess_summary.py and bench_peers.py compute what they claim.

Speed is measured in benchmarks/, never asserted here: these tests check answers only, at
1e3 points. The spatstat comparison needs R with spatstat, the peers the ``bench`` extra;
each is skipped without them.
"""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import bench_peers  # noqa: E402
import bench_pointprocess_summary as summary_bench  # noqa: E402


def spatstat_installed() -> bool:
    if shutil.which("Rscript") is None:
        return False
    return subprocess.run(["Rscript", "-e", "library(spatstat)"], capture_output=True).returncode == 0


@pytest.fixture(scope="module")
def peer_differences():
    return bench_peers.check_peers()


def test_two_thread_prototype_and_our_kernel_agree_with_kest():
    assert summary_bench.check_prototype(1_000) < 1e-12


def test_our_estimates_match_spatstat_on_the_benchmark_points():
    if not spatstat_installed():
        pytest.skip("R with spatstat is not installed")
    differences = summary_bench.check_against_spatstat(1_000)
    assert set(differences) >= {"Lest_isotropic iso", "Lest_border border", "Kest_isotropic iso",
                                "Lcross_isotropic iso", "pcf_default trans", "pcf_default iso"}
    worst = max(differences, key=differences.get)
    assert differences[worst] < 1e-12, (worst, differences[worst])


def test_graycomatrix_counts_equal_ours(peer_differences):
    assert peer_differences["skimage graycomatrix vs cooccurrence_counts (count differences)"] == 0


@pytest.mark.skipif(bench_peers.RipleysKEstimator is None, reason="astropy (bench extra) is not installed")
def test_astropy_none_and_translation_are_our_estimators_and_ripley_differs(peer_differences):
    differences = peer_differences
    assert differences["astropy none vs Kest un"] < 1e-12
    assert differences["astropy translation vs Kest trans"] < 1e-12
    # astropy weights each unordered pair by one circle only
    assert 1e-4 < differences["astropy ripley vs Kest iso"] < 0.1


@pytest.mark.skipif(bench_peers.pointpats_distance is None, reason="pointpats (bench extra) is not installed")
def test_pointpats_is_our_uncorrected_l_up_to_its_normalisation(peer_differences):
    differences = peer_differences
    assert differences["pointpats l vs Lest un, raw"] > 1e-4
    assert differences["pointpats l vs Lest un, rescaled by sqrt((n-1)/n |bbox|)"] < 1e-12
