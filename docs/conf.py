"""Sphinx configuration of paperlib's documentation site (``make docs`` -> build/docs/html/index.html).

The site is built from the project's own files: the static pages beside this file, and pages that
``docs/generate.py`` writes into ``docs/_generated/`` (git-ignored) when the build starts, one per paper and
notebook and the API reference. Notebooks are never executed here (``nb_execution_mode = "off"``): a page shows
the executed copy ``make reproduce`` left in ``build/notebooks/``, or the source's markdown cells, with the
committed figures. Nothing is fetched from outside the machine: the theme bundles its assets, no math renderer
loads from a CDN, widget outputs are dropped (tests/test_docs.py checks the built HTML).
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from docutils import nodes  # noqa: E402

import generate  # noqa: E402  (docs/generate.py, beside this file)

project = "paperlib"
author = "paperlib contributors"
copyright = "paperlib contributors"  # noqa: A001  (Sphinx's name)

extensions = [
    "myst_nb",
    "sphinx.ext.autodoc",
    "numpydoc",
    "sphinx_copybutton",
]

# The generated fragments (a paper's notebooks and ledger, the scorecard link) are included by pages, not pages.
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "**.ipynb_checkpoints", "_generated/papers",
                    "_generated/index_extra.md"]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}

# MyST / myst-nb: never execute; render what the executed copies hold.
nb_execution_mode = "off"
nb_merge_streams = True
myst_enable_extensions = ["colon_fence"]
myst_heading_anchors = 3
# numpydoc renames a docstring's References ([1], [2]) per object; a reference list that the text does not
# cite is reported as "Citation ... is not referenced": the references are still shown, nothing is broken.
suppress_warnings = ["ref.citation"]

# API reference: autodoc + numpydoc, members of each module's __all__.
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_member_order = "bysource"
autodoc_typehints = "none"
numpydoc_show_class_members = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set = set()

# Offline: no MathJax from a CDN. The one formula (the docstring of pointprocess.rmh) is shown as its LaTeX
# source by the "plain" renderer below; the theme bundles its own assets.
html_math_renderer = "plain"
html_theme = "pydata_sphinx_theme"
html_title = "paperlib"
html_static_path = ["_static"]
html_css_files = ["paperlib.css"]
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "header_links_before_dropdown": 6,
    "secondary_sidebar_items": ["page-toc"],
}
# The theme reads the colour mode from the page; without one it logs an error in the console.
html_context = {"default_mode": "light"}
html_show_sourcelink = False
html_copy_source = False


def _visit_math(self, node) -> None:
    self.body.append(self.starttag(node, "code", "", CLASS="math notranslate"))
    self.body.append(self.encode(node.astext()))
    self.body.append("</code>")
    raise nodes.SkipNode


def _visit_displaymath(self, node) -> None:
    self.body.append(self.starttag(node, "pre", "", CLASS="math notranslate"))
    self.body.append(self.encode(node.astext()))
    self.body.append("</pre>")
    raise nodes.SkipNode


_BARS = re.compile(r"(?<![\\`|])\|(?=[^\s|])([^|`\n]*?[^\s\\|])\|(?![|_\w])")
_LITERAL = re.compile(r"(``.*?``|`[^`]*`)")


def _escape_bars(app, what, name, obj, options, lines) -> None:
    """Read ``|W|`` in a docstring's prose as absolute value, not as a reST substitution reference.

    Docstrings are written for ``help()`` as much as for Sphinx, with ``|W|`` for the area of a window and
    ``|det matrix|``; reST would take them for substitutions that are never defined. Literal blocks, directives
    (``.. math::``) and inline literals are left alone.
    """
    block_indent = None
    for number, line in enumerate(lines):
        indent = len(line) - len(line.lstrip())
        if block_indent is not None:
            if not line.strip() or indent > block_indent:
                continue
            block_indent = None
        if line.rstrip().endswith("::"):
            block_indent = indent
        parts = _LITERAL.split(line)
        lines[number] = "".join(part if index % 2 else _BARS.sub(r"\\|\1\\|", part)
                                for index, part in enumerate(parts))


def _generate(app) -> None:
    generate.generate(Path(app.srcdir) / generate.GENERATED)


def setup(app):
    app.add_html_math_renderer("plain", (_visit_math, None), (_visit_displaymath, None))
    app.connect("builder-inited", _generate)
    app.connect("autodoc-process-docstring", _escape_bars)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
