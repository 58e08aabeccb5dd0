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

# The key tables of the reference (reference.md) are generated when the
# guide is built: a line ```{granasym-keys} KIND``` (with its closing fence)
# becomes the output of `granasym keys KIND --format markdown`, the tables
# the parsers check every key against, so that the reference cannot drift
# from the code. The program is $GRANASYM (the docs target and the test
# Docs.guide_builds set it); its output is kept in the build tree, beside
# the HTML (keys/KIND.md). Without it the build fails, saying so.
import os
import re
import subprocess

_KEYS_FENCE = re.compile(r"^```\{granasym-keys\}[ \t]+(\w+)[ \t]*\n```[ \t]*$", re.MULTILINE)


def _generated_keys(app, kind):
    program = os.environ.get("GRANASYM", "")
    if not program or not os.access(program, os.X_OK):
        raise RuntimeError(
            "the reference's key tables need the granasym program: set GRANASYM to its path "
            "(e.g. GRANASYM=build/app/granasym sphinx-build ...; the CMake target docs and "
            "the test Docs.guide_builds set it)")
    folder = os.path.join(os.path.dirname(os.path.abspath(app.outdir)), "keys")
    os.makedirs(folder, exist_ok=True)
    text = subprocess.run([program, "keys", kind, "--format", "markdown"], check=True,
                          capture_output=True, text=True).stdout
    with open(os.path.join(folder, kind + ".md"), "w") as out:
        out.write(text)
    # Its title is the section's own; its tables become its sub-sections.
    lines = text.splitlines()
    if lines and lines[0].startswith("# "):
        lines = lines[1:]
    body = "\n".join(lines)
    return re.sub(r"^## ", "### ", body, flags=re.MULTILINE)


def _include_keys(app, docname, source):
    source[0] = _KEYS_FENCE.sub(lambda m: _generated_keys(app, m.group(1)), source[0])


def setup(app):
    app.connect("source-read", _include_keys)
    return {"parallel_read_safe": True}
