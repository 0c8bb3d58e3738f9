#!/bin/sh
# Makes what the baseline tests render the new baselines (tests/baselines/NAME.png), on purpose
# only: after a change meant to change a picture, or for a new baseline test. It runs the tests
# whose names contain ".Baseline." with CLOUDVIS_REGENERATE_BASELINES=1, which writes each image
# into this folder instead of comparing. Look at every image it changed before committing it.
#
#   tests/baselines/regenerate.sh [BUILD_DIR]        (default: build, built already)
#
# An alternate for a platform that draws a picture differently but rightly is NAME_1.png (then
# _2 ...): copy it by hand from the build's tests/baseline-output, where a failing test leaves
# its image and the difference.
set -eu
baselines=$(cd "$(dirname "$0")" && pwd)
build=${1:-build}
cd "$build"
if [ -n "${DISPLAY:-}" ]; then
  CLOUDVIS_REGENERATE_BASELINES=1 ctest -R '\.Baseline\.' --output-on-failure
else
  CLOUDVIS_REGENERATE_BASELINES=1 xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
    ctest -R '\.Baseline\.' --output-on-failure
fi
git -C "$baselines" status --short .
