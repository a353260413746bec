# fldsim — the two commands: `make demo` and `make test` (each installs what is missing,
# builds, then runs). `make bench` runs the benchmarks, `make validate` the long physics
# validations, `make figures` the quick study plots.
SHELL := /bin/bash
BUILD ?= build
JOBS ?= $(shell nproc)
FLDSIM = $(BUILD)/bin/fldsim

.PHONY: all deps configure build demo test bench validate figures docs format clean

all: build

deps:
	@bash tools/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release > $(BUILD).configure.log 2>&1 || (cat $(BUILD).configure.log; exit 1)

build: configure
	@cmake --build $(BUILD) -j$(JOBS)

demo: build
	@echo "== fldsim demo: examples/quickstart.yaml (64 homonuclear dicolloids, phi = 0.3, Pe = 10, FLD) =="
	$(FLDSIM) run examples/quickstart.yaml -o results/quickstart.h5 --overwrite
	@echo "== steady-state results =="
	$(FLDSIM) summary results/quickstart.h5
	@echo "Results: results/quickstart.h5  (plots: /usr/bin/python3 tools/plot_run.py results/quickstart.h5 -o results/quickstart)"

test: build
	@cd $(BUILD) && ctest --output-on-failure -j$(JOBS) --timeout 600 2>&1 | tee ctest.log; \
	  status=$${PIPESTATUS[0]}; \
	  passed=$$(grep -cE 'Test +#[0-9]+: .* +Passed +[0-9.]+ sec$$' ctest.log); \
	  failed=$$(grep -cE 'Test +#[0-9]+: .*\*\*\*(Failed|Timeout|Exception)' ctest.log); \
	  skipped=$$(grep -cE 'Test +#[0-9]+: .*Not Run' ctest.log); \
	  echo "$$passed passed, $$failed failed, $$skipped skipped"; exit $$status

bench: build
	@bash bench/run.sh $(BUILD)

# Long physics validations (validate/README.md); `make validate V="equilibrium"` runs only those named.
validate: build
	@bash validate/run.sh $(BUILD) $(V)

figures: build
	@bash examples/paper/quick/run_quick_study.sh $(BUILD)

docs: build
	@bash tools/plugin-docs.sh $(BUILD)

format:
	@clang-format -i $$(git ls-files '*.cpp' '*.hpp')

clean:
	rm -rf $(BUILD) $(BUILD).configure.log
