#!/usr/bin/python3
"""No function of the product's code is longer than a reader can hold at once (issue 33).

Lists every C++ function (lambdas included) of app/, filters/ and paraview/ with Universal Ctags,
and every Python function there with the ast module, and fails naming each one longer than
--most lines (150), from its name's line to its closing brace or last statement.

    FunctionLengths.py --source DIR [--most N] [--ctags PATH]
"""
import argparse
import ast
import os
import sys

from CppTags import cpp_tags

FOLDERS = ("app", "filters", "paraview")


def cpp_lengths(source, ctags):
    """(lines, path, name) of every C++ function and lambda Universal Ctags finds."""
    found = [(int(fields["end"]) - int(fields["line"]) + 1, path, name)
             for name, path, fields in cpp_tags(source, FOLDERS, "f", ctags,
                                                caller="FunctionLengths")
             if "line" in fields and "end" in fields]
    if not found:
        sys.exit(f"FunctionLengths: {ctags} gave no function with its end line: it must be "
                 "Universal Ctags (the universal-ctags package), not Exuberant Ctags")
    return found


def python_lengths(source):
    """(lines, path, name) of every Python function."""
    found = []
    for folder in FOLDERS:
        for root, _, files in os.walk(os.path.join(source, folder)):
            for name in files:
                if name.endswith(".py"):
                    path = os.path.join(root, name)
                    with open(path, encoding="utf-8") as file:
                        tree = ast.parse(file.read(), path)
                    for node in ast.walk(tree):
                        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                            found.append((node.end_lineno - node.lineno + 1,
                                          os.path.relpath(path, source), node.name))
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source", required=True)
    parser.add_argument("--most", type=int, default=150)
    parser.add_argument("--ctags", default="ctags")
    options = parser.parse_args()
    functions = cpp_lengths(options.source, options.ctags) + python_lengths(options.source)
    long = sorted((f for f in functions if f[0] > options.most), reverse=True)
    for lines, path, name in long:
        print(f"  {path}: {name} is {lines} lines")
    if long:
        sys.exit(f"{len(long)} functions of app/, filters/ and paraview/ are longer than "
                 f"{options.most} lines: split them into named steps")
    longest = max(functions)
    print(f"{len(functions)} functions, none over {options.most} lines (the longest: "
          f"{longest[1]}: {longest[2]}, {longest[0]})")


if __name__ == "__main__":
    main()
