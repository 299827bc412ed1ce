# A thin shell over CMake. On a fresh Debian machine `make demo` and
# `make test` are all the set-up there is: both install missing packages
# first (scripts/install-deps.sh), configure, and build.
BUILD      ?= build
JOBS       ?= $(shell nproc)
CMAKE_ARGS ?=

.PHONY: all deps configure build demo test bench fuzz test-sanitize install clean format lint readme

all: build

deps:
	@bash scripts/install-deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_ARGS)

configure: deps $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# The demo needs only the library and the command, not the test suite, so a
# newcomer sees a result as soon as those are compiled.
demo: configure
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
test-sanitize: deps
	cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMPCAL_SANITIZE=ON \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DMPCAL_BUILD_BENCH=OFF $(CMAKE_ARGS)
	cmake --build build-sanitize -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --test-dir build-sanitize --output-on-failure -j $(JOBS)

# Reruns every command shown in README.md and writes what it prints today
# into the README (CI checks the same with --check).
readme: build
	python3 scripts/readme_run.py --update --build $(BUILD)

install: build
	cmake --install $(BUILD)

format:
	clang-format -i $$(git ls-files '*.h' '*.cc')

# clang-format, file sizes and clang-tidy, as CI checks them (scripts/lint.sh).
lint: configure
	bash scripts/lint.sh $(BUILD)

clean:
	rm -rf $(BUILD) build-sanitize build-fuzz
