# strangebeta — see README.md. Every target installs missing Debian packages first.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
# ccache, where installed, serves unchanged objects again (also to a second
# clone: paths under the checkout are hashed relative to it).
LAUNCHER := $(if $(shell command -v ccache),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache,)
export CCACHE_BASEDIR := $(CURDIR)
# Seconds per input format for `make fuzz` (`make test` fuzzes each for
# SB_TEST_FUZZ_SECONDS, default 6; docs/testing.md).
FUZZ_SECONDS ?= 60

.PHONY: all setup configure build test test-sanitize fuzz run bench clean

all: build

setup:
	@bash scripts/setup.sh

configure: setup
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(LAUNCHER) $(CMAKE_FLAGS) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# The normal suite, then the sanitizer suite and bounded fuzzing.
test: build
	@bash scripts/test.sh $(BUILD)

# Unit and API tests under AddressSanitizer + UBSan (the checked build, build-sanitize/).
test-sanitize: setup
	@JOBS=$(JOBS) bash scripts/sanitize.sh

# libFuzzer harnesses, FUZZ_SECONDS per format (the same checked build, build-sanitize/).
fuzz: setup
	@JOBS=$(JOBS) bash scripts/fuzz.sh $(FUZZ_SECONDS)

run: build
	@bash scripts/run.sh $(BUILD)

bench: build
	@bash scripts/bench.sh $(BUILD)

clean:
	rm -rf $(BUILD) build-sanitize build-fuzz
