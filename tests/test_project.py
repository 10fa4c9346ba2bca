"""Project files: pyproject and environment.yml agree; the benchmark scaffold runs."""

import json
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
REQUIREMENT = re.compile(r"^\s*([A-Za-z0-9_.\-]+)(\[[^\]]*\])?\s*(.*)$")


def normalise(requirement: str) -> tuple[str, str]:
    """('scikit-image', '>=0.22') with PEP 503 name normalisation."""
    name, _extras, spec = REQUIREMENT.match(requirement).groups()
    return re.sub(r"[-_.]+", "-", name).lower(), spec.replace(" ", "")


def pyproject_requirements() -> set:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    requirements = list(project["dependencies"])
    for extra in project["optional-dependencies"].values():
        requirements += extra
    return {normalise(r) for r in requirements}


def environment_requirements() -> set:
    environment = yaml.safe_load((ROOT / "environment.yml").read_text())
    requirements = set()
    for item in environment["dependencies"]:
        if isinstance(item, dict):
            requirements |= {normalise(r) for r in item["pip"] if not r.startswith("-e")}
        elif not item.startswith(("python", "pip")) or item.startswith("python-"):
            requirements.add(normalise(item))
    return requirements


def test_pyproject_and_environment_list_the_same_dependencies():
    assert pyproject_requirements() == environment_requirements()


def test_dependencies_have_lower_bounds_not_pins():
    for name, spec in pyproject_requirements():
        assert spec.startswith(">="), f"{name} should have a lower bound, got {spec!r}"


def test_benchmark_scaffold_writes_table_and_json(tmp_path):
    output = tmp_path / "results.json"
    completed = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "run.py"), "--quick", "--only", "in-process", "--output", str(output)],
        capture_output=True, text=True, check=True,
    )
    assert "ratio" in completed.stdout and "plain loop" in completed.stdout
    rows = json.loads(output.read_text())["results"]
    assert rows and all(row["seconds"] > 0 and row["ratio"] > 0 for row in rows)


def test_benchmark_unknown_pattern_fails_clearly(tmp_path):
    completed = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "run.py"), "--only", "nothing-like-this",
         "--output", str(tmp_path / "r.json")],
        capture_output=True, text=True,
    )
    assert completed.returncode == 2 and "no benchmark matches" in completed.stderr
    assert not (tmp_path / "r.json").exists()
