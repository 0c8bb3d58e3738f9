"""The C++ tags Universal Ctags lists, for the checks of the code's shape (FunctionLengths.py,
UnusedExports.py)."""
import subprocess
import sys


def cpp_tags(source, folders, kinds, ctags="ctags", fields="+neKS", caller="CppTags"):
    """(name, path, fields) of every C++ tag of `kinds` (ctags' letters: f functions, p
    prototypes) under `folders` of `source`, paths relative to it."""
    try:
        listing = subprocess.run(
            [ctags, f"--fields={fields}", "-o", "-", "-R", "--languages=C++",
             f"--kinds-C++={kinds}"] + list(folders),
            cwd=source, capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError) as error:
        sys.exit(f"{caller}: {ctags} could not list the functions ({error}); "
                 "cmake/debian-packages.txt installs universal-ctags")
    found = []
    for line in listing.splitlines():
        columns = line.split("\t")
        found.append((columns[0], columns[1],
                      dict(c.split(":", 1) for c in columns[3:] if ":" in c)))
    return found
