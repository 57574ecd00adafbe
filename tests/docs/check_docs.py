#!/usr/bin/env python3
"""Checks every Markdown file of the repository.

    check_docs.py paths  SOURCE_DIR   every repository path the docs write exists
    check_docs.py issues SOURCE_DIR   no internal issue number ("issue 15")

The Markdown files: every *.md under SOURCE_DIR except in build*/, out/,
.git/ and other dot-folders, and third-party or generated trees (venv,
node_modules, _deps).

What counts as a repository path (the rule, so that a miss is explainable):
- the target of a Markdown link `[text](target)` that is not a URL
  (scheme://, mailto:) or a bare #anchor; the #anchor is dropped;
- an inline code span `like/this` of one word (no space) holding a '/'
  whose first component exists in the repository root or, for a relative
  path, in the Markdown file's own folder (or is '..'); so `tlm/bus/bus.h`
  and, in sw_driver/README.md, `gl/README.md` count, while `min / max`,
  `9.4/0.24` or `out/frame_0000.png` do not.
Left out: fenced code blocks (commands and program output: the README's
are run by readme_commands), paths under build/ or out/ (what a build or a
run makes), absolute paths and ~ or $VARIABLE paths (the user's), paths
with a placeholder (<id>, NNNN, *, ..., {a,b} is expanded instead),
and the text after a ':' line number or a '::' C++ scope. `name.h/.cpp`
stands for both files. A Markdown file that walks through a hypothetical
example names the example's paths in a comment, which exempts paths
starting with them in that file only:
    <!-- check_docs: example paths tlm/sdma tests/sdma -->
A link target passes when it exists relative to the Markdown file's
folder (where a viewer resolves it); a code span when it exists relative to
the repository root or to the Markdown file's folder, or, without an
extension, as PATH.cpp (a test or tool program named by its source).
"""

import pathlib
import re
import sys

SKIP_DIRS = {"out", "venv", "node_modules", "_deps", "__pycache__"}
GENERATED_ROOTS = {"build", "out"}


def markdown_files(root):
    for path in sorted(root.rglob("*.md")):
        parts = path.relative_to(root).parts
        if any(part.startswith(".") or part.startswith("build") or part in SKIP_DIRS for part in parts[:-1]):
            continue
        yield path


def prose(text):
    """The text outside fenced code blocks, with line numbers."""
    fenced = False
    for number, line in enumerate(text.splitlines(), 1):
        if re.match(r"^\s*(```|~~~)", line):
            fenced = not fenced
            continue
        if not fenced:
            yield number, line


def expand_braces(path):
    pair = re.match(r"^(.*)\.(\w+)/\.(\w+)$", path)  # name.h/.cpp
    if pair:
        return [f"{pair.group(1)}.{pair.group(2)}", f"{pair.group(1)}.{pair.group(3)}"]
    match = re.search(r"\{([^{}]*,[^{}]*)\}", path)
    if not match:
        return [path]
    return [
        expanded
        for choice in match.group(1).split(",")
        for expanded in expand_braces(path[: match.start()] + choice + path[match.end() :])
    ]


def candidates(line):
    for match in re.finditer(r"\[[^\]]*\]\(([^)\s]+)\)", line):
        target = match.group(1)
        if re.match(r"^[a-z]+:", target) or target.startswith("#"):
            continue
        yield target.split("#")[0], True
    # Inline code spans, outside the link targets.
    for match in re.finditer(r"`([^`\s]+)`", re.sub(r"\]\([^)]*\)", "]()", line)):
        token = match.group(1)
        if "/" in token:
            yield token, False


def is_checked(token):
    if re.match(r"^([a-z]+:|/|~|\$)", token) or "://" in token:
        return False
    if any(mark in token for mark in ("<", ">", "*", "...", "NNNN", "%", "=")):
        return False
    return True


def clean(token):
    token = token.split("::")[0]
    token = re.sub(r":\d.*$", "", token)  # file.cpp:123
    token = token.rstrip(".,;:)")
    return token


def check_paths(root):
    root_entries = {entry.name for entry in root.iterdir()}
    failures = []
    checked = 0
    for md in markdown_files(root):
        folder = md.parent
        folder_entries = {entry.name for entry in folder.iterdir()}
        text = md.read_text(errors="replace")
        examples = [
            prefix
            for comment in re.findall(r"<!-- check_docs: example paths ([^>]*)-->", text)
            for prefix in comment.split()
        ]
        for number, line in prose(text):
            for token, is_link in candidates(line):
                if not token or not is_checked(token):
                    continue
                token = clean(token)
                first = token.split("/")[0]
                if first in GENERATED_ROOTS:
                    continue
                if not is_link and first not in root_entries and first not in folder_entries and first != "..":
                    continue
                if any(token.startswith(prefix) for prefix in examples):
                    continue
                for path in expand_braces(token):
                    checked += 1
                    bases = (folder,) if is_link else (root, folder)
                    exists = any(
                        (base / path).exists()
                        or (not is_link and not pathlib.PurePath(path).suffix and (base / (path + ".cpp")).exists())
                        for base in bases
                    )
                    if not exists:
                        failures.append(f"{md.relative_to(root)}:{number}: '{path}' does not exist")
    for failure in failures:
        print(failure)
    print(f"{checked} repository paths checked in the Markdown files, {len(failures)} missing")
    return 1 if failures or checked == 0 else 0


# "issue 15", "issues 13 and 15", "Issue 15's", "(#15)", "issue #15", and
# the issue named without its number ("the issue's goal", "this issue").
ISSUE_NUMBER = re.compile(r"\bissues?\s+#?\d+|\(#\d+\)|\bthe issue's|\bthis issue\b", re.I)


def check_issues(root):
    failures = []
    files = 0
    for md in markdown_files(root):
        files += 1
        for number, line in enumerate(md.read_text(errors="replace").splitlines(), 1):
            for match in ISSUE_NUMBER.finditer(line):
                failures.append(f"{md.relative_to(root)}:{number}: '{match.group(0)}': say what the thing is instead")
    for failure in failures:
        print(failure)
    print(f"{files} Markdown files checked for internal issue numbers, {len(failures)} found")
    return 1 if failures or files == 0 else 0


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("paths", "issues"):
        sys.exit(__doc__)
    root = pathlib.Path(sys.argv[2]).resolve()
    return check_paths(root) if sys.argv[1] == "paths" else check_issues(root)


if __name__ == "__main__":
    sys.exit(main())
