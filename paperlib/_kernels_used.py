"""Which of paperlib's numba kernels a process has used: the coverage measure of the determinism rerun.

``make test`` reruns only a subset of the notebooks to check that the same seed gives the same
statistics; the subset must exercise every compiled kernel the full run does (issue 26). A notebook
records :func:`kernels_used` in its ``stats.json`` (see :func:`paperlib.repro.record`), and the test
compares the subset's union with the full run's.

A dispatcher has signatures once it was compiled or loaded from numba's on-disk cache in this
process. Loading a cached kernel does not load the kernels it calls (their code is linked into its
own), while compiling it does, so the raw set would depend on which notebook compiled first; the set
is therefore closed over the calls each kernel's source names, which makes it the same whichever
notebook found the cache warm.
"""

from __future__ import annotations

import sys
import types

from numba.core.dispatcher import Dispatcher

_PACKAGE = "paperlib"


def _dispatchers() -> list[Dispatcher]:
    """Every numba dispatcher defined at module level in the imported paperlib modules."""
    found = {}
    for name, module in list(sys.modules.items()):
        if module is None or not (name == _PACKAGE or name.startswith(_PACKAGE + ".")):
            continue
        for value in vars(module).values():
            if isinstance(value, Dispatcher) and value.py_func.__module__.startswith(_PACKAGE):
                found[id(value)] = value
    return list(found.values())


def _callees(dispatcher: Dispatcher) -> list[Dispatcher]:
    """The dispatchers a kernel's source names as globals or as attributes of a global module."""
    code, namespace = dispatcher.py_func.__code__, dispatcher.py_func.__globals__
    names = set(code.co_names)
    for constant in code.co_consts:  # nested functions (closures compiled with the kernel)
        if isinstance(constant, types.CodeType):
            names |= set(constant.co_names)
    callees = []
    for name in names:
        value = namespace.get(name)
        if isinstance(value, types.ModuleType):
            callees += [getattr(value, other) for other in names if isinstance(getattr(value, other, None), Dispatcher)]
        elif isinstance(value, Dispatcher):
            callees.append(value)
    return callees


def kernel_name(dispatcher: Dispatcher) -> str:
    """``module.qualname`` of a dispatcher's Python function."""
    return f"{dispatcher.py_func.__module__}.{dispatcher.py_func.__qualname__}"


def kernels_used() -> list[str]:
    """Names of the paperlib kernels this process has compiled or loaded, with everything they call.

    Returns
    -------
    list of str
        Sorted ``module.qualname`` names.
    """
    pending = [dispatcher for dispatcher in _dispatchers() if dispatcher.signatures]
    used = {}
    while pending:
        dispatcher = pending.pop()
        if id(dispatcher) not in used:
            used[id(dispatcher)] = dispatcher
            pending += _callees(dispatcher)
    return sorted({kernel_name(dispatcher) for dispatcher in used.values()})
