#!/usr/bin/python3
"""A header declares what other files call (issue 33).

Lists with Universal Ctags every free function a header of app/, filters/ or paraview/ declares
(a prototype outside a class), finds the source file that defines it, and fails naming each one
that no other file of the project (app, filters, paraview, bench, tests, python) mentions: a
function only its own file calls belongs in that file's anonymous namespace, not in a header.

    UnusedExports.py --source DIR [--ctags PATH]
"""
import argparse
import os
import re
import sys

from CppTags import cpp_tags

DECLARING = ("app", "filters", "paraview")
CALLING = ("app", "filters", "paraview", "bench", "tests", "python")
SUFFIXES = (".h", ".cxx", ".py", ".glsl", ".cmake", ".txt")
# A mention in a comment is no call.
COMMENT = re.compile(r"//[^\n]*|/\*.*?\*/", re.DOTALL)


def project_files(source):
    """Every file of the project that may call a declared function, with its text."""
    texts = {}
    for folder in CALLING:
        for root, _, names in os.walk(os.path.join(source, folder)):
            for name in names:
                if name.endswith(SUFFIXES):
                    path = os.path.join(root, name)
                    with open(path, encoding="utf-8", errors="replace") as file:
                        texts[os.path.relpath(path, source)] = COMMENT.sub("", file.read())
    return texts


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source", required=True)
    parser.add_argument("--ctags", default="ctags")
    options = parser.parse_args()
    tags = lambda kinds: cpp_tags(options.source, DECLARING, kinds, options.ctags,
                                  caller="UnusedExports")
    declared = [(name, path) for name, path, fields in tags("p")
                if path.endswith(".h") and not ("class" in fields or "struct" in fields)
                and not name.startswith("operator")]
    if not declared:
        sys.exit(f"UnusedExports: {options.ctags} found no function declared in a header")
    declarations = {}
    for entry in declared:
        declarations[entry] = declarations.get(entry, 0) + 1
    defined = {}
    for name, path, _ in tags("f"):
        if path.endswith(".cxx"):
            defined.setdefault(name, set()).add(path)
    texts = project_files(options.source)
    unused = []
    for name, header in sorted(set(declared)):
        own = {header} | defined.get(name, set())
        word = re.compile(r"\b" + re.escape(name) + r"\b")
        # The header may call it itself (a default argument, an inline function): any mention
        # there beyond its declarations.
        in_header = len(word.findall(texts[header])) > declarations[(name, header)]
        if not in_header and not any(
                word.search(text) for path, text in texts.items() if path not in own):
            unused.append((header, name, sorted(defined.get(name, {"no file"}))))
    for header, name, definitions in unused:
        print(f"  {header}: {name} is called only in {', '.join(definitions)}")
    if unused:
        sys.exit(f"{len(unused)} functions are declared in a header and used only in the file "
                 "that defines them: make them local to that file")
    print(f"{len(set(declared))} functions declared in headers, each used beyond its own file")


if __name__ == "__main__":
    main()
