# Argil: two commands on a fresh Debian 12 machine.
#   make demo   installs what is missing, builds, runs the bundled example
#   make test   installs what is missing, builds, runs the whole suite (ctest)
# Also: make bench, make soak, make test-sanitize, make fuzz [FUZZ_SECONDS=60], make format,
# make clean.

BUILD      ?= build
BENCH_BUILD ?= build-bench
SAN_BUILD  ?= build-sanitize
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_ARGS ?=

PACKAGES := g++ make cmake ninja-build libeigen3-dev libocct-data-exchange-dev libtbb-dev \
            libassimp-dev nlohmann-json3-dev catch2 libcairo2-dev pkg-config
# Headless Chromium runs the viewer page's test (web/check_view.cjs).
BROWSER_PACKAGES := chromium
BENCH_PACKAGES := libbenchmark-dev libfcl-dev libsisl-dev
# libFuzzer ships with clang's compiler-rt.
FUZZ_PACKAGES := clang-14 libclang-rt-14-dev
FUZZ_TARGETS := fuzz_json_surfaces fuzz_step_import fuzz_iges_import fuzz_scene fuzz_script

.PHONY: deps bench-deps fuzz-deps configure build test demo bench soak test-sanitize fuzz format \
        clean

# Installs only the Debian packages that are missing; never touches apt otherwise.
deps:
	@./tools/install-packages $(PACKAGES) $(BROWSER_PACKAGES)
	@./tools/install-web

bench-deps:
	@./tools/install-packages $(PACKAGES) $(BENCH_PACKAGES)

fuzz-deps:
	@./tools/install-packages $(PACKAGES) $(FUZZ_PACKAGES)

configure: deps
	@# -g1 (line tables: backtraces with file and line) compiles a third faster than -g.
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DARGIL_WERROR=ON $(CMAKE_ARGS)

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

test: build
	@cd $(BUILD) && ctest --output-on-failure --no-tests=error -j $(JOBS)

# The demo needs the argil program only, not the test suite.
demo: configure
	@cmake --build $(BUILD) -j $(JOBS) --target argil
	@./tools/demo $(BUILD)

bench: bench-deps
	@cmake -S . -B $(BENCH_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DARGIL_BUILD_TESTS=OFF \
	  -DARGIL_BUILD_BENCH=ON -DARGIL_WERROR=ON $(CMAKE_ARGS)
	@cmake --build $(BENCH_BUILD) -j $(JOBS)
	@for b in $(BENCH_BUILD)/tests/bench/bench_*; do echo "== $$b"; $$b || exit 1; done

# 1,000,000 ticks of random strokes through the full haptic tick (Release):
# no NaN, no energy or memory growth; prints the peak RSS.
SOAK_TICKS ?= 1000000
soak: bench-deps
	@cmake -S . -B $(BENCH_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DARGIL_BUILD_TESTS=OFF \
	  -DARGIL_BUILD_BENCH=ON -DARGIL_WERROR=ON $(CMAKE_ARGS)
	@cmake --build $(BENCH_BUILD) -j $(JOBS) --target argil_soak
	@$(BENCH_BUILD)/tests/soak/argil_soak $(SOAK_TICKS) 16 sphere 1

test-sanitize: deps
	@# Debug keeps assertions; -O1 keeps Eigen-heavy tests fast enough under ASan (-O2 gained
	@# a tenth in tests and lost it in the build); -g1 gives the reports file and line.
	@cmake -S . -B $(SAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" \
	  -DARGIL_SANITIZE=ON -DARGIL_WERROR=ON $(CMAKE_ARGS)
	@cmake --build $(SAN_BUILD) -j $(JOBS)
	@cd $(SAN_BUILD) && ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure --no-tests=error -j $(JOBS)

# Builds the libFuzzer targets (clang, ASan + UBSan) and runs each for FUZZ_SECONDS.
fuzz: fuzz-deps
	@CC=clang-14 CXX=clang++-14 cmake -S . -B $(FUZZ_BUILD) -G Ninja \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DARGIL_FUZZ=ON -DARGIL_BUILD_TESTS=OFF -DARGIL_WERROR=ON \
	  $(CMAKE_ARGS)
	@cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(FUZZ_TARGETS)
	@./tools/run-fuzz $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

format:
	@git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	@rm -rf $(BUILD) $(BENCH_BUILD) $(SAN_BUILD) $(FUZZ_BUILD)
