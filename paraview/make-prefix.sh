#!/usr/bin/env bash
# Makes the private prefix that ParaView's Python and CMake files need beside Debian's VTK
# (docs/paraview.md, "Installing"): usage make-prefix.sh DIR.
#
# Debian's python3-paraview and python3-vtk9 both ship the Python package `vtkmodules`, so they
# cannot be installed together, and cloudvis needs python3-vtk9 for `import cloudvis`. pvbatch and
# pvpython need python3-paraview's files, and so does paraview-dev's CMake package: its targets
# name the Python modules' files and CMake refuses a package whose files are missing. So the
# package is extracted (not installed) into DIR/python, and DIR/usr mirrors /usr with links except
# for lib/python3/dist-packages, which holds the extracted files. CMake finds ParaView in DIR/usr,
# where every file its targets name exists; pvbatch and pvpython run with
# PYTHONPATH=DIR/python/usr/lib/python3/dist-packages. Nothing outside DIR is written, and no root
# is needed.
set -euo pipefail
dir=${1:?usage: make-prefix.sh DIR}
version=$(dpkg-query -W -f='${Version}' paraview-dev 2>/dev/null || true)
if [ -z "$version" ]; then
  echo "make-prefix.sh: paraview-dev is not installed (cmake/install-deps.sh installs it)" >&2
  exit 1
fi
# Made once per ParaView version: the stamp names the version it was made for.
if [ "$(cat "$dir/version" 2>/dev/null || true)" = "$version" ]; then
  exit 0
fi
rm -rf "$dir"
mkdir -p "$dir/download"
# The same version as paraview's, which apt-get download fetches from the configured sources.
(cd "$dir/download" && apt-get download -q "python3-paraview=$version" 2>&1 | grep -v "unsandboxed")
dpkg-deb -x "$dir"/download/python3-paraview_*.deb "$dir/python"
rm -rf "$dir/download"

arch=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || gcc -print-multiarch)
usr="$dir/usr"
mkdir -p "$usr/bin" "$usr/lib/$arch" "$usr/lib/python3"
for top in include share; do
  ln -s "/usr/$top" "$usr/$top"
done
# pvpython is the package's too.
for entry in /usr/bin/* "$dir"/python/usr/bin/*; do
  ln -sf "$entry" "$usr/bin/$(basename "$entry")"
done
for entry in /usr/lib/"$arch"/*; do
  case "$(basename "$entry")" in cmake | vtk) continue ;; esac
  ln -s "$entry" "$usr/lib/$arch/$(basename "$entry")"
done
# ParaView's CMake files are copied, not linked: they find their prefix from their real path.
mkdir -p "$usr/lib/$arch/cmake"
for entry in /usr/lib/"$arch"/cmake/*; do
  ln -s "$entry" "$usr/lib/$arch/cmake/$(basename "$entry")"
done
rm "$usr/lib/$arch/cmake/paraview-5.11"
cp -r "/usr/lib/$arch/cmake/paraview-5.11" "$usr/lib/$arch/cmake/"
# The wrap hierarchies of ParaView's modules, which the package does not ship, are written here by
# the build (paraview/WrapHierarchies.cmake).
mkdir -p "$usr/lib/$arch/vtk/hierarchy/ParaView"
ln -s "$dir/python/usr/lib/python3/dist-packages" "$usr/lib/python3/dist-packages"
echo "$version" > "$dir/version"
