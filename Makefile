# The two commands of the README:
#   make demo   solve the shipped default scene (the main job)
#   make test   build everything and run the whole test suite
# Both install missing Debian packages first and build Release with CMake.
MAKEFLAGS += --no-print-directory
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

.PHONY: demo test deps build sanitize test-sanitize studies bench clean

deps:
	@bash scripts/install-deps.sh

build: deps
	@cmake --preset release >/dev/null
	@cmake --build --preset release -j $(JOBS)

demo: build
	@bash scripts/demo.sh

test: build
	@ctest --preset release -j $(JOBS)

# Address + undefined-behaviour sanitizers over the whole suite (CI runs this too).
test-sanitize: deps
	@cmake --preset sanitize >/dev/null
	@cmake --build --preset sanitize -j $(JOBS)
	@ctest --preset sanitize -j $(JOBS)

studies: build
	@bash scripts/run-studies.sh

clean:
	rm -rf build build-*
