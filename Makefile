# The two commands of the README:
#   make demo   solve the shipped default scene (the main job)
#   make test   build everything and run the whole test suite
# Both install missing Debian packages first and build Release with CMake.
MAKEFLAGS += --no-print-directory
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

.PHONY: demo test deps deps-mpi configure build build-mpi sanitize test-sanitize test-fuzz studies bench friction-map clean

deps:
	@bash scripts/install-deps.sh

deps-mpi:
	@bash scripts/install-deps.sh --mpi

configure: deps
	@cmake --preset release >/dev/null

build: configure
	@cmake --build --preset release -j $(JOBS)

# The demo builds the command line only (the suite, studies and Python package are `make test`'s).
demo: configure
	@cmake --build --preset release -j $(JOBS) --target rhabel_cli
	@bash scripts/demo.sh

# make test also builds `rhabel sweep` with MPI (RHABEL_WITH_MPI) and runs it under mpirun
# (cli.mpi_sweep); the program still runs without mpirun.
build-mpi: deps-mpi
	@cmake --preset release -DRHABEL_WITH_MPI=ON >/dev/null
	@cmake --build --preset release -j $(JOBS)

test: build-mpi
	@ctest --preset release -j $(JOBS)

# Friction against sliding speed for the shipped master curve: out/friction_speed.{csv,png}.
friction-map: build
	@mkdir -p out
	@build/bin/rhabel sweep examples/friction_speed_sweep.json --out out/friction_speed.csv --quiet
	@/usr/bin/python3 scripts/plot_sweep.py out/friction_speed.csv out/friction_speed.png

# Address + undefined-behaviour sanitizers over the whole suite (CI runs this too; the header-only
# modules' tests with ASan alone, tests/CMakeLists.txt).
test-sanitize: deps
	@cmake --preset sanitize >/dev/null
	@cmake --build --preset sanitize -j $(JOBS)
	@ctest --preset sanitize -j $(JOBS)

# The libFuzzer targets (tests/fuzz/README.md): the scene parser and the solve entry (60 s), the
# master-curve reader and the sweep schema (30 s each); clang, only the sources they need, each on
# its committed corpus (CI runs this too).
test-fuzz: deps
	@cmake --preset fuzz >/dev/null
	@cmake --build --preset fuzz -j $(JOBS)
	@bash tests/fuzz/run.sh build-fuzz/bin/fuzz_scene
	@bash tests/fuzz/run.sh build-fuzz/bin/fuzz_master_curve 30
	@bash tests/fuzz/run.sh build-fuzz/bin/fuzz_sweep 30

studies: build
	@bash scripts/run-studies.sh

clean:
	rm -rf build build-*
