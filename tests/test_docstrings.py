"""Issue 22 item 6: every public callable has a complete numpydoc docstring.

The public API is the one the fuzz registry enumerates (``fuzz_registry.public_callables``: each
callable in the ``__all__`` of the modules of ``fuzz_registry.MODULES``), plus the public methods
that each public class defines itself (functions, static and class methods; properties are left
out). Each is run through ``numpydoc.validate.validate`` and only the completeness codes are
enforced: a docstring with a summary, a Parameters section that documents every parameter (for a
class, the parameters of ``__init__``) and names no parameter that does not exist, a Returns
section when the callable returns a value, a Yields section for a generator. Stylistic codes
(GL01, GL02, SS0x, PR08, PR09, SA01, EX01, ES01, ...) are not checked.
"""

from __future__ import annotations

import importlib
import inspect
import sys
import warnings
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

import fuzz_registry  # noqa: E402

validate = pytest.importorskip("numpydoc.validate").validate

#: The numpydoc codes that say a docstring is incomplete (as opposed to badly styled).
COMPLETENESS_CODES = {
    "GL08": "no docstring",
    "SS01": "no summary",
    "PR01": "a parameter is not documented",
    "PR02": "a documented parameter does not exist",
    "RT01": "no Returns section although the callable returns a value",
    "YD01": "no Yields section although the callable is a generator",
}


def documented_callables() -> list[str]:
    """The public callables of :func:`fuzz_registry.public_callables` and their classes' own public methods."""
    names = []
    for full_name in fuzz_registry.public_callables():
        names.append(full_name)
        module_name, name = full_name.rsplit(".", 1)
        obj = getattr(importlib.import_module(module_name), name)
        if not inspect.isclass(obj):
            continue
        for attribute, value in vars(obj).items():
            if attribute.startswith("_"):
                continue
            if isinstance(value, (staticmethod, classmethod)):
                value = value.__func__
            if inspect.isfunction(value):
                names.append(f"{full_name}.{attribute}")
    return names


CALLABLES = documented_callables()


def test_the_enumeration_covers_the_fuzzed_public_api():
    assert set(fuzz_registry.public_callables()) <= set(CALLABLES)
    assert len(CALLABLES) == len(set(CALLABLES))


@pytest.mark.parametrize("name", CALLABLES)
def test_docstring_is_complete(name):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # numpydoc warns about sections it does not know
        result = validate(name)
    problems = [f"{code} ({COMPLETENESS_CODES[code]}): {message}" for code, message in result["errors"]
                if code in COMPLETENESS_CODES]
    assert not problems, f"{name} ({result['file']}:{result['file_line']}):\n" + "\n".join(problems)
