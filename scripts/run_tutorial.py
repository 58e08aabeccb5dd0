#!/usr/bin/env python3
"""Runs the commands of one tutorial page of the user guide, in order.

    run_tutorial.py PAGE.md --granasym BIN --work DIR [--copy NAME=PATH]...
                    [--module DIR --python BIN]

A tutorial command block is a MyST code block with the class `tutorial`:

    ```{code-block} bash
    :class: tutorial

    granasym study run studies/programmes/paper.toml --scale small --out study
    ```

A block of class tutorial in `python` is run by a Python interpreter of its
own (`--python`, default python3) at its place among the bash blocks: each
python block is a whole program, as a reader would save and run it.

The blocks are joined into one bash script (`set -euo pipefail`), which runs
in DIR (emptied first) as a reader's shell would at the repository root: the
repository's files are linked into DIR, `build/app/granasym` is BIN and BIN's
folder is first on PATH; `--module DIR` (the built Python module's folder)
is linked as build/python. The scale is forced to tiny: `--scale X`,
`SCALE=X` and a Python argument `scale="X"` become tiny, so a page may show
the scale a reader would choose.
`--copy NAME=PATH` copies a file or folder that a test fixture computed to
DIR/NAME first: a page's `study run` into a copied study finds its cases done
and computes nothing, so the page's later commands run on a real study at
the cost of a copy. Exits with the script's status; prints PASS with the count
of blocks and the time on success.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

FENCE = re.compile(r"^(`{3,})\{code-block\}\s+(\S+)\s*$")


def tutorial_blocks(page):
    """(line, language, text) of every code block with the class tutorial."""
    with open(page, encoding="utf-8") as f:
        lines = f.read().split("\n")
    blocks = []
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        fence, language, start = m.group(1), m.group(2), i + 1
        j = i + 1
        options = {}
        while j < len(lines) and lines[j].startswith(":"):
            key, _, value = lines[j][1:].partition(":")
            options[key.strip()] = value.strip()
            j += 1
        body = []
        while j < len(lines) and lines[j].rstrip() != fence:
            body.append(lines[j])
            j += 1
        if j == len(lines):
            sys.exit(f"error: {page}:{start}: code block without its closing {fence}")
        if "tutorial" in options.get("class", "").split():
            if language not in ("bash", "python"):
                sys.exit(f"error: {page}:{start}: a tutorial block is `bash` or `python`, "
                         f"not `{language}`")
            blocks.append((start, language, "\n".join(body).strip("\n")))
        i = j + 1
    return blocks


def force_tiny(text):
    forced = re.sub(r"--scale(\s+|=)(small|medium|paper)\b", r"--scale\1tiny", text)
    forced = re.sub(r"""\bscale\s*=\s*(["'])(small|medium|paper)\1""", r"scale=\1tiny\1", forced)
    return re.sub(r"\bSCALE=(small|medium|paper)\b", "SCALE=tiny", forced)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("page")
    parser.add_argument("--granasym", required=True, help="the built program")
    parser.add_argument("--work", required=True, help="folder to run in (emptied)")
    parser.add_argument("--copy", action="append", default=[], metavar="NAME=PATH",
                        help="copy a file or folder (a computed study) to WORK/NAME first")
    parser.add_argument("--module", help="the built Python module's folder (build/python)")
    parser.add_argument("--python", default="python3", help="the interpreter of python blocks")
    args = parser.parse_args()

    page = os.path.abspath(args.page)
    root = os.path.dirname(os.path.dirname(os.path.dirname(page)))
    if not os.path.isfile(os.path.join(root, "run.sh")):
        root = os.path.dirname(root)  # a page one folder deeper (docs/guide/tutorials)
    if not os.path.isfile(os.path.join(root, "run.sh")):
        sys.exit(f"error: {page}: not inside docs/guide of a granasym checkout")
    granasym = os.path.abspath(args.granasym)
    if not os.access(granasym, os.X_OK):
        sys.exit(f"error: --granasym {granasym}: not an executable")
    blocks = tutorial_blocks(page)
    if not blocks:
        sys.exit(f"error: {page}: no code block with `:class: tutorial`")

    work = os.path.abspath(args.work)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(os.path.join(work, "build", "app"))
    for entry in os.listdir(root):
        if entry in ("build", "out", ".git") or entry.startswith("."):
            continue
        os.symlink(os.path.join(root, entry), os.path.join(work, entry))
    os.symlink(granasym, os.path.join(work, "build", "app", "granasym"))
    if args.module:
        if not os.path.isdir(args.module):
            sys.exit(f"error: --module {args.module}: not a folder")
        os.symlink(os.path.abspath(args.module), os.path.join(work, "build", "python"))
    for spec in args.copy:
        name, sep, path = spec.partition("=")
        if not sep or not name or "/" in name or not os.path.exists(path):
            sys.exit(f"error: --copy {spec}: expected NAME=PATH with an existing file or folder")
        if os.path.isdir(path):
            shutil.copytree(path, os.path.join(work, name), symlinks=True)
        else:
            shutil.copy2(path, os.path.join(work, name))

    script = ["set -euo pipefail"]
    for line, language, text in blocks:
        script.append(f"echo '>>> {os.path.basename(page)}:{line}'")
        if language == "python":
            if "\nGRANASYM_PYTHON_BLOCK\n" in f"\n{text}\n":
                sys.exit(f"error: {page}:{line}: a line GRANASYM_PYTHON_BLOCK ends the block early")
            script.append(f"\"$GRANASYM_TUTORIAL_PYTHON\" - <<'GRANASYM_PYTHON_BLOCK'\n"
                          f"{force_tiny(text)}\nGRANASYM_PYTHON_BLOCK")
        else:
            script.append(force_tiny(text))
    with open(os.path.join(work, "tutorial.sh"), "w", encoding="utf-8") as f:
        f.write("\n".join(script) + "\n")
    env = dict(os.environ)
    env["PATH"] = os.path.join(work, "build", "app") + os.pathsep + env.get("PATH", "")
    env["GRANASYM_TUTORIAL_PYTHON"] = args.python
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    start = time.monotonic()
    status = subprocess.call(["bash", "-x", "tutorial.sh"], cwd=work, env=env)
    seconds = time.monotonic() - start
    if status != 0:
        print(f"FAIL: tutorial {os.path.basename(page)}: exit status {status} "
              f"after {seconds:.1f} s (the script: {work}/tutorial.sh)")
        return 1
    print(f"PASS: tutorial {os.path.basename(page)}: {len(blocks)} blocks in {seconds:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
