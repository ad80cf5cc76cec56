# minksum — the two commands a newcomer needs are `make demo` and `make test`.
# Both install missing Debian packages (as root), configure, build and run.

BUILD      ?= build
BUILD_TYPE ?= Release
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
SANITIZE   ?= OFF
CMAKE_ARGS ?=

CONFIGURE = cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) \
            -DMINKSUM_SANITIZE=$(SANITIZE) $(CMAKE_ARGS)

.PHONY: all setup configure build demo test test-long asan clean

all: build

setup:
	@bash scripts/setup.sh

$(BUILD)/CMakeCache.txt:
	@$(MAKE) --no-print-directory setup
	$(CONFIGURE)

configure: setup
	$(CONFIGURE)

build: $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# The main job on built-in polytopes: no input files needed.
demo: build
	@mkdir -p $(BUILD)/demo
	$(BUILD)/bin/minksum sum cube sphere:3 --method chms -o $(BUILD)/demo/cube+sphere3.off
	$(BUILD)/bin/minksum sum dodecahedron truncated-cube --method chms -o $(BUILD)/demo/dodeca+trunccube.off
	$(BUILD)/bin/minksum stats $(BUILD)/demo/cube+sphere3.off

# The whole suite, with assertions on (MINKSUM_ASSERTIONS keeps assert() live in Release).
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -LE long

test-long: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -L long

# Debug build with AddressSanitizer + UndefinedBehaviorSanitizer, then the suite.
asan:
	$(MAKE) --no-print-directory test BUILD=build-asan BUILD_TYPE=Debug SANITIZE=ON

clean:
	rm -rf $(BUILD) build-asan
