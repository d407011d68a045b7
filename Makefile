# Tessera's two commands on a fresh Debian 12 machine: `make demo` and `make test`. Everything else is a convenience.
# Each target installs missing Debian packages first (scripts/install-deps.sh is idempotent and quiet when all is there).

PREFIX ?= /usr/local
JOBS ?= $(shell nproc)
OUT ?= out
CMAKE ?= cmake
TESSERA := build/release/apps/tessera/tessera

.PHONY: all deps build demo test lint bench asan install python clean

all: build

deps:
	@scripts/install-deps.sh

build: deps
	@$(CMAKE) --preset release >/dev/null
	@$(CMAKE) --build --preset release -j $(JOBS)

# The demo needs only the library and the command: the packages to build them, and no tests, test peers or Python
# module. The same build folder as `make test` (which turns them back on), so that neither builds the library twice.
demo:
	@scripts/install-deps.sh demo
	@$(CMAKE) --preset release -DTESSERA_BUILD_TESTS=OFF -DTESSERA_BUILD_PYTHON=OFF >/dev/null
	@$(CMAKE) --build --preset release -j $(JOBS) --target tessera
	$(TESSERA) demo -o $(OUT)
	@echo "demo pictures written to $(OUT)/ (open $(OUT)/index.html)"

# The format check, the release build's tests, then the clang sanitizer build's unit tests and fuzz runs (make asan),
# then clang-tidy's check for new findings (on the clang build's compile commands).
test: build
	scripts/check-format.sh
	ctest --preset release
	@$(MAKE) --no-print-directory asan
	scripts/check-tidy.py build/asan

# The tree formatted as .clang-format says, and no clang-tidy finding that .clang-tidy-baseline does not list.
lint: deps
	scripts/check-format.sh
	@$(CMAKE) --preset asan >/dev/null
	scripts/check-tidy.py build/asan

bench: deps
	@$(CMAKE) --preset bench >/dev/null
	@$(CMAKE) --build --preset bench -j $(JOBS)
	scripts/run-benchmarks.sh build/bench

# clang's AddressSanitizer + UBSan: builds and runs every module's unit tests, and each libFuzzer target for
# TESSERA_FUZZ_SECONDS (10) from its seeds (fuzz/CMakeLists.txt); scripts/fuzz-campaign.sh runs long campaigns.
asan: deps
	@$(CMAKE) --preset asan >/dev/null
	@$(CMAKE) --build --preset asan -j $(JOBS) --target unit_tests
	ctest --preset asan -L unit

# The Python package in the virtual environment build/venv (Debian's numpy and friends visible, nothing from PyPI),
# installed from the release build: `. build/venv/bin/activate` then `python -c "import tessera"` (docs/python.md).
python: build
	@rm -rf build/venv && /usr/bin/python3 -m venv --system-site-packages build/venv
	TESSERA_BUILD_DIR=build/release build/venv/bin/pip install --quiet --no-build-isolation --no-index ./python
	@echo "tessera installed in build/venv: . build/venv/bin/activate"

install: build
	$(CMAKE) --install build/release --prefix $(PREFIX)

clean:
	rm -rf build $(OUT)
