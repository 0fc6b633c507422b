# Sphinx configuration of flexgait's documentation. Built by scripts/docs (Debian's
# python3-sphinx and python3-myst-parser), warnings are errors. The reference pages are
# generated into the staging copy of this folder at build time (docs/generate_reference.py), the
# C++ API from Doxygen's XML of the headers (docs/Doxyfile) through Breathe (python3-breathe).
import os

project = "flexgait"
author = "The flexgait authors"
copyright = "2026, The flexgait authors"
version = release = os.environ.get("FLEXGAIT_VERSION", "0.1.0")

extensions = ["myst_parser", "sphinx.ext.mathjax", "breathe"]
breathe_projects = {"flexgait": os.environ.get("FLEXGAIT_DOXYGEN_XML", "doxygen/xml")}
breathe_default_project = "flexgait"
breathe_domain_by_extension = {"hpp": "cpp"}
# Warnings are errors, and -n reports every reference that does not resolve. In the API pages a
# type from another namespace or library (std::, Eigen::) and a header's file page (not rendered:
# the pages are by namespace) do not resolve; those stay plain text instead of failing the build.
nitpick_ignore_regex = [(r"cpp:.*", r".*"), (r"std:ref", r".*_8hpp.*")]
myst_enable_extensions = ["dollarmath", "deflist"]
myst_heading_anchors = 3
source_suffix = {".md": "markdown"}
exclude_patterns = ["_build", "README.md"]
root_doc = "index"

html_theme = "alabaster"
html_title = "flexgait"
html_static_path = []
html_theme_options = {"description": "legged locomotion with compliance", "fixed_sidebar": True}
# Offline: MathJax is loaded by the reader's browser; the site itself holds no remote asset.
