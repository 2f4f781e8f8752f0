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

# The test suite again in a separate AddressSanitizer + UndefinedBehaviorSanitizer build.
sanitize-test: deps
	@cmake -S . -B $(BUILD_DIR)-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMIRAGE_SANITIZE=ON -DMIRAGE_BUILD_BENCH=OFF > /dev/null
	@cmake --build $(BUILD_DIR)-asan -j $(JOBS)
	@cd $(BUILD_DIR)-asan && ctest --output-on-failure -j $(JOBS)

# The scenario parser and the recorded-data (CSV) readers under libFuzzer with ASan+UBSan, each
# for FUZZ_SECONDS (default 60), seeded with the examples, the bad inputs of the CLI tests and
# the example recording.
FUZZ_SECONDS ?= 60
fuzz:
	@bash scripts/install_deps.sh fuzz
	@CXX=clang++ cmake -S . -B $(BUILD_DIR)-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMIRAGE_SANITIZE=ON \
	    -DMIRAGE_BUILD_FUZZERS=ON -DMIRAGE_BUILD_TESTS=OFF -DMIRAGE_BUILD_BENCH=OFF > /dev/null
	@cmake --build $(BUILD_DIR)-fuzz -j $(JOBS) --target scenario_fuzzer recorded_data_fuzzer
	@mkdir -p $(BUILD_DIR)-fuzz/corpus && cp examples/*.yaml tests/cli/bad/*.yaml $(BUILD_DIR)-fuzz/corpus/ 2>/dev/null || true
	@mkdir -p $(BUILD_DIR)-fuzz/corpus_csv && python3 scripts/recorded_fuzz_seeds.py examples/recorded $(BUILD_DIR)-fuzz/corpus_csv examples/recorded_acoustic tests/io/data/recorded_tdoa
	@cd $(BUILD_DIR)-fuzz && status=0; ./bin/scenario_fuzzer -max_total_time=$(FUZZ_SECONDS) \
	    -max_len=16384 -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 corpus > fuzz.log 2>&1 \
	    || status=$$?; tail -n 8 fuzz.log; [ $$status -eq 0 ] || exit $$status; \
	    ./bin/recorded_data_fuzzer -max_total_time=$(FUZZ_SECONDS) -max_len=16384 -timeout=10 -rss_limit_mb=4096 \
	    -print_final_stats=1 corpus_csv > fuzz_csv.log 2>&1 || status=$$?; tail -n 8 fuzz_csv.log; exit $$status

clean:
	rm -rf $(BUILD_DIR) $(BUILD_DIR)-asan $(BUILD_DIR)-fuzz
