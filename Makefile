# Quick start (README): `make demo` and `make test`. Both install missing Debian packages,
# configure and build (Release) first.
BUILD_DIR ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

.PHONY: all deps build demo test bench validate clean check-asan fuzz fuzz-libhdf5

all: build

deps:
	@scripts/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD_DIR) -j$(JOBS)

demo: build
	@BIN=$(BUILD_DIR)/bin/wetroad OUT=$(BUILD_DIR)/demo scripts/demo.sh

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS)

# The unit and end-to-end tests under AddressSanitizer + UndefinedBehaviorSanitizer (own build
# folder; any report fails the test that triggered it). Leaks inside Open MPI's and PETSc's start-up
# are suppressed by name (tests/sanitizers/lsan.supp); the project's own are not.
ASAN_DIR ?= build-asan
# Open MPI keeps its plug-ins loaded (disable_dlclose) so that their leaks are named, and the
# slow unwinder walks through the libraries built without frame pointers.
SANITIZER_ENV = ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitizers/lsan.supp:print_suppressions=0:fast_unwind_on_malloc=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 OMPI_MCA_memory=^patcher OMPI_MCA_mca_base_component_disable_dlclose=1
check-asan: deps
	@cmake -S . -B $(ASAN_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWETROAD_SANITIZE=address,undefined >/dev/null
	@cmake --build $(ASAN_DIR) -j$(JOBS)
	@cd $(ASAN_DIR) && $(SANITIZER_ENV) ctest --output-on-failure -j$(JOBS)

# libFuzzer on every reader (tests/fuzz/): each target runs FUZZ_SECONDS from the seed corpus in
# tests/fuzz/seeds/; a crash, hang (> 10 s), sanitizer report or uncaught non-input error fails it.
FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 120
FUZZ_TARGETS = fuzz_height_map fuzz_text_grid fuzz_x3p fuzz_point_cloud fuzz_measured_csv fuzz_compound_json \
  fuzz_scene_json fuzz_checkpoint
fuzz: deps
	@scripts/install-deps.sh --fuzz
	@CC=clang CXX=clang++ cmake -S . -B $(FUZZ_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWETROAD_FUZZ=ON \
	  -DBUILD_TESTING=OFF >/dev/null
	@cmake --build $(FUZZ_DIR) -j$(JOBS) --target $(FUZZ_TARGETS)
	@for t in $(FUZZ_TARGETS); do \
	  extra=""; [ $$t = fuzz_height_map ] && extra="quarantine_size_mb=16"; \
	  FUZZ_ASAN_EXTRA=$$extra scripts/run-fuzz.sh $(FUZZ_DIR)/bin/$$t tests/fuzz/seeds/$$t $(FUZZ_DIR)/corpus/$$t \
	    $(FUZZ_SECONDS) || exit 1; \
	done

# Raw bytes as an HDF5 container: what Debian's libhdf5 itself does with corrupt files (it reads
# past its buffers on some: docs/robustness.md). Not part of make fuzz: its findings are not ours.
fuzz-libhdf5: fuzz
	@cmake --build $(FUZZ_DIR) -j$(JOBS) --target fuzz_hdf5_container
	@scripts/run-fuzz.sh $(FUZZ_DIR)/bin/fuzz_hdf5_container tests/fuzz/seeds/fuzz_hdf5_container \
	  $(FUZZ_DIR)/corpus/fuzz_hdf5_container $(FUZZ_SECONDS)

# Benchmarks and long validations: run by hand, results go into docs/performance.md and docs/validation.md.
bench: build
	$(BUILD_DIR)/bin/wetroad bench speed --sizes 300 4096 --repeat 3
	$(BUILD_DIR)/bin/wetroad bench speed --sizes 300 4096 --repeat 3 --files
	$(BUILD_DIR)/bin/wetroad bench water --size 1024
	$(BUILD_DIR)/bin/wetroad bench spectral --sizes 1024 2048
	$(BUILD_DIR)/bin/wetroad bench spectral-shear --size 512
	scripts/bench-sweep-mpi.sh $(BUILD_DIR)/bin/wetroad $(BUILD_DIR)/bench-sweep-mpi

validate: build
	$(BUILD_DIR)/bin/wetroad bench summits --realizations 100
	$(BUILD_DIR)/bin/wetroad bench coverage --seeds 10
	OMP_NUM_THREADS=1 $(BUILD_DIR)/bin/wetroad bench hertz --meshes 32 64 128
	$(BUILD_DIR)/bin/wetroad bench kappa --sizes 256 512 1024 --band 256 --seeds 4 --plot $(BUILD_DIR)/kappa.svg
	OMP_NUM_THREADS=1 mpirun --allow-run-as-root --oversubscribe -np 2 $(BUILD_DIR)/bin/wetroad bench spectral-vs-fem \
	  --plot $(BUILD_DIR)/spectral-vs-fem.svg
	OMP_NUM_THREADS=1 mpirun --allow-run-as-root --oversubscribe -np 2 $(BUILD_DIR)/bin/wetroad bench accuracy \
	  --fem-refines 1 2 3 --spectral-refines 1 2 3 4 8 --plot $(BUILD_DIR)/accuracy.svg
	$(BUILD_DIR)/bin/wetroad synth --scene default --size 32 --dx 9.375e-4 -o $(BUILD_DIR)/d32.h5 -q
	OMP_NUM_THREADS=1 mpirun --allow-run-as-root --oversubscribe -np 2 $(BUILD_DIR)/bin/wetroad bench mesh-convergence \
	  --surface $(BUILD_DIR)/d32.h5 --refines 1 2 4 8 --tol 1e-4 --json $(BUILD_DIR)/mesh-convergence.json \
	  --plot $(BUILD_DIR)/mesh-convergence.svg
	$(BUILD_DIR)/bin/wetroad bench sliding --size 1024 --band 64 --seeds 1 2 3 --pressures 1e5 3e5 \
	  --json $(BUILD_DIR)/sliding.json --plot $(BUILD_DIR)/exact-rung-mu-v.svg --plot-ratio $(BUILD_DIR)/exact-rung-ratio.svg
	$(BUILD_DIR)/bin/wetroad bench sliding-convergence --band 64 --sizes 512 1024 2048 --speeds 1e-4 1e-2 1 10 \
	  --json $(BUILD_DIR)/sliding-convergence.json --ladder-plot $(BUILD_DIR)/friction-ladder.svg \
	  --fem-json $(BUILD_DIR)/mesh-convergence.json

clean:
	rm -rf $(BUILD_DIR)
