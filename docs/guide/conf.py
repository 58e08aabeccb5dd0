# Sphinx configuration of the granasym user guide (docs/guide/).
# Built with Debian's python3-sphinx and python3-myst-parser
# (scripts/install_deps.sh): `sphinx-build -W -n --keep-going -b html
# docs/guide OUT`, or the CMake target `docs` and the test Docs.guide_builds.
project = "granasym"
copyright = "the granasym authors"
author = "the granasym authors"

extensions = ["myst_parser"]
source_suffix = {".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build"]

# Headings up to level 3 get anchors, so that [text](page.md#heading) links
# are checked by the build (-n, warnings as errors).
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath", "deflist"]

html_theme = "alabaster"
html_theme_options = {"nosidebar": False, "page_width": "1100px"}
html_title = "granasym user guide"
html_show_sourcelink = False
html_copy_source = False
language = "en"
