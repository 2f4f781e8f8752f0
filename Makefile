# SPDX-License-Identifier: MIT
# Two commands set everything up on a fresh Debian machine (as root):
#   make demo   installs what is missing, builds, runs the seminar-room example
#   make test   installs what is missing, builds, runs every test
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all deps configure build demo test bench clean sanitize-test fuzz

all: build

deps:
	@bash scripts/install_deps.sh

configure: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) > /dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

demo: build
	@mkdir -p $(BUILD_DIR)/demo
	$(BUILD_DIR)/bin/mirage run examples/seminar_room.yaml --json $(BUILD_DIR)/demo/report.json \
	    --csv $(BUILD_DIR)/demo/csv --plot $(BUILD_DIR)/demo/seminar_room.png

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

bench: build
	$(BUILD_DIR)/bin/mirage_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

# The test suite again in a separate AddressSanitizer + UndefinedBehaviorSanitizer build, with
# clang, so that the same build also holds the fuzzers (`make fuzz`): the library is compiled
# once for both. Line tables are the debug information the sanitizers' reports need. Four
# statistical end-to-end tests of 100-530 s each under the sanitizers (CI's time) run in the
# release suite only; their examples (acoustic_height, acoustic_height_office, acoustic_holdout)
# run here too, every variant, in cli_examples_run.
SANITIZE_SKIP = AcousticHeight.FloorEchoesPinTheHeight|AcousticHeight.ASenderOnTheRoomsSymmetryLineIsNotReadFromItsWallEchoes|AcousticHeightOffice.SecondOrderEchoesPredictedKeepTheHeightFirstOrderOnlyBiasesIt|AcousticHoldout.WithUnmodelledEchoesTheStartFollowsTheWalkerAndALostTrackStartsAgain
SANITIZE_DIR = $(BUILD_DIR)-asan
SANITIZE_FLAGS = -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only" -DMIRAGE_SANITIZE=ON \
    -DMIRAGE_BUILD_FUZZERS=ON -DMIRAGE_BUILD_BENCH=OFF
sanitize-test: deps
	@bash scripts/install_deps.sh fuzz
	@cmake -S . -B $(SANITIZE_DIR) $(SANITIZE_FLAGS) > /dev/null
	@cmake --build $(SANITIZE_DIR) -j $(JOBS)
	@cd $(SANITIZE_DIR) && ctest --output-on-failure -j $(JOBS) -E '^($(SANITIZE_SKIP))$$'

# The scenario parser and the recorded-data (CSV) readers under libFuzzer with ASan+UBSan, each
# for FUZZ_SECONDS (default 60), seeded with the examples, the bad inputs of the CLI tests and
# the example recording. Built in the sanitizer build (after `make sanitize-test` only the two
# fuzzers are left to build).
FUZZ_SECONDS ?= 60
fuzz:
	@bash scripts/install_deps.sh fuzz
	@cmake -S . -B $(SANITIZE_DIR) $(SANITIZE_FLAGS) > /dev/null
	@cmake --build $(SANITIZE_DIR) -j $(JOBS) --target scenario_fuzzer recorded_data_fuzzer
	@mkdir -p $(SANITIZE_DIR)/corpus && cp examples/*.yaml tests/cli/bad/*.yaml $(SANITIZE_DIR)/corpus/ 2>/dev/null || true
	@mkdir -p $(SANITIZE_DIR)/corpus_csv && python3 scripts/recorded_fuzz_seeds.py examples/recorded $(SANITIZE_DIR)/corpus_csv examples/recorded_acoustic tests/io/data/recorded_tdoa
	@cd $(SANITIZE_DIR) && status=0; ./bin/scenario_fuzzer -max_total_time=$(FUZZ_SECONDS) \
	    -max_len=16384 -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 corpus > fuzz.log 2>&1 \
	    || status=$$?; tail -n 8 fuzz.log; [ $$status -eq 0 ] || exit $$status; \
	    ./bin/recorded_data_fuzzer -max_total_time=$(FUZZ_SECONDS) -max_len=16384 -timeout=10 -rss_limit_mb=4096 \
	    -print_final_stats=1 corpus_csv > fuzz_csv.log 2>&1 || status=$$?; tail -n 8 fuzz_csv.log; exit $$status

clean:
	rm -rf $(BUILD_DIR) $(BUILD_DIR)-asan $(BUILD_DIR)-fuzz
