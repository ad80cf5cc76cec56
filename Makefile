# minksum — the two commands a newcomer needs are `make demo` and `make test`.
# Both install missing Debian packages (as root), configure, build and run.

BUILD      ?= build
BUILD_TYPE ?= Release
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
SANITIZE   ?= OFF
CMAKE_ARGS ?=

CONFIGURE = cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) \
            -DMINKSUM_SANITIZE=$(SANITIZE) $(CMAKE_ARGS)

.PHONY: all setup configure build demo test test-long asan tsan clean

all: build

setup:
	@bash scripts/setup.sh
	@bash scripts/setup-web.sh

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
	$(BUILD)/bin/minksum sum cube sphere:3 --exact -o $(BUILD)/demo/cube+sphere3.off
	$(BUILD)/bin/minksum sum sphere:6 sphere:6@rot:1
	$(BUILD)/bin/minksum sum dodecahedron truncated-cube --method essdms --exact -o $(BUILD)/demo/dodeca+trunccube.off
	$(BUILD)/bin/minksum sum sphere:3 sphere:3@rot:5 --method cgm --exact -o $(BUILD)/demo/sphere3+rotated.off
	$(BUILD)/bin/minksum stats $(BUILD)/demo/cube+sphere3.off
	$(BUILD)/bin/minksum sum tube sphere:2@scale:1/4 --exact -o $(BUILD)/demo/tube+sphere2.off
	$(BUILD)/bin/minksum cgm dioctagonal:17 dioctagonal:17@rot:100,0,0,99 --svg $(BUILD)/demo/cgm.svg
	$(BUILD)/bin/minksum view truncated-cube sphere:3@rot:1 -o $(BUILD)/demo/scene.html
	$(BUILD)/bin/minksum sum truncated-cube segment:0,0,0:3,1,2 -o $(BUILD)/demo/sweep.off
	@echo "demo: open $(abspath $(BUILD))/demo/scene.html in a browser (one file, works offline): A, B and A ⊕ B in 3D"

# Fig. 4 of Fogel and Halperin (2006): a robot grazing, then penetrating an obstacle, turning every
# other frame (answered on the placed bodies, without M); per-frame state and query time, and an SVG trail.
.PHONY: demo-motion
demo-motion: build
	@mkdir -p $(BUILD)/demo
	$(BUILD)/bin/minksum simulate --frames 40 -o $(BUILD)/demo/motion.svg

# The whole suite, with assertions on (MINKSUM_ASSERTIONS keeps assert() live in Release).
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -LE long

test-long: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -L long

# Debug build with AddressSanitizer + UndefinedBehaviorSanitizer, then the suite.
asan:
	$(MAKE) --no-print-directory test BUILD=build-asan BUILD_TYPE=Debug SANITIZE=ON

# The same build, with only the fast suites (what .ci/run runs): the unit
# suites of the targets below (the convex core, I/O, the command line,
# sweeps, proximity under translation and under rigid motion), without the
# CGM sums (minutes under the sanitizers; the same code paths run in the
# optimised suite), the predicates' bulk random agreement tests (their
# degenerate, extreme-magnitude and rounding-mode cases stay), the layer
# probes and the package test.  The conformance matrix, the slope-diagram
# methods, CVMS and the non-convex engine's suites run in the optimised
# suite only.
ASAN_FAST_TARGETS = minksum_cli test_catalog test_cgm test_chms test_cli test_difference test_io \
                    test_mesh_support test_point_list test_polytope test_predicates test_progress \
                    test_proximity test_reliability test_rigid_proximity test_rounded_predicates test_roundtrip \
                    test_sweep test_walk
ASAN_FAST_EXCLUDE = ^((CgmSum|layers|package)[.]|PredicateTest[.](RandomUniform|Rationals|RandomSmallIntegers|RandomWideExponents)<)
.PHONY: asan-fast
asan-fast:
	@$(MAKE) --no-print-directory setup
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DMINKSUM_SANITIZE=ON $(CMAKE_ARGS)
	cmake --build build-asan -j $(JOBS) --target $(ASAN_FAST_TARGETS)
	cd build-asan && ctest --output-on-failure -j $(JOBS) -L unit -E '$(ASAN_FAST_EXCLUDE)' --no-tests=error

# Optimised build (with debug info and assertions) under ThreadSanitizer in
# build-tsan/, then the tests that run threads: concurrent sums with progress
# and cancellation, concurrent readers of lazily computed planes, per-thread
# predicate counters, and the progress line's display thread in `minksum sum`.
TSAN_BUILD   = build-tsan
TSAN_TARGETS = test_progress test_point_list test_predicates test_cli minksum_cli
TSAN_TESTS   = ^(ProgressReports|Cancellation|LazyCache|PredicateStatsTest\.CountersArePerThread|Cli\.SumProgress)
tsan:
	@$(MAKE) --no-print-directory setup
	cmake -S . -B $(TSAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMINKSUM_TSAN=ON -DMINKSUM_SANITIZE=OFF $(CMAKE_ARGS)
	cmake --build $(TSAN_BUILD) -j $(JOBS) --target $(TSAN_TARGETS)
	cd $(TSAN_BUILD) && TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" \
	  ctest --output-on-failure -j $(JOBS) -L unit -R '$(TSAN_TESTS)' --no-tests=error

# The README's screenshots (docs/images/*.png): pages written by minksum,
# photographed in Debian's headless chromium (web/screenshots.mjs).
.PHONY: screenshots
screenshots: build
	node web/screenshots.mjs --minksum $(BUILD)/bin/minksum --out docs/images

clean:
	rm -rf $(BUILD) build-asan $(TSAN_BUILD) $(BENCH_BUILD) $(FUZZ_BUILD)

# The side-by-side benchmark (bench/, docs/generated/benchmarks.md): a separate Release
# build with assertions off.  `make bench` runs the full suite and rewrites
# docs/generated/benchmarks.md, docs/generated/benchmarks-plot.svg and docs/generated/benchmarks-proximity.md
# (minksum's proximity queries against libccd); `make bench-quick` runs the
# short development suite and writes build-bench/quick/benchmarks.md;
# `make bench-e2e` runs the end-to-end section alone (whole processes, file to
# file: `minksum sum` against Qhull's `qconvex`) and rewrites that section of
# docs/generated/benchmarks.md.
BENCH_BUILD ?= build-bench
BENCH_JOBS  ?= 2
BENCH_CONFIGURE = cmake -S . -B $(BENCH_BUILD) -DCMAKE_BUILD_TYPE=Release -DMINKSUM_BENCH=ON \
                  -DMINKSUM_ASSERTIONS=OFF -DMINKSUM_TESTS=OFF
.PHONY: bench bench-quick bench-e2e

bench:
	@$(MAKE) --no-print-directory setup
	$(BENCH_CONFIGURE)
	cmake --build $(BENCH_BUILD) -j $(BENCH_JOBS) --target minksum_bench bench_proximity minksum_cli bench_spawn
	$(BENCH_BUILD)/bin/minksum_bench --suite full --out docs/generated --command "make bench"
	bash bench/proximity/run.sh $(BENCH_BUILD)
	$(E2E) --command "make bench"

E2E = /usr/bin/python3 bench/e2e.py --minksum $(BENCH_BUILD)/bin/minksum --work $(BENCH_BUILD)/e2e \
      --page docs/generated/benchmarks.md

# Sums of non-convex solids: minksum, CGAL's minkowski_sum_3 (stopped after
# 120 s) and Manifold's minkowskiSum (npm manifold-3d under Node) in one run;
# rewrites docs/generated/benchmarks-nonconvex.md (docs/nonconvex.md, "Speed").
.PHONY: bench-nonconvex
bench-nonconvex:
	@$(MAKE) --no-print-directory setup
	bash scripts/setup-web.sh bench/nonconvex
	$(BENCH_CONFIGURE)
	cmake --build $(BENCH_BUILD) -j $(BENCH_JOBS) --target bench_nonconvex minksum_cli
	/usr/bin/python3 bench/nonconvex/run.py --build $(BENCH_BUILD) --page docs/generated/benchmarks-nonconvex.md \
	  $(if $(MESHES),--meshes $(MESHES)) --command "make bench-nonconvex$(if $(MESHES), MESHES=<a directory of meshes>)"

bench-e2e:
	@$(MAKE) --no-print-directory setup
	$(BENCH_CONFIGURE)
	cmake --build $(BENCH_BUILD) -j $(BENCH_JOBS) --target minksum_cli bench_spawn
	$(E2E) --command "make bench-e2e"

# The Python package against its C++ calls and against scipy.spatial.ConvexHull
# (bench/python_bench.py); rewrites the benchmark section of docs/python.md.
.PHONY: bench-python
bench-python:
	@$(MAKE) --no-print-directory setup
	$(BENCH_CONFIGURE)
	cmake --build $(BENCH_BUILD) -j $(BENCH_JOBS) --target minksum_python
	PYTHONPATH=$(BENCH_BUILD)/python /usr/bin/python3 bench/python_bench.py --page docs/python.md --command "make bench-python"

# The walk against the conversion of its result to a ConvexPolytope
# (to_polytope), alternating on the pairs of docs/data-model.md.
CONVERSION_PAIRS ?= sphere:3 sphere:3@rot:1 sphere:4 sphere:4@rot:1 sphere:5 sphere:5@rot:1 \
                    sphere:6 sphere:6@rot:1 sphere:5@rot:1 sphere:5@rot:2 icosahedron icosahedron@rot:1 \
                    pentagonal-hexecontahedron truncated-icosidodecahedron cube box:1:2:3@rot:1 cube sphere:6
.PHONY: bench-conversion
bench-conversion:
	@$(MAKE) --no-print-directory setup
	$(BENCH_CONFIGURE)
	cmake --build $(BENCH_BUILD) -j $(BENCH_JOBS) --target bench_conversion
	$(BENCH_BUILD)/bin/bench_conversion $(CONVERSION_PAIRS)

bench-quick:
	@$(MAKE) --no-print-directory setup
	$(BENCH_CONFIGURE)
	cmake --build $(BENCH_BUILD) -j $(BENCH_JOBS) --target minksum_bench
	@mkdir -p $(BENCH_BUILD)/quick
	$(BENCH_BUILD)/bin/minksum_bench --suite quick --out $(BENCH_BUILD)/quick --command "make bench-quick"

# libFuzzer targets (tests/fuzz/): each reader (off obj ply stl wrl) through
# the public io API, the trajectory-line and query-vector parsers, and the
# writer of non-convex solids over extreme scales (solid_writer), built
# with clang, ASan and UBSan in build-fuzz/ (MINKSUM_FUZZ=ON; only the layers
# they use).  `make fuzz` runs each for FUZZ_SECONDS from its seed corpus
# (tests/fuzz/corpus/); `make fuzz-smoke` for 20 s each (what .ci/run does).
# A finding is saved in build-fuzz/fuzz-artifacts/TARGET/ and fails the run.
FUZZ_BUILD   ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_TARGETS ?= off obj ply stl wrl trajectory vector solid_writer
.PHONY: fuzz fuzz-smoke fuzz-build
fuzz-build:
	@$(MAKE) --no-print-directory setup
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMINKSUM_FUZZ=ON \
	  -DMINKSUM_TESTS=OFF -DMINKSUM_STATIC_CLI=OFF $(CMAKE_ARGS)
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS))

fuzz: fuzz-build
	bash scripts/fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

fuzz-smoke:
	@$(MAKE) --no-print-directory fuzz FUZZ_SECONDS=20
