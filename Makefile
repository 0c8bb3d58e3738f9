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

.PHONY: all deps configure build demo test bench clean

all: build

deps:
	@bash cmake/install-deps.sh

$(BUILD_DIR)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE)

configure: deps $(BUILD_DIR)/CMakeCache.txt

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

demo: build
	$(HEADLESS) $(CLOUDVIS)

test: build
	cd $(BUILD_DIR) && $(HEADLESS) ctest --output-on-failure -j $(JOBS)

bench: build
	$(HEADLESS) $(BUILD_DIR)/bin/cloudvis-bench-generation

clean:
	rm -rf $(BUILD_DIR) out
