# SPDX-License-Identifier: Apache-2.0
"""Sphinx configuration of the smoothshaper API reference (built by scripts/docs.sh)."""
project = "smoothshaper"
author = "smoothshaper contributors"
extensions = ["sphinx.ext.autodoc", "sphinx.ext.napoleon"]
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": True}
autodoc_member_order = "bysource"
autodoc_typehints = "none"
napoleon_numpy_docstring = True
napoleon_google_docstring = False
html_theme = "alabaster"
exclude_patterns = ["_build"]
# Cross-references to objects outside the documented modules (numpy, builtins in type
# descriptions) are not errors.
nitpicky = False
suppress_warnings = ["ref.python"]
# Dataclass fields are listed in the class docstring's Attributes section: render them as
# fields of the class description, not as attribute entries autodoc also creates.
napoleon_use_ivar = True
