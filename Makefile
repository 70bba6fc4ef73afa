# aabench: build, test, run, bench, install.
#
#   make run     install missing Debian packages, build, run the main benchmark
#   make test    the same set-up, then every test (plain and under ASan+UBSan),
#                the test binaries in parallel (one job a core)
#   make bench   speed measurements (not tests: nothing here asserts a time)
#   make fuzz    libFuzzer on the spec parsers and image readers (needs clang)
#   make valgrind  the tests under valgrind memcheck
#   make install PREFIX=/usr/local
#
# Dependencies are found with pkg-config; scripts/install-deps.sh installs
# what is missing.  Targets that need them re-enter make after installing,
# so the flags below are computed with the packages present.

PREFIX ?= /usr/local
# V=1 shows the full commands
Q := $(if $(V),,@)
BUILD  := build
CC     := gcc
CXX    := g++

PKGS      := gsl OpenImageIO
# the peer rasterizers (algorithms/freetype.c, stb.c, cairo.c)
PKGS      += freetype2 stb cairo
TEST_PKGS := cmocka
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   = $(shell pkg-config --libs $(PKGS) 2>/dev/null)
TEST_LIBS  = $(shell pkg-config --cflags --libs $(TEST_PKGS) 2>/dev/null)

WARN     := -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wno-unknown-pragmas
HARNESS  := harness/core harness/truth harness/bench harness/cli
# -MMD -MP: each object records the headers it read (build/**/*.d)
CPPFLAGS := -MMD -MP -D_DEFAULT_SOURCE -Iharness $(addprefix -I,$(HARNESS)) -Ipatterns -Ialgorithms
CFLAGS   := -std=c11 -O2 -g $(WARN) -fopenmp -fPIC
CXXFLAGS := -std=c++17 -O2 -g -Wall -Wextra -Werror -fPIC
LDLIBS    = $(PKG_LIBS) -lstdc++ -lm -ldl -fopenmp

SAN       := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
SAN_BUILD := $(BUILD)/san

CLI_SRC  := $(wildcard harness/cli/*.c)
LIB_CSRC := $(wildcard harness/core/*.c harness/truth/*.c harness/bench/*.c) \
            $(wildcard patterns/*.c) $(wildcard algorithms/*.c)
LIB_XSRC := $(wildcard harness/core/*.cpp)
TEST_SRC := $(wildcard tests/test_*.c)
TEST_AUX := $(filter-out $(TEST_SRC) tests/bench_%.c tests/plugin_%.c,$(wildcard tests/*.c))
PLUGIN_SRC := $(wildcard tests/plugin_*.c)
BENCH_SRC := $(wildcard tests/bench_*.c)

# $(1): build folder, $(2): extra flags
define objs
$(patsubst %.c,$(1)/obj/%.o,$(LIB_CSRC)) $(patsubst %.cpp,$(1)/obj/%.o,$(LIB_XSRC))
endef

LIB      := $(BUILD)/libaabench.a
SAN_LIB  := $(SAN_BUILD)/libaabench.a
TESTS     := $(patsubst tests/%.c,$(BUILD)/tests/%,$(TEST_SRC))
PLUGINS   := $(patsubst tests/%.c,$(BUILD)/tests/%.so,$(PLUGIN_SRC))
SAN_PLUGINS := $(patsubst tests/%.c,$(SAN_BUILD)/tests/%.so,$(PLUGIN_SRC))
SAN_TESTS := $(patsubst tests/%.c,$(SAN_BUILD)/tests/%,$(TEST_SRC))
BENCHES   := $(patsubst tests/%.c,$(BUILD)/%,$(BENCH_SRC))

# keep the objects of test helpers between runs
.PRECIOUS: $(BUILD)/obj/%.o $(SAN_BUILD)/obj/%.o

# Running the tests: each binary is its own target, NAME.run (phony), which
# writes NAME.log and NAME.result beside the binary and never fails, so that
# make -j runs them side by side and every test runs; the pass's summary
# then prints the failed ones and "N passed, N failed" and fails if any did.
# The longest start first, so that they do not run on alone at the end.
SLOW_TESTS := test_cli test_truth_gauss test_tables test_peers test_oracle test_patterns
ordered = $(foreach t,$(SLOW_TESTS),$(filter $(1)/tests/$(t),$(2))) \
          $(filter-out $(addprefix $(1)/tests/,$(SLOW_TESTS)),$(2))
TEST_RUNS     := $(addsuffix .run,$(call ordered,$(BUILD),$(TESTS)))
SAN_TEST_RUNS := $(addsuffix .run,$(call ordered,$(SAN_BUILD),$(SAN_TESTS)))
# A pass runs with one job a core (TEST_JOBS), unless make was given -j.
TEST_JOBS ?= $(shell nproc 2>/dev/null || echo 2)
TEST_J     = $(if $(findstring -j,$(MAKEFLAGS)),,-j$(TEST_JOBS))

.PHONY: all deps run test check-tests check-tests-san check-gate baseline bench install clean \
        fuzz valgrind check-tests-pass check-tests-san-pass $(TEST_RUNS) $(SAN_TEST_RUNS)
.DEFAULT_GOAL := all

all: $(BUILD)/aabench $(LIB)

deps:
	@sh scripts/install-deps.sh

# ---- plain build ----
$(BUILD)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	@echo '  CC    $@'
	$(Q)$(CC) $(CPPFLAGS) $(CFLAGS) $(PKG_CFLAGS) -c $< -o $@
$(BUILD)/obj/%.o: %.cpp
	@mkdir -p $(dir $@)
	@echo '  CXX   $@'
	$(Q)$(CXX) $(CPPFLAGS) $(CXXFLAGS) $(PKG_CFLAGS) -c $< -o $@
$(LIB): $(call objs,$(BUILD))
	@rm -f $@
	@echo '  AR    $@'
	$(Q)ar rcs $@ $^
# The command exports the whole library, so plug-ins can call it.
WHOLE = -rdynamic -Wl,--whole-archive $(1) -Wl,--no-whole-archive
$(BUILD)/aabench: $(patsubst %.c,$(BUILD)/obj/%.o,$(CLI_SRC)) $(LIB)
	@echo '  LD    $@'
	$(Q)$(CC) $(CFLAGS) $(filter %.o,$^) $(call WHOLE,$(LIB)) -o $@ $(LDLIBS)
# A test links its own source and the objects only: its .d file adds the
# headers and included sources it read as prerequisites, which are no inputs.
$(BUILD)/tests/%: tests/%.c $(patsubst %.c,$(BUILD)/obj/%.o,$(TEST_AUX)) $(LIB)
	@mkdir -p $(dir $@)
	@echo '  LD    $@'
	$(Q)$(CC) $(CPPFLAGS) $(CFLAGS) -Itests $(PKG_CFLAGS) $< $(filter %.o,$^) $(call WHOLE,$(LIB)) -o $@ $(LDLIBS) $(TEST_LIBS)
$(BUILD)/tests/%.so: tests/%.c harness/aabench.h
	@mkdir -p $(dir $@)
	@echo '  LD    $@'
	$(Q)$(CC) $(CPPFLAGS) $(CFLAGS) -shared $< -o $@
$(BUILD)/bench_%: tests/bench_%.c $(LIB)
	@echo '  LD    $@'
	$(Q)$(CC) $(CPPFLAGS) $(CFLAGS) $(PKG_CFLAGS) $^ -o $@ $(LDLIBS)

# ---- sanitizer build ----
$(SAN_BUILD)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	@echo '  CC    $@'
	$(Q)$(CC) $(CPPFLAGS) $(CFLAGS) -O1 $(SAN) $(PKG_CFLAGS) -c $< -o $@
$(SAN_BUILD)/obj/%.o: %.cpp
	@mkdir -p $(dir $@)
	@echo '  CXX   $@'
	$(Q)$(CXX) $(CPPFLAGS) $(CXXFLAGS) -O1 $(SAN) $(PKG_CFLAGS) -c $< -o $@
$(SAN_LIB): $(call objs,$(SAN_BUILD))
	@rm -f $@
	@echo '  AR    $@'
	$(Q)ar rcs $@ $^
$(SAN_BUILD)/aabench: $(patsubst %.c,$(SAN_BUILD)/obj/%.o,$(CLI_SRC)) $(SAN_LIB)
	@echo '  LD    $@'
	$(Q)$(CC) $(CFLAGS) $(SAN) $(filter %.o,$^) $(call WHOLE,$(SAN_LIB)) -o $@ $(LDLIBS)
$(SAN_BUILD)/tests/%: tests/%.c $(patsubst %.c,$(SAN_BUILD)/obj/%.o,$(TEST_AUX)) $(SAN_LIB)
	@mkdir -p $(dir $@)
	@echo '  LD    $@'
	$(Q)$(CC) $(CPPFLAGS) $(CFLAGS) -O1 $(SAN) -Itests $(PKG_CFLAGS) $< $(filter %.o,$^) $(call WHOLE,$(SAN_LIB)) -o $@ $(LDLIBS) $(TEST_LIBS)
$(SAN_BUILD)/tests/%.so: tests/%.c harness/aabench.h
	@mkdir -p $(dir $@)
	@echo '  LD    $@'
	$(Q)$(CC) $(CPPFLAGS) $(CFLAGS) -O1 $(SAN) -shared $< -o $@

# ---- fuzzing (libFuzzer; clang, not part of `make test`) ----
# The library is built again with clang into build/fuzz, instrumented for
# the fuzzer and ASan+UBSan, with LLVM's OpenMP (Debian libomp-dev).
FUZZ_BUILD   := $(BUILD)/fuzz
FUZZ_SECONDS ?= 60
FUZZ_FLAGS   := -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -g -O1
FUZZ_TARGETS := $(FUZZ_BUILD)/fuzz_spec $(FUZZ_BUILD)/fuzz_image
$(FUZZ_BUILD)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	@echo '  CLANG $@'
	$(Q)clang $(CPPFLAGS) -std=c11 $(WARN) -Wno-pass-failed -fPIC -fopenmp $(FUZZ_FLAGS) $(PKG_CFLAGS) -c $< -o $@
$(FUZZ_BUILD)/obj/%.o: %.cpp
	@mkdir -p $(dir $@)
	@echo '  CLANG $@'
	$(Q)clang++ $(CPPFLAGS) -std=c++17 -Wall -Wextra -Werror -fPIC $(FUZZ_FLAGS) $(PKG_CFLAGS) -c $< -o $@
$(FUZZ_BUILD)/libaabench.a: $(call objs,$(FUZZ_BUILD))
	@rm -f $@
	@echo '  AR    $@'
	$(Q)ar rcs $@ $^
$(FUZZ_BUILD)/fuzz_%: tests/fuzz/fuzz_%.c $(FUZZ_BUILD)/libaabench.a
	@echo '  LD    $@'
	$(Q)clang++ $(CPPFLAGS) -x c -std=c11 $(WARN) -fsanitize=fuzzer,address,undefined -g -O1 $< -x none \
	  $(FUZZ_BUILD)/libaabench.a -o $@ $(PKG_LIBS) -lm -ldl -fopenmp
fuzz:
	@command -v clang >/dev/null 2>&1 && test -e /usr/lib/llvm-14/lib/libomp.so || { echo "make fuzz needs clang and libomp-dev: apt-get install clang libomp-dev" >&2; exit 2; }
	@$(MAKE) --no-print-directory $(FUZZ_TARGETS)
	@for t in spec image; do \
	  mkdir -p $(FUZZ_BUILD)/corpus-$$t $(FUZZ_BUILD)/crash-$$t; \
	  echo "fuzz_$$t: $(FUZZ_SECONDS) s"; \
	  $(FUZZ_BUILD)/fuzz_$$t -max_total_time=$(FUZZ_SECONDS) -max_len=4096 -timeout=10 \
	    -artifact_prefix=$(FUZZ_BUILD)/crash-$$t/ -print_final_stats=1 \
	    $(FUZZ_BUILD)/corpus-$$t tests/fuzz/corpus/$$t 2>&1 | \
	    grep -E '^(#[0-9]+ +DONE|stat::number_of_executed_units|stat::peak_rss|==[0-9]+==ERROR|SUMMARY)' ; \
	  if ls $(FUZZ_BUILD)/crash-$$t/* >/dev/null 2>&1; then \
	    echo "fuzz_$$t found crashes: $(FUZZ_BUILD)/crash-$$t/ (add them to tests/fuzz/regress/$$t/)"; exit 1; fi; \
	done

# ---- valgrind (memcheck) over the plain test binaries ----
# tests/valgrind/hwy_timer.c explains the preloaded library.
$(BUILD)/valgrind/hwy_timer.so: tests/valgrind/hwy_timer.c
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CFLAGS) -shared $< -o $@
valgrind: $(BUILD)/aabench $(TESTS) $(PLUGINS) $(BUILD)/valgrind/hwy_timer.so
	@command -v valgrind >/dev/null 2>&1 || { echo "make valgrind needs valgrind: apt-get install valgrind" >&2; exit 2; }
	@LD_PRELOAD=$(CURDIR)/$(BUILD)/valgrind/hwy_timer.so AABENCH_VALGRIND=1 \
	  sh scripts/run-tests.sh $(BUILD) $(TESTS)

# ---- the two set-up commands ----
run: deps
	@$(MAKE) --no-print-directory all
	@sh scripts/run.sh

test: deps
	@$(MAKE) --no-print-directory check-tests
	@$(MAKE) --no-print-directory check-tests-san
	@$(MAKE) --no-print-directory check-gate

# The regression gate: the quick suite against results/baseline.csv.
check-gate: $(BUILD)/aabench
	$(BUILD)/aabench check --baseline results/baseline.csv

# Remake the baseline from the quick suite (commit the result).
baseline: $(BUILD)/aabench
	$(BUILD)/aabench run --suite quick --reps 3 --no-images --no-plots -q --out $(BUILD)/baseline-run
	cp $(BUILD)/baseline-run/results.csv results/baseline.csv

check-tests:
	@$(MAKE) --no-print-directory $(TEST_J) check-tests-pass

check-tests-pass: $(TEST_RUNS)
	@sh scripts/run-tests.sh summary $(TESTS)

$(TEST_RUNS): %.run: % $(BUILD)/aabench $(PLUGINS)
	@sh scripts/run-tests.sh one $(BUILD) $*

check-tests-san:
	@$(MAKE) --no-print-directory $(TEST_J) check-tests-san-pass

check-tests-san-pass: $(SAN_TEST_RUNS)
	@sh scripts/run-tests.sh summary $(SAN_TESTS)

$(SAN_TEST_RUNS): %.run: % $(SAN_BUILD)/aabench $(SAN_PLUGINS)
	@ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  sh scripts/run-tests.sh one $(SAN_BUILD) $*

bench: deps
	@$(MAKE) --no-print-directory $(BUILD)/aabench $(BENCHES)
	@sh scripts/bench.sh $(BUILD)

# The seed papers' figures remade into results/figures, then the gallery
# checked in a headless browser when chromium is present.
.PHONY: figures
figures: $(BUILD)/aabench
	$(BUILD)/aabench figures
	@if command -v chromium >/dev/null 2>&1; then sh scripts/check-gallery.sh results/figures; \
	else echo "figures: chromium missing, gallery not checked (apt-get install chromium)"; fi

install: all
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib $(DESTDIR)$(PREFIX)/include
	install -m 755 $(BUILD)/aabench $(DESTDIR)$(PREFIX)/bin/
	install -m 644 $(LIB) $(DESTDIR)$(PREFIX)/lib/
	install -m 644 harness/aabench.h $(DESTDIR)$(PREFIX)/include/

clean:
	rm -rf $(BUILD)

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
