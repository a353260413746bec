# fldsim — the two commands: `make demo` and `make test` (each installs what is missing,
# builds, then runs). `make bench` runs the benchmarks, `make validate` the long physics
# validations, `make figures` the quick study plots.
SHELL := /bin/bash
BUILD ?= build
JOBS ?= $(shell nproc)
FLDSIM = $(BUILD)/bin/fldsim
# The pass and fail counts of a `ctest ... | tee ctest.log` (shell variables passed, failed).
CTEST_COUNTS = passed=$$(grep -cE 'Test +\#[0-9]+: .* +Passed +[0-9.]+ sec$$' ctest.log); \
  failed=$$(grep -cE 'Test +\#[0-9]+: .*\*\*\*(Failed|Timeout|Exception)' ctest.log);

.PHONY: all deps configure build demo test bench validate figures docs format clean sanitize sanitize-fuzz

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
	  status=$${PIPESTATUS[0]}; $(CTEST_COUNTS) \
	  skipped=$$(grep -cE 'Test +#[0-9]+: .*Not Run' ctest.log); \
	  echo "$$passed passed, $$failed failed, $$skipped skipped"; exit $$status

# The whole suite and the robustness fuzzer under AddressSanitizer + UndefinedBehaviorSanitizer,
# in its own build folder (RelWithDebInfo: findings come with file:line). allocator_may_return_null:
# a huge malloc returns NULL as without ASan (HDF5 then reports a corrupt file) instead of aborting. FUZZ_ITERATIONS sets
# the fuzzer's budget; SANITIZE_TESTS a ctest -R filter (default: everything). Leaks inside HDF5 on
# corrupt input are suppressed (tools/sanitize/lsan.supp says which and why).
SANITIZE_BUILD ?= build-sanitize
FUZZ_ITERATIONS ?= 2000
SANITIZE_TESTS ?= .
SANITIZER_ENV = ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:detect_odr_violation=0:allocator_may_return_null=1 \
  LSAN_OPTIONS=suppressions=$(CURDIR)/tools/sanitize/lsan.supp UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
sanitize: deps
	@cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFLDSIM_SANITIZE=ON \
	  -DFLDSIM_BUILD_BENCH=OFF > $(SANITIZE_BUILD).configure.log 2>&1 || (cat $(SANITIZE_BUILD).configure.log; exit 1)
	@cmake --build $(SANITIZE_BUILD) -j$(JOBS)
	@cd $(SANITIZE_BUILD) && FLDSIM_FUZZ_ITERATIONS=$(FUZZ_ITERATIONS) $(SANITIZER_ENV) \
	  ctest --output-on-failure -j$(JOBS) --timeout 1800 -R '$(SANITIZE_TESTS)' 2>&1 | tee ctest.log; \
	  status=$${PIPESTATUS[0]}; $(CTEST_COUNTS) \
	  echo "sanitize: $$passed passed, $$failed failed"; exit $$status

# CI's sanitizer stage (.ci/run, after `make test`): the mutation fuzzer (ctest label fuzz) under
# ASan + UBSan at its default budget (300 experiment and 150 file mutants). Only what it runs is
# built (the core, the fldsim program, the plugins its seeds name: tests/robustness/CMakeLists.txt),
# at -O0 without debug info: compiling is the stage's cost (at -O1 with every plugin it added 431 s
# to CI: 1307 s against 876 s), -O0 compiles about a fifth faster and the small mutant scenes run as
# fast (27 s).
# `make sanitize` (everything, RelWithDebInfo) would not fit CI's 20 minutes. A finding is replayed
# with file:line in `make sanitize SANITIZE_TESTS=Fuzz`.
SANITIZE_FUZZ_BUILD ?= build-sanitize-fuzz
sanitize-fuzz: deps
	@cmake -S . -B $(SANITIZE_FUZZ_BUILD) -DCMAKE_BUILD_TYPE=Release -DFLDSIM_SANITIZE=ON -DFLDSIM_BUILD_BENCH=OFF \
	  -DCMAKE_CXX_FLAGS_RELEASE="-O0 -DNDEBUG" -DCMAKE_C_FLAGS_RELEASE="-O0 -DNDEBUG" \
	  > $(SANITIZE_FUZZ_BUILD).configure.log 2>&1 || (cat $(SANITIZE_FUZZ_BUILD).configure.log; exit 1)
	@cmake --build $(SANITIZE_FUZZ_BUILD) -j$(JOBS) --target fuzz_tests
	@cd $(SANITIZE_FUZZ_BUILD) && $(SANITIZER_ENV) ctest --output-on-failure -j$(JOBS) --timeout 600 -L fuzz 2>&1 | tee ctest.log; \
	  status=$${PIPESTATUS[0]}; $(CTEST_COUNTS) \
	  echo "sanitize-fuzz: $$passed passed, $$failed failed"; exit $$status

bench: build
	@bash bench/run.sh $(BUILD)

# Long physics validations (validate/README.md); `make validate V="equilibrium"` runs only those named.
# Their cases run JOBS at a time (one thread each); run again after an interruption to resume.
validate: build
	@JOBS=$(JOBS) bash validate/run.sh $(BUILD) $(V)

# The quick study (examples/paper/quick-sweep.yaml): a sweep on the local cores (finished points
# are skipped, interrupted ones resumed), then the paper's figures from its result files.
figures: build
	$(FLDSIM) sweep examples/paper/quick-sweep.yaml
	/usr/bin/python3 tools/plot_study.py results/quick-study/*.h5 -o results/quick-study/figures --table

docs: build
	@bash tools/plugin-docs.sh $(BUILD)

format:
	@clang-format -i $$(git ls-files '*.cpp' '*.hpp')

clean:
	rm -rf $(BUILD) $(BUILD).configure.log $(SANITIZE_BUILD) $(SANITIZE_BUILD).configure.log
