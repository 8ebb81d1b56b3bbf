# Quick start (README): `make demo` and `make test`. Both install missing Debian packages,
# configure and build (Release) first.
BUILD_DIR ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

.PHONY: all deps build demo test bench validate clean

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

# Benchmarks and long validations: run by hand, results go into issue notes.
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

clean:
	rm -rf $(BUILD_DIR)
