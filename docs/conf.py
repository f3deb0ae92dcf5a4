"""Sphinx configuration of the cosserat documentation.

Build (warnings are errors)::

    pip install -e ".[docs]"
    sphinx-build -W --keep-going -b html docs docs/_build/html

Why Sphinx: numpydoc docstrings are the package's convention, and Sphinx with numpydoc,
autosummary and sphinx-gallery is the usual scientific-Python stack (NumPy, SciPy, Matplotlib):
the API reference is generated from those docstrings and the gallery's figures are made by
running the examples at build time. myst-parser brings in the existing Markdown notes in docs/
unchanged. MathJax is served from a local copy (sphinx-mathjax-offline), so equations render
without a network.
"""

from __future__ import annotations

import importlib
import os
import re
import sys
from pathlib import Path

from docutils.statemachine import StringList
from sphinx.directives.other import TocTree
from sphinx.util import docname_join

import cosserat

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))

# Matplotlib without a display; numba's cache in the usual place.
os.environ.setdefault("MPLBACKEND", "Agg")

project = "cosserat"
author = "cosserat developers"
copyright = "2026, cosserat developers"
release = cosserat.__version__
version = ".".join(release.split(".")[:2])

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
    "sphinx-mathjax-offline",  # a local MathJax 3 copy: equations render offline
    "parameter_tables",  # docs/parameter_tables.py: tables from the parameter declarations
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "auto_examples/*.ipynb", "auto_examples/*.py", "**.zip"]

# -- Markdown notes (myst) ----------------------------------------------------------------
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_dmath_double_inline = True
myst_heading_anchors = 3

# -- API reference --------------------------------------------------------------------------
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "member-order": "bysource", "ignore-module-all": True}
autodoc_typehints = "none"  # numpydoc's Parameters sections carry the types and units
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

# -- Gallery -------------------------------------------------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": "../examples",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "ignore_pattern": r"^(?!plot_)",  # the other scripts in examples/ are tools, not gallery
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    "show_memory": False,
    "write_computation_times": False,  # its page loads jQuery from a CDN: no network here
    "abort_on_example_error": False,
    "only_warn_on_example_error": False,
}

# -- HTML ----------------------------------------------------------------------------------
html_theme = "furo"
html_title = f"cosserat {release}"
html_show_sourcelink = False

# Internal references must resolve; typing names and numpy aliases in signatures are not
# documented here.
nitpicky = True
nitpick_ignore_regex = [
    (
        r"py:.*",
        r"(numpy|np|npt|typing|collections\.abc|pathlib|dataclasses|matplotlib|pandas|xarray)\..*",
    ),
    (r"py:class", r"(optional|array-like|array_like|callable|sequence|mapping|iterable)"),
    (r"py:class", r"(float|int|str|bool|dict|list|tuple|None|object|Any|Path|Figure|.*Array.*)"),
    # annotations kept as strings (``from __future__ import annotations``) in a few signatures
    (r"py:class", r".*'.*"),
    # module constants without a docstring are not documented
    (r"py:data", r"REQUIRED_KEYS"),
    # The compiled kernels (numba) are internal: not in the API reference; docstrings that name
    # them stay as they are.
    (r"py:(mod|func|data)", r"cosserat\.numerics(\..*)?"),
]


class OptionalTocTree(TocTree):
    """A toctree whose entries that do not exist (yet) are left out silently.

    Pages that other work adds later (``derivation_ngf``, ``derivation_channel``, ``dem``) are
    listed here and appear as soon as their file is in ``docs/``.
    """

    def run(self):  # type: ignore[no-untyped-def]
        env = self.state.document.settings.env
        kept = [
            line
            for line in self.content
            if not line.strip()
            or line.strip().startswith(":")
            or docname_join(env.docname, line.strip()) in env.found_docs
        ]
        self.content = StringList(kept, source=self.content.source(0) if self.content else "")
        return super().run()


# Markdown links from the notes in docs/ to files of the repository outside docs/: the page of
# the site that shows the same file (the notes stay readable where they are).
OUTSIDE_LINKS = {
    "../benchmarks/RESULTS.md": "benchmarks.md",
    "../benchmarks/RESULTS_speed.md": "benchmarks.md",
    "../CHANGELOG.md": "changelog.md",
    "../README.md": "getting_started.rst",
}


def link_outside_files(app, docname, source):  # type: ignore[no-untyped-def]
    """Point links such as ``](../benchmarks/RESULTS.md)`` at the site's page for that file."""
    text = source[0]
    for target, page in OUTSIDE_LINKS.items():
        text = text.replace(f"]({target})", f"]({page})")
    source[0] = text


# In a docstring, |x| is an absolute value, never a reStructuredText substitution.
_BARS = re.compile(r"(?<![|\\`\w])\|(?=[^\s|])([^|`\n]*?[^\s|\\])\|(?![|\w])")


def escape_absolute_values(app, what, name, obj, options, lines):  # type: ignore[no-untyped-def]
    """Escape ``|x|`` outside literals, so that docutils does not read it as a substitution."""
    for i, line in enumerate(lines):
        parts = line.split("``")
        for j in range(0, len(parts), 2):  # outside inline literals
            parts[j] = _BARS.sub(r"\\|\1\\|", parts[j])
        lines[i] = "``".join(parts)


def _canonical_name(module_name: str | None, target: str) -> str | None:
    """``module.qualname`` of what ``target`` names inside ``module_name`` (None if nothing)."""
    if not module_name:
        return None
    try:
        obj = importlib.import_module(module_name)
        for part in target.split("."):
            obj = getattr(obj, part)
    except (ImportError, AttributeError):
        return None
    module = getattr(obj, "__module__", None)
    qualname = getattr(obj, "__qualname__", None)
    if isinstance(obj, type(importlib)):
        return obj.__name__
    return f"{module}.{qualname}" if module and qualname else None


def resolve_short_names(app, env, node, contnode):  # type: ignore[no-untyped-def]
    """Resolve a Python reference that names an object by a shorter or older path.

    ``:class:`NoSolutionError``` written in a module that imports it, or a path from before a
    module moved, resolves to the one documented object whose name ends the same way; zero or
    several candidates leave the reference unresolved (and the nitpicky build fails).
    """
    if node.get("refdomain") != "py":
        return None
    target = node["reftarget"].lstrip("~.")
    domain = env.get_domain("py")
    # First choice: the object the referring module itself sees under that name.
    canonical = _canonical_name(node.get("py:module"), target)
    if canonical in domain.objects:
        node["reftarget"] = canonical
        return domain.resolve_xref(
            env, node["refdoc"], app.builder, node["reftype"], canonical, node, contnode
        )
    tail = "." + target.rsplit(".", 1)[-1]
    kinds = {"mod": ("module",)}.get(node["reftype"])
    matches = [
        name
        for name, obj in domain.objects.items()
        if (name.endswith("." + target) or name.endswith(tail))
        and (kinds is None or obj.objtype in kinds)
        and not obj.aliased
    ]
    exact = [name for name in matches if name.endswith("." + target)]
    chosen = exact or matches
    if len(chosen) != 1:
        return None
    node["reftarget"] = chosen[0]
    return domain.resolve_xref(
        env, node["refdoc"], app.builder, node["reftype"], chosen[0], node, contnode
    )


def reread_optional_toctrees(app, env, added, changed, removed):  # type: ignore[no-untyped-def]
    """Pages read again on every build: those with an optional toctree (whether an entry shows
    depends on files that may have appeared since) and the API reference (it depends on the
    sources in src/, which Sphinx does not watch)."""
    return [
        d
        for d in env.found_docs
        if d.startswith("api/") or "optional-toctree" in Path(env.doc2path(d)).read_text()
    ]


def skip_namedtuple_aliases(app, what, name, obj, skip, options):  # type: ignore[no-untyped-def]
    """NamedTuple fields document themselves as "Alias for field number N": the class docstring
    already says what they are."""
    if (getattr(obj, "__doc__", None) or "").startswith("Alias for field number"):
        return True
    return None


def setup(app):  # type: ignore[no-untyped-def]
    app.add_directive("optional-toctree", OptionalTocTree)
    app.connect("env-get-outdated", reread_optional_toctrees)
    app.connect("autodoc-skip-member", skip_namedtuple_aliases)
    app.connect("source-read", link_outside_files)
    app.connect("autodoc-process-docstring", escape_absolute_values, priority=400)
    app.connect("missing-reference", resolve_short_names)
