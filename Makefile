# A thin shell over CMake. On a fresh Debian machine `make demo` and
# `make test` are all the set-up there is: both install missing packages
# first (scripts/install-deps.sh: `make demo` only what the library and the
# command need), configure, and build.
BUILD         ?= build
BUILD_PACKAGE ?= build-package
JOBS          ?= $(shell nproc)
CMAKE_ARGS    ?=

WITH_TESTS    = -DMPCAL_BUILD_TESTS=ON -DMPCAL_BUILD_BENCH=ON -DMPCAL_BUILD_EXAMPLES=ON
WITHOUT_TESTS = -DMPCAL_BUILD_TESTS=OFF -DMPCAL_BUILD_BENCH=OFF -DMPCAL_BUILD_EXAMPLES=OFF

.PHONY: all deps deps-demo deps-package configure configure-demo build demo test bench fuzz \
	test-sanitize install package clean format lint readme

all: build

deps:
	@bash scripts/install-deps.sh all

deps-demo:
	@bash scripts/install-deps.sh demo

deps-package:
	@bash scripts/install-deps.sh package

# A tree configured by `make demo` (without the tests, whose packages it does
# not install) gets them turned on; any other is configured once, and CMake
# reconfigures itself when a CMakeLists.txt changes.
configure: deps
	@if [ ! -f $(BUILD)/CMakeCache.txt ] || \
	    grep -q '^MPCAL_BUILD_TESTS:BOOL=OFF$$' $(BUILD)/CMakeCache.txt; then \
	  echo cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(WITH_TESTS) $(CMAKE_ARGS); \
	  cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(WITH_TESTS) $(CMAKE_ARGS); \
	fi

# A fresh tree for the demo leaves out the tests, benches and examples, so
# that GoogleTest and the benchmark library need not be installed.
configure-demo: deps-demo
	@if [ ! -f $(BUILD)/CMakeCache.txt ]; then \
	  echo cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(WITHOUT_TESTS) $(CMAKE_ARGS); \
	  cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(WITHOUT_TESTS) $(CMAKE_ARGS); \
	fi

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# The demo needs only the library and the command, not the test suite, so a
# newcomer sees a result as soon as those are compiled.
demo: configure-demo
	cmake --build $(BUILD) -j $(JOBS) --target mpcal_cli
	$(BUILD)/mpcal demo

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

bench: build
	bash bench/run.sh $(BUILD)

# libFuzzer targets for the readers, each for FUZZ_SECONDS (default 60).
FUZZ_SECONDS ?= 60
fuzz: deps
	bash scripts/fuzz.sh $(FUZZ_SECONDS)

# The whole suite under AddressSanitizer + UndefinedBehaviorSanitizer, at
# -O1 -g1 (line tables only): compiles in a third of the time of -O2 -g under
# the sanitizers (gyro_solve.cc: 45 s against 126 s) and still names the line.
# Left out: the report pages drawn in a browser and the Debian package, whose
# checks are of a page and a package, not of mpcal's memory (the commands
# they run are run by the cli tests too).
test-sanitize: deps
	cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMPCAL_SANITIZE=ON \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DMPCAL_BUILD_BENCH=OFF $(CMAKE_ARGS)
	cmake --build build-sanitize -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --test-dir build-sanitize --output-on-failure -j $(JOBS) --label-exclude 'browser|package'

# Reruns every command shown in README.md and writes what it prints today
# into the README (CI checks the same with --check).
readme: build
	python3 scripts/readme_run.py --update --build $(BUILD)

install: build
	cmake --install $(BUILD)

# A Debian package, build-package/mpcal_<version>_<arch>.deb, of what
# `make install` installs, built apart (installed under /usr, no tests) by
# CPack (cmake/MpcalPackage.cmake); `sudo apt install ./build-package/mpcal_*.deb`.
package: deps-package
	cmake -S . -B $(BUILD_PACKAGE) -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
	  $(WITHOUT_TESTS) $(CMAKE_ARGS)
	cmake --build $(BUILD_PACKAGE) -j $(JOBS) --target package

format:
	clang-format -i $$(git ls-files '*.h' '*.cc')

# clang-format, file sizes and clang-tidy, as CI checks them (scripts/lint.sh).
lint: configure
	bash scripts/lint.sh $(BUILD)

clean:
	rm -rf $(BUILD) $(BUILD_PACKAGE) build-sanitize build-fuzz
