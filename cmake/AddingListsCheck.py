#!/usr/bin/python3
"""The "how to add" lists name files and names that exist (issue 33).

README.md ("Adding a field format", "Adding a scene key") and docs/transport.md ("Adding a
lighting model") tell a developer which files to touch, step by step. Each step names files in
backquotes (`app/fields/FieldIO.cxx`, or a bare `CloudMarchShader.cxx` found anywhere in the
tree), code names (`FieldFormats()`, `LightingParameters`) and tests (`app.scene_docs`). This
check fails naming every step whose file no longer exists, whose code name none of the step's
files mentions, or whose test no CMakeLists.txt under tests/ defines: a list that drifted from
the code.

    AddingListsCheck.py --source .
"""
import argparse
import pathlib
import re
import sys

LISTS = {
    "README.md": ["Adding a field format", "Adding a scene key"],
    "docs/transport.md": ["Adding a lighting model"],
}
SKIPPED = {"build", "out", ".git"}


def sections(text, titles):
    """The numbered steps under each heading of `titles`: (title, step number, step text)."""
    for title in titles:
        match = re.search(r"^#+ " + re.escape(title) + r"\s*$", text, re.M)
        if not match:
            yield title, 0, None
            continue
        body = text[match.end():]
        end = re.search(r"^#", body, re.M)
        body = body[: end.start()] if end else body
        for step in re.finditer(r"^(\d+)\. (.*?)(?=^\d+\. |^\S|\Z)", body, re.M | re.S):
            yield title, int(step.group(1)), step.group(2)


def find_file(source, name):
    if "/" in name:
        path = source / name
        return [path] if path.is_file() else []
    return [p for p in source.rglob(name) if not SKIPPED & set(p.relative_to(source).parts)]


def test_names(source):
    names = set()
    for cmake in (source / "tests").rglob("CMakeLists.txt"):
        names.update(re.findall(r"add_test\(NAME (\S+)", cmake.read_text()))
    return names


def check_step(source, tests, step):
    """The problems of one step: files that are missing, names its files do not hold."""
    problems, files = [], []
    quoted = re.findall(r"`([^`]+)`", step)
    for token in quoted:
        if re.fullmatch(r"[\w./-]+\.(cxx|h|glsl|txt|md|py|cmake)", token):
            found = find_file(source, token)
            if not found:
                problems.append("names `%s`, which does not exist" % token)
            files += found
    for token in quoted:
        if re.fullmatch(r"(app|render|unit)\.\w+", token):
            if token not in tests:
                problems.append("names the test `%s`, which no tests/ CMakeLists.txt defines" % token)
        elif re.fullmatch(r"[A-Z]\w*[a-z]\w*(\(\))?", token):  # not a macro (UNIFORM)
            name = token.rstrip("()")
            if files and not any(re.search(r"\b%s\b" % name, f.read_text()) for f in files):
                problems.append("names `%s`, which none of its files (%s) holds"
                                % (token, ", ".join(str(f.relative_to(source)) for f in files)))
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source", required=True, type=pathlib.Path)
    source = parser.parse_args().source.resolve()
    tests = test_names(source)
    problems, steps = [], 0
    for document, titles in LISTS.items():
        text = (source / document).read_text()
        for title, number, step in sections(text, titles):
            if step is None:
                problems.append('%s has no section "%s"' % (document, title))
                continue
            steps += 1
            for problem in check_step(source, tests, step):
                problems.append('%s, "%s", step %d %s' % (document, title, number, problem))
    for problem in problems:
        print(problem)
    if problems:
        return 1
    print("%d steps in %d lists, each naming files and names that exist"
          % (steps, sum(len(t) for t in LISTS.values())))
    return 0


if __name__ == "__main__":
    sys.exit(main())
