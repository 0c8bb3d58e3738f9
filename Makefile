# The two set-up commands of the README, and a few helpers around them.
#   make demo   install what is missing, build, render the default scene into out/
#   make test   install what is missing, build, run every test (under Xvfb when there is no display)

BUILD_DIR ?= build
BUILD_TYPE ?= RelWithDebInfo
JOBS ?= $(shell nproc)
CLOUDVIS := $(BUILD_DIR)/bin/cloudvis
# Tests and the demo need an X display; without one, run them under a virtual framebuffer.
# -noreset: the server must not restart (and refuse connections) each time its last client,
# one test process, disconnects.
HEADLESS := $(if $(DISPLAY),,xvfb-run -a -s "-screen 0 1280x1024x24 -noreset")
# ccache, when the machine has it, makes rebuilds across clones and build folders cheap; the
# build does not need it.
CCACHE := $(shell command -v ccache 2> /dev/null)
CCACHE_ARGS := $(if $(CCACHE),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
CCACHE_ENV := CCACHE_BASEDIR=$(CURDIR) CCACHE_NOHASHDIR=1

.PHONY: all deps configure build demo python test bench bench-check docs clean python-path

all: build

deps:
	@bash cmake/install-deps.sh

$(BUILD_DIR)/CMakeCache.txt: | deps
	$(CCACHE_ENV) cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(CCACHE_ARGS)

configure: deps $(BUILD_DIR)/CMakeCache.txt

build: configure
	$(CCACHE_ENV) cmake --build $(BUILD_DIR) -j $(JOBS)

# The demo builds the cloudvis binary alone: nothing it renders waits on the Python wrapping or
# the tests (`make test` and `make python` build those).
demo: configure
	$(CCACHE_ENV) cmake --build $(BUILD_DIR) -j $(JOBS) --target cloudvis
	$(HEADLESS) $(CLOUDVIS)

# `import cloudvis` (docs/python.md): the wrapped modules, which `make test` also builds.
python: configure
	$(CCACHE_ENV) cmake --build $(BUILD_DIR) -j $(JOBS) --target cloudvis-python

test: build
	cd $(BUILD_DIR) && $(HEADLESS) ctest --output-on-failure -j $(JOBS)

bench: build
	$(HEADLESS) $(BUILD_DIR)/bin/cloudvis-bench-generation

# The ratios that matter on small sizes (about 30 s here) against bench/check-figures.json: prints
# each, and every one worse by more than 15% (exit status 1 then). Never part of `make test`.
# `python3 bench/check.py --record` writes a new record (docs/performance.md).
bench-check: build
	$(HEADLESS) python3 bench/check.py --build $(BUILD_DIR)

# The reference tables of docs/scene-format.md, written from the scene schema (cloudvis schema).
docs: build
	cmake -DCLOUDVIS=$(CLOUDVIS) -DDOC=docs/scene-format.md -DUPDATE=ON -P cmake/SceneDocs.cmake

clean:
	rm -rf $(BUILD_DIR) out

# Where `import cloudvis` finds the package after `make python` (or `make test`) (docs/python.md):
#   make python && PYTHONPATH=$(make -s python-path) python3 -c "import cloudvis"
python-path:
	@path=$$(sed -n 's/^CLOUDVIS_PYTHONPATH:INTERNAL=//p' $(BUILD_DIR)/CMakeCache.txt 2> /dev/null); \
	if [ -z "$$path" ]; then \
	  echo "make python-path: no Python package in $(BUILD_DIR): run make python first (CLOUDVIS_PYTHON on)" >&2; exit 1; \
	fi; echo "$$path"

# ---- reliability: sanitizers, fuzzing, soak (docs/reliability.md) ----------------------------
#   make test-asan        Debug build with AddressSanitizer + UBSan in build-asan, the whole ctest suite
#   make test-asan-unit   the same build, only the unit tests (what .ci/run adds after `make test`)
#   make fuzz             libFuzzer targets (clang) in build-fuzz, FUZZ_SECONDS each (default 60)
#   make soak             the 1,000-frame soak test in $(BUILD_DIR) (ctest label "soak")
ASAN_BUILD_DIR ?= build-asan
FUZZ_BUILD_DIR ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_TARGETS := scene override field
SANITIZER_FILES := $(CURDIR)/tests/sanitizers
# Leaks fail a test (LSan reports through ASan's exit code); UBSan already aborts at the first
# report (-fno-sanitize-recover). The suppressions cover third-party code only.
# Mesa's GLX and DRI driver are preloaded so they are never unloaded: glvnd dlclose()s them before
# LeakSanitizer looks, and their allocations then show as leaks from "<unknown module>" that no
# suppression can name (see tests/sanitizers/lsan.supp). verify_asan_link_order=0 allows the
# preload ahead of libasan.
MESA_PRELOAD := $(wildcard /usr/lib/$(shell gcc -print-multiarch)/dri/swrast_dri.so \
  /usr/lib/$(shell gcc -print-multiarch)/libGLX_mesa.so.0)
SANITIZER_ENV := ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:check_initialization_order=1:verify_asan_link_order=0 \
  LSAN_OPTIONS=suppressions=$(SANITIZER_FILES)/lsan.supp:print_suppressions=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:suppressions=$(SANITIZER_FILES)/ubsan.supp
SANITIZER_RUN_ENV := $(SANITIZER_ENV) LD_PRELOAD="$(MESA_PRELOAD)"

.PHONY: asan-build test-asan test-asan-unit fuzz soak

$(ASAN_BUILD_DIR)/CMakeCache.txt: | deps
	$(CCACHE_ENV) cmake -S . -B $(ASAN_BUILD_DIR) -DCMAKE_BUILD_TYPE=Debug \
	  -DCLOUDVIS_SANITIZE=address,undefined $(CCACHE_ARGS)

# The build runs test executables (gtest discovery), so it needs the sanitizer settings too.
asan-build: $(ASAN_BUILD_DIR)/CMakeCache.txt
	$(CCACHE_ENV) $(SANITIZER_ENV) cmake --build $(ASAN_BUILD_DIR) -j $(JOBS)

test-asan: asan-build
	cd $(ASAN_BUILD_DIR) && $(SANITIZER_RUN_ENV) $(HEADLESS) ctest --output-on-failure -j $(JOBS)

test-asan-unit: $(ASAN_BUILD_DIR)/CMakeCache.txt
	$(CCACHE_ENV) $(SANITIZER_ENV) cmake --build $(ASAN_BUILD_DIR) -j $(JOBS) --target cloudvis-unit-tests
	cd $(ASAN_BUILD_DIR) && $(SANITIZER_ENV) ctest --output-on-failure -j $(JOBS) -R '^unit\.'

$(FUZZ_BUILD_DIR)/CMakeCache.txt: | deps
	$(CCACHE_ENV) cmake -S . -B $(FUZZ_BUILD_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang -DCLOUDVIS_FUZZ=ON \
	  -DCLOUDVIS_SANITIZE=address,undefined -DBUILD_TESTING=OFF $(CCACHE_ARGS)

# Each target starts from its seed corpus; what it finds on the way is kept in
# $(FUZZ_BUILD_DIR)/corpus/<target> (not in the source tree), crashes in $(FUZZ_BUILD_DIR)/crashes.
# CLOUDVIS_READ_SECONDS: the isolated read of a field file (app/fields/private/IsolatedRead.h)
# gives up before libFuzzer's -timeout, so a slow library is reported by cloudvis, not as a hang.
fuzz: $(FUZZ_BUILD_DIR)/CMakeCache.txt
	$(CCACHE_ENV) cmake --build $(FUZZ_BUILD_DIR) -j $(JOBS) \
	  $(foreach t,$(FUZZ_TARGETS),--target cloudvis-fuzz-$(t))
	mkdir -p $(FUZZ_BUILD_DIR)/crashes
	set -e; for t in $(FUZZ_TARGETS); do \
	  mkdir -p $(FUZZ_BUILD_DIR)/corpus/$$t; \
	  echo "== fuzzing $$t for $(FUZZ_SECONDS) s"; \
	  CLOUDVIS_READ_SECONDS=20 $(SANITIZER_ENV) $(FUZZ_BUILD_DIR)/bin/cloudvis-fuzz-$$t -max_total_time=$(FUZZ_SECONDS) \
	    -rss_limit_mb=4096 -timeout=30 -print_final_stats=1 \
	    -artifact_prefix=$(FUZZ_BUILD_DIR)/crashes/$$t- \
	    $(FUZZ_BUILD_DIR)/corpus/$$t tests/fuzz/corpus/$$t; \
	done

soak: build
	cd $(BUILD_DIR) && CLOUDVIS_SOAK=1 $(if $(findstring asan,$(BUILD_DIR)),$(SANITIZER_RUN_ENV)) \
	  $(HEADLESS) ctest --output-on-failure -L soak
