"""One clean app per method: the explorer of :mod:`paperlib.widgets`, served by Voila or opened in JupyterLab.

Each method has an app notebook beside this module, ``<paper>.ipynb`` (``hurtut2009``,
``barla2006``, ``kim2009``, ``alvarez2015``, ``simhon2001``), whose only cell is
``app("<paper>")``: the panel in its default preset, freshly built (no state left by the checks of
the ``notebooks/<paper>_explorer.ipynb`` notebooks, which test the explorers and record their
statistics). ``python -m paperlib explore <paper>`` serves one with Voila on 127.0.0.1
(:func:`serve`).

Files. A served page runs a kernel with the server's permissions, so an app confines the file boxes
of its explorer (the SVG drawing of Hurtut 2009, the JSON scripts and the output folder of Alvarez
2015) to one folder, :func:`default_file_root` unless told otherwise, and offers an upload button
for files from the browser. Nothing an app writes goes to the repository's ``figures/``.

Offline. Voila's own page template links Font Awesome from a CDN although its bundle already
carries the icons; the ``paperlib`` template beside this module (``jupyter/voila/templates``)
drops the two links, so a served app loads nothing from outside the server.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from paperlib._checks import check_flag, integer_in_range

__all__ = ["APPS", "ALIASES", "FILE_ROOT_VARIABLE", "app", "app_notebook", "default_file_root", "resolve_method",
           "serve", "voila_command", "voila_environment"]

#: The apps: paper key -> (explorer factory in :mod:`paperlib.widgets`, what it explores).
APPS = {
    "hurtut2009": ("arrangement_explorer", "Hurtut 2009: element arrangements (categorize, fit, synthesize)"),
    "barla2006": ("strokepattern_explorer", "Barla 2006: stroke patterns (clustering, synthesis along a path)"),
    "kim2009": ("stipple_explorer", "Kim 2009: stippling by example (library, tone map, rendering)"),
    "alvarez2015": ("mlts_explorer", "Alvarez 2015: multi-layered textures (every script parameter)"),
    "simhon2001": ("sketch_explorer", "Simhon 2001: sketch elaboration (draw a curve, elaborate it)"),
}

#: Module names accepted for the paper keys.
ALIASES = {"arrangement": "hurtut2009", "strokepattern": "barla2006", "stipple": "kim2009", "mlts": "alvarez2015",
           "sketch": "simhon2001"}

#: The explorers that read or write files, and so take a ``file_root``.
_FILE_APPS = ("hurtut2009", "alvarez2015")

#: Environment variable naming the folder served apps read and write (see :func:`default_file_root`).
FILE_ROOT_VARIABLE = "PAPERLIB_FILE_ROOT"

_HERE = Path(__file__).resolve().parent


def resolve_method(method) -> str:
    """The paper key of ``method`` (a paper key such as ``"kim2009"`` or a module name such as ``"stipple"``).

    Parameters
    ----------
    method : str
        One of :data:`APPS` or :data:`ALIASES`.

    Returns
    -------
    str
        The paper key.
    """
    if not isinstance(method, str):
        raise TypeError(f"method must be a str, got {type(method).__name__}")
    key = ALIASES.get(method, method)
    if key not in APPS:
        choices = ", ".join([*APPS, *ALIASES])
        raise ValueError(f"method must be one of {choices}; got {method!r}")
    return key


def default_file_root() -> Path:
    """The folder a served app's file boxes are confined to, created if missing.

    Returns
    -------
    Path
        ``$PAPERLIB_FILE_ROOT`` when set, else ``build/explorer_files`` of the checkout paperlib runs
        from (or of the current folder for an installed paperlib).
    """
    configured = os.environ.get(FILE_ROOT_VARIABLE, "").strip()
    if configured:
        folder = Path(configured).expanduser()
    else:
        checkout = _HERE.parents[1]
        is_checkout = (checkout / "pyproject.toml").is_file() and (checkout / "paperlib").is_dir()
        folder = (checkout if is_checkout else Path.cwd()) / "build" / "explorer_files"
    folder.mkdir(parents=True, exist_ok=True)
    return folder


def app(method, *, file_root=None):
    """Build the explorer of ``method`` in its default preset, files confined to ``file_root``.

    The only call of an app notebook; the returned explorer displays itself as the cell's value.

    Parameters
    ----------
    method : str
        A paper key or module name (:func:`resolve_method`).
    file_root : str, os.PathLike or None
        Folder the file boxes may read and write (Hurtut 2009 and Alvarez 2015); None:
        :func:`default_file_root`.

    Returns
    -------
    ExplorerBase
        The explorer (``display`` it, or leave it as a cell's last value).
    """
    from paperlib import widgets

    key = resolve_method(method)
    factory = getattr(widgets, APPS[key][0])
    if key not in _FILE_APPS:
        return factory()
    return factory(file_root=default_file_root() if file_root is None else file_root)


def app_notebook(method) -> Path:
    """The app notebook of ``method``: one cell, ``app("<paper>")``.

    Parameters
    ----------
    method : str
        A paper key or module name (:func:`resolve_method`).

    Returns
    -------
    Path
    """
    return _HERE / f"{resolve_method(method)}.ipynb"


def voila_command(method, *, port: int = 8866, open_browser: bool = False) -> list[str]:
    """The command that serves ``method``'s app with Voila on 127.0.0.1 (see :func:`serve`).

    Parameters
    ----------
    method : str
        A paper key or module name (:func:`resolve_method`).
    port : int
        TCP port, 1024 to 65535.
    open_browser : bool
        Open the page in the default browser once served.

    Returns
    -------
    list of str
        The arguments, starting with this interpreter (so the kernel is the one with paperlib).
    """
    port = integer_in_range(port, "port", 1024, 65535)
    open_browser = check_flag(open_browser, "open_browser")
    return [sys.executable, "-m", "voila", str(app_notebook(method)), "--Voila.ip=127.0.0.1", f"--port={port}",
            "--template=paperlib", "--show_tracebacks=False", "--browser" if open_browser else "--no-browser"]


def voila_environment(file_root=None) -> dict:
    """The environment of the Voila server: the ``paperlib`` template on ``JUPYTER_PATH``, the file root set.

    Parameters
    ----------
    file_root : str, os.PathLike or None
        The folder of the apps' file boxes; None: :func:`default_file_root`.

    Returns
    -------
    dict
    """
    from paperlib.widgets._base import check_file_root

    folder = check_file_root(default_file_root() if file_root is None else file_root)
    env = dict(os.environ)
    paths = [str(_HERE / "jupyter"), *filter(None, env.get("JUPYTER_PATH", "").split(os.pathsep))]
    env["JUPYTER_PATH"] = os.pathsep.join(paths)
    env[FILE_ROOT_VARIABLE] = str(folder)
    return env


def serve(method, *, port: int = 8866, file_root=None, open_browser: bool = False) -> int:
    """Serve ``method``'s app with Voila on ``http://127.0.0.1:<port>`` until interrupted.

    Voila listens on 127.0.0.1 only: the kernel behind the page runs with your permissions, so
    keep it there unless an authenticating proxy stands in front.

    Parameters
    ----------
    method : str
        A paper key or module name (:func:`resolve_method`).
    port : int
        TCP port, 1024 to 65535.
    file_root : str, os.PathLike or None
        The folder of the apps' file boxes (must exist); None: :func:`default_file_root`.
    open_browser : bool
        Open the page in the default browser once served.

    Returns
    -------
    int
        Voila's exit status (0 after Ctrl-C).
    """
    command = voila_command(method, port=port, open_browser=open_browser)
    env = voila_environment(file_root)
    print(f"serving {APPS[resolve_method(method)][1]} at http://127.0.0.1:{port}/ "
          f"(files under {env[FILE_ROOT_VARIABLE]}); Ctrl-C stops", file=sys.stderr)
    try:
        return subprocess.run(command, env=env, check=False).returncode
    except KeyboardInterrupt:
        return 0
