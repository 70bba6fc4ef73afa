# aabench: build, test, run, bench, install.
#
#   make run     install missing Debian packages, build, run the main benchmark
#   make check   the quick checks: the quick tier of the tests (plain build,
#                in parallel) and no link-level cycle between files
#   make test    the same set-up as run, then every test (plain and under
#                ASan+UBSan) and the regression gate: what CI runs
#   make bench   speed measurements (not tests: nothing here asserts a time)
#   make fuzz    libFuzzer on the spec parsers, image, cache, CSV and SVG readers, the stroker (needs clang)
#   make valgrind  the tests under valgrind memcheck
#   make install PREFIX=/usr/local
#
# Dependencies are found with pkg-config; scripts/install-deps.sh installs
# what is missing.  Targets that need them re-enter make after installing,
# so the flags below are computed with the packages present.  Each is
# computed once, where first used (VAR = $(eval VAR := ...)$(VAR)): as a
# plain recursive variable it ran pkg-config again in every compile's and
# link's command, 756 times in `make test`'s 422 commands, 5 now (`make -n
# -B check-tests-both`: 8.1 s of CPU, 0.2 s computed once), for the same
# flags.

PREFIX ?= /usr/local
# V=1 shows the full commands
Q := $(if $(V),,@)
BUILD  := build
CC     := gcc
CXX    := g++

PKGS      := gsl
# the peer rasterizers (algorithms/freetype.c, stb.c, cairo.c, agg.cpp)
PKGS      += freetype2 stb cairo libagg
# run manifests (harness/bench/shard.c)
PKGS      += libcjson
# the patterns svg (patterns/svgfile.c: libxml2) and text (patterns/text.c:
# FreeType and HarfBuzz)
PKGS      += libxml-2.0 harfbuzz
# .png files (harness/core/image_png.c): libpng, not OpenImageIO's module
PKGS      += libpng
TEST_PKGS := cmocka
PKG_CFLAGS = $(eval PKG_CFLAGS := $(shell pkg-config --cflags $(PKGS) 2>/dev/null))$(PKG_CFLAGS)
PKG_LIBS   = $(eval PKG_LIBS := $(shell pkg-config --libs $(PKGS) 2>/dev/null))$(PKG_LIBS)
# OpenImageIO is linked into a module of its own, aabench-oiio.so
# (harness/core/oiio.cpp), which the library loads with dlopen when an image
# file first needs it (harness/core/oiio.h): the command and the tests do
# not link it, and start without loading its ~250 libraries.
OIIO_CFLAGS = $(eval OIIO_CFLAGS := $(shell pkg-config --cflags OpenImageIO 2>/dev/null))$(OIIO_CFLAGS)
OIIO_LIBS   = $(eval OIIO_LIBS := $(shell pkg-config --libs OpenImageIO 2>/dev/null))$(OIIO_LIBS)
# where `make install` puts the module; compiled into image.c
OIIO_DIR   := $(PREFIX)/lib/aabench
TEST_LIBS  = $(eval TEST_LIBS := $(shell pkg-config --cflags --libs $(TEST_PKGS) 2>/dev/null))$(TEST_LIBS)

WARN     := -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes -Wno-unknown-pragmas
HARNESS  := harness/core harness/truth harness/bench harness/cli
# -MMD -MP: each object records the headers it read (build/**/*.d)
CPPFLAGS := -MMD -MP -D_DEFAULT_SOURCE -Iharness $(addprefix -I,$(HARNESS)) -Ipatterns -Ialgorithms
# no path of this tree in the objects (debug information, __FILE__): the
# program finds its data at run time (harness/core/paths.c)
CPPFLAGS += -ffile-prefix-map=$(CURDIR)=.
# -fno-semantic-interposition: the library's code is built -fPIC (for the
# tests' shared library and plug-ins' use of it), which otherwise lets a
# call from one of its functions to another global one go through the PLT
# and never be inlined, in case another module replaced it; none does.
# Inlined, the reference's integrand (truth.c) takes 15-25% less time, to
# the same bits.
# -g1: line tables only (file, line and function: a profile's and a
# stack's), as in the sanitizer build and the tests' own code; the locals'
# descriptions of -g took 12-20% of each compile (truth.c 3.5 s of CPU
# instead of 4.1, svgfile.c 3.1 instead of 3.6, harness/core/oiio.cpp 4.8
# instead of 5.9, agg.cpp 2.1 instead of 2.7).
CFLAGS   := -std=c11 -O2 -g1 -fno-semantic-interposition $(WARN) -fopenmp -fPIC
CXXFLAGS := -std=c++17 -O2 -g1 -fno-semantic-interposition -Wall -Wextra -Werror -fPIC
# -lstdc++: the AGG peer (algorithms/agg.cpp) is C++ inside the library
LDLIBS    = $(PKG_LIBS) -lstdc++ -lm -ldl -fopenmp

# -g1: line tables, all a report's stack needs (file, line, function), and
# about an eighth less compile time than -g for the sanitizer build
SAN       := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all -g1
SAN_BUILD := $(BUILD)/san

# Each build states its compilers and flags, BUILD_CC, _CXX, _CFLAGS (C),
# _CXXFLAGS (C++), _ALGO_CXXFLAGS (the C++ methods) and _TEST_CFLAGS (what a
# test program adds); compile_rules below makes its rules from them.
PLAIN_CC            := $(CC)
PLAIN_CXX           := $(CXX)
PLAIN_CFLAGS        := $(CFLAGS)
PLAIN_CXXFLAGS      := $(CXXFLAGS)
PLAIN_ALGO_CXXFLAGS  = $(ALGO_CXXFLAGS)
# a test's own code with line tables only (enough for a failure's stack),
# at -O1: the library it tests is built -O2 above (and the helpers'
# objects, tests/support.c and the others, with it); a test's own code is
# set-up and checks, whose time did not change at -O1 (test_gradient,
# test_cubic, test_oracle), and the 77 plain test programs compile in 36 s
# of CPU instead of 44
PLAIN_TEST_CFLAGS   := -O1 -g1
SAN_CC              := $(CC)
SAN_CXX             := $(CXX)
SAN_CFLAGS          := $(CFLAGS) -O1 $(SAN)
SAN_CXXFLAGS        := $(CXXFLAGS) -O1 $(SAN)
SAN_ALGO_CXXFLAGS    = $(ALGO_CXXFLAGS) -O1 $(SAN)
# AA_SANITIZED: a test may run a declared subset under the sanitizers
# where its plain run repeats the same code paths (tests/README.md, "Tiers")
SAN_TEST_CFLAGS     := -DAA_SANITIZED

CLI_SRC  := $(wildcard harness/cli/*.c)
LIB_CSRC := $(wildcard harness/core/*.c harness/truth/*.c harness/bench/*.c) \
            $(wildcard patterns/*.c) $(wildcard algorithms/*.c)
# The longest compiles first: make -j starts the objects in this order, and
# algorithms/analytic.c (47 s of CPU in the plain build, more than any three
# others together) started where the wildcard put it, about a third of the
# way in, and went on alone on one core after the rest were done.  Started
# first, the other objects fill the other core meanwhile.  harness/truth/
# truth.c is the sanitizer build's longest (6.6 s).
SLOW_CSRC := algorithms/analytic.c harness/truth/truth.c
LIB_CSRC := $(foreach f,$(SLOW_CSRC),$(filter $(f),$(LIB_CSRC))) $(filter-out $(SLOW_CSRC),$(LIB_CSRC))
# C++ methods (agg.cpp), linked into the library; no exception leaves them.
# C++20: AGG shifts negative covers left, which C++17 leaves undefined and
# C++20 defines (two's complement).
LIB_CXXSRC := $(wildcard algorithms/*.cpp)
ALGO_CXXFLAGS = $(CXXFLAGS) -std=c++20 -fopenmp
OIIO_SRC := harness/core/oiio.cpp
TEST_SRC := $(wildcard tests/test_*.c)
TEST_AUX := $(filter-out $(TEST_SRC) tests/bench_%.c tests/plugin_%.c,$(wildcard tests/*.c))
PLUGIN_SRC := $(wildcard tests/plugin_*.c)
BENCH_SRC := $(wildcard tests/bench_*.c)

# The library's objects in build folder $(1)
define objs
$(patsubst %.c,$(1)/obj/%.o,$(LIB_CSRC)) $(patsubst %.cpp,$(1)/obj/%.o,$(LIB_CXXSRC))
endef

LIB      := $(BUILD)/libaabench.a
SAN_LIB  := $(SAN_BUILD)/libaabench.a
# The tests link the library's objects as one shared library beside the
# build's libaabench.a, found at run time through the tests' rpath
# $ORIGIN/.. (they are in BUILD/tests/).
TEST_SO     := $(BUILD)/libaabench-test.so
SAN_TEST_SO := $(SAN_BUILD)/libaabench-test.so
OIIO_SO     := $(BUILD)/aabench-oiio.so
SAN_OIIO_SO := $(SAN_BUILD)/aabench-oiio.so
PLUGINS   := $(patsubst tests/%.c,$(BUILD)/tests/%.so,$(PLUGIN_SRC))
SAN_PLUGINS := $(patsubst tests/%.c,$(SAN_BUILD)/tests/%.so,$(PLUGIN_SRC))
BENCHES   := $(patsubst tests/%.c,$(BUILD)/%,$(BENCH_SRC))

# Two tiers of tests.  A test file of the full tier, the slow and
# exhaustive ones, says so in a line of its own near its top:
#     /* tier: full */
# `make check` runs the others (the quick tier), in the plain build;
# `make test` runs every test in both builds.
FULL_SRC  := $(shell grep -l '^/\* tier: full \*/' $(TEST_SRC) /dev/null)
QUICK_SRC := $(filter-out $(FULL_SRC),$(TEST_SRC))
tests_in   = $(patsubst tests/%.c,$(1)/tests/%,$(2))
TESTS       := $(call tests_in,$(BUILD),$(FULL_SRC) $(QUICK_SRC))
QUICK_TESTS := $(call tests_in,$(BUILD),$(QUICK_SRC))
SAN_TESTS   := $(call tests_in,$(SAN_BUILD),$(FULL_SRC) $(QUICK_SRC))
# A pass starts its tests in the order of their last run's times, the
# longest first, so that none runs on alone at the end; those not run yet
# (a clean build) first of all, the full tier's (the longest as a rule)
# before the others, of both builds (scripts/run-tests.sh order).
runs_in_order = $(addsuffix .run,$(shell sh scripts/run-tests.sh order $(1)))

# keep the objects of test helpers between runs
.PRECIOUS: $(BUILD)/obj/%.o $(SAN_BUILD)/obj/%.o

# Running the tests: each binary is its own target, NAME.run (phony), which
# writes NAME.log and NAME.result beside the binary and never fails, so that
# make -j runs them side by side and every test runs; the pass's summary
# then prints the failed ones and "N passed, N failed" and fails if any did.
TEST_RUNS       := $(addsuffix .run,$(TESTS))
SAN_TEST_RUNS   := $(addsuffix .run,$(SAN_TESTS))
# A pass runs with one job a core and one more (TEST_JOBS: many tests wait on
# the command they start), unless make was given -j.
TEST_JOBS ?= $(shell echo $$(( $$(nproc 2>/dev/null || echo 1) + 1 )))
TEST_J     = $(if $(findstring -j,$(MAKEFLAGS)),,-j$(TEST_JOBS))

.PHONY: all deps deps-test run test check check-tests check-tests-quick check-tests-san check-gate baseline \
        bench install clean fuzz valgrind FORCE check-tests-pass check-tests-quick-pass \
        check-tests-san-pass check-tests-both $(TEST_RUNS) $(SAN_TEST_RUNS)
.DEFAULT_GOAL := all

all: $(BUILD)/aabench $(LIB) $(OIIO_SO)

# deps: what building and `make run` need; deps-test: that and the locale
# the tests run under (de_DE.UTF-8)
deps:
	@sh scripts/install-deps.sh

deps-test:
	@sh scripts/install-deps.sh --locale

# ---- the builds: plain ($(BUILD)), sanitizer ($(SAN_BUILD)), fuzz ----
# $(call compile_rules,FOLDER,BUILD): the rules that compile the objects
# of build folder FOLDER with BUILD's compilers and flags (see PLAIN_CC).
define compile_rules
$(1)/obj/%.o: %.c
	@mkdir -p $$(dir $$@)
	@echo '  CC    $$@'
	$$(Q)$$($(2)_CC) $$(CPPFLAGS) $$($(2)_CFLAGS) $$(PKG_CFLAGS) -c $$< -o $$@
$(1)/obj/%.o: %.cpp
	@mkdir -p $$(dir $$@)
	@echo '  CXX   $$@'
	$$(Q)$$($(2)_CXX) $$(CPPFLAGS) $$($(2)_CXXFLAGS) $$(OIIO_CFLAGS) -c $$< -o $$@
$(1)/obj/algorithms/%.o: algorithms/%.cpp
	@mkdir -p $$(dir $$@)
	@echo '  CXX   $$@'
	$$(Q)$$($(2)_CXX) $$(CPPFLAGS) $$($(2)_ALGO_CXXFLAGS) $$(PKG_CFLAGS) -c $$< -o $$@
endef

# -z defs (the module and the tests' library): they need no symbol of the
# program that loads them.  The tests' library is the library's objects
# (the same as in libaabench.a, all built -fPIC); a plug-in a test loads
# resolves the library's functions in it, as it does in the command.  Its
# soname is what a test records, so each build's tests find their own
# through the rpath.
TEST_SO_FLAGS = -shared -Wl,-soname,libaabench-test.so -Wl,-z,defs
# The command exports the whole library, so plug-ins can call it.
WHOLE = -rdynamic -Wl,--whole-archive $(1) -Wl,--no-whole-archive
# A test links its own source, the test helpers' objects and the tests'
# library, which it finds in the folder above its own at run time (rpath
# $ORIGIN/..); its .d file adds the headers and included sources it read as
# prerequisites, which are no inputs.  It relinks when the library changes.
# --allow-shlib-undefined: the link does not check the library's own
# references again in the libraries it needs (-z defs did when it was
# made), which takes a plain test's link about a third of its time.
# Linked with gold where binutils has it: half the CPU of a test's compile
# and link (0.45 s a test, measured on test_spec and test_cli, both builds).
TEST_LDFLAGS := -Wl,-rpath,'$$ORIGIN/..' -Wl,--allow-shlib-undefined \
                $(if $(shell command -v ld.gold 2>/dev/null),-fuse-ld=gold)

# $(call build_rules,FOLDER,BUILD): the library, the command, the image
# module, the tests and the plug-ins of build folder FOLDER.
define build_rules
$(call compile_rules,$(1),$(2))
$(1)/aabench-oiio.so: $(patsubst %.cpp,$(1)/obj/%.o,$(OIIO_SRC))
	@echo '  LD    $$@'
	$$(Q)$$($(2)_CXX) $$($(2)_CXXFLAGS) -shared -Wl,-z,defs $$^ -o $$@ $$(OIIO_LIBS)
$(1)/libaabench.a: $(call objs,$(1))
	@rm -f $$@
	@echo '  AR    $$@'
	$$(Q)ar rcs $$@ $$^
$(1)/aabench: $(1)/libaabench.a $(patsubst %.c,$(1)/obj/%.o,$(CLI_SRC)) | $(1)/aabench-oiio.so
	@echo '  LD    $$@'
	$$(Q)$$($(2)_CC) $$($(2)_CFLAGS) $$(filter %.o,$$^) $$(call WHOLE,$(1)/libaabench.a) -o $$@ $$(LDLIBS)
$(1)/libaabench-test.so: $(call objs,$(1))
	@echo '  LD    $$@'
	$$(Q)$$($(2)_CC) $$($(2)_CFLAGS) $$(TEST_SO_FLAGS) $$^ -o $$@ $$(LDLIBS)
$(1)/tests/%: tests/%.c $(patsubst %.c,$(1)/obj/%.o,$(TEST_AUX)) $(1)/libaabench-test.so | $(1)/aabench-oiio.so
	@mkdir -p $$(dir $$@)
	@echo '  LD    $$@'
	$$(Q)$$($(2)_CC) $$(CPPFLAGS) $$($(2)_CFLAGS) $$($(2)_TEST_CFLAGS) -Itests $$(PKG_CFLAGS) $$< $$(filter %.o %.so,$$^) $$(TEST_LDFLAGS) -o $$@ $$(LDLIBS) $$(TEST_LIBS)
$(1)/tests/%.so: tests/%.c harness/aabench.h
	@mkdir -p $$(dir $$@)
	@echo '  LD    $$@'
	$$(Q)$$($(2)_CC) $$(CPPFLAGS) $$($(2)_CFLAGS) -shared $$< -o $$@
endef
$(eval $(call build_rules,$(BUILD),PLAIN))
$(eval $(call build_rules,$(SAN_BUILD),SAN))

# Flags of single objects.
# The module's install folder is compiled into image.o, which is remade when
# PREFIX changes (the file $(BUILD)/oiio-dir holds the last one).
$(BUILD)/oiio-dir: FORCE
	@mkdir -p $(dir $@)
	@echo '$(OIIO_DIR)' | cmp -s - $@ || echo '$(OIIO_DIR)' > $@
FORCE:
$(BUILD)/obj/harness/core/image.o $(SAN_BUILD)/obj/harness/core/image.o: $(BUILD)/oiio-dir
$(BUILD)/obj/harness/core/image.o $(SAN_BUILD)/obj/harness/core/image.o: \
  CPPFLAGS += -DAA_OIIO_DIR='"$(OIIO_DIR)"'
# What results files record of the build (harness/bench/context.c): the
# commit and dirty flag and the libraries' versions in build/build-info.h
# (scripts/build-info.sh, replaced only when it changes), the compiler's
# flags in AA_BUILD_FLAGS.
BUILD_INFO := $(BUILD)/build-info.h
$(BUILD_INFO): FORCE
	@mkdir -p $(dir $@)
	@sh scripts/build-info.sh > $@.tmp && { cmp -s $@.tmp $@ || mv $@.tmp $@; }; rm -f $@.tmp
CONTEXT_O := harness/bench/context.o
$(BUILD)/obj/$(CONTEXT_O) $(SAN_BUILD)/obj/$(CONTEXT_O) $(BUILD)/fuzz/obj/$(CONTEXT_O): $(BUILD_INFO)
$(BUILD)/obj/$(CONTEXT_O): CPPFLAGS += -DAA_BUILD_INFO -I$(BUILD) \
  -DAA_BUILD_FLAGS='"$(PLAIN_CFLAGS)"'
$(SAN_BUILD)/obj/$(CONTEXT_O): CPPFLAGS += -DAA_BUILD_INFO -I$(BUILD) \
  -DAA_BUILD_FLAGS='"$(SAN_CFLAGS)"'
$(BUILD)/fuzz/obj/$(CONTEXT_O): CPPFLAGS += -DAA_BUILD_INFO -I$(BUILD)
# The external method's renderer adapters: the source tree's
# scripts/renderers (found at run time), then their copy that `make install`
# puts in $(OIIO_DIR)/renderers.
$(BUILD)/obj/algorithms/external.o $(SAN_BUILD)/obj/algorithms/external.o: $(BUILD)/oiio-dir
$(BUILD)/obj/algorithms/external.o $(SAN_BUILD)/obj/algorithms/external.o: \
  CPPFLAGS += -DAA_RENDERERS_INSTALLED='"$(OIIO_DIR)/renderers"'
# The installed data (the SVG scenes in DATA_DIR/svg), for a program that
# runs neither from this tree nor from PREFIX/bin (harness/core/paths.c).
DATA_DIR := $(PREFIX)/share/aabench
$(BUILD)/obj/harness/core/paths.o $(SAN_BUILD)/obj/harness/core/paths.o: $(BUILD)/oiio-dir
$(BUILD)/obj/harness/core/paths.o $(SAN_BUILD)/obj/harness/core/paths.o: \
  CPPFLAGS += -DAA_DATA_DIR='"$(DATA_DIR)"'
# The analytic method's parts as one function in the sanitizer build, not
# 192 unrolled copies (algorithms/analytic.c, AN_SPECIALIZE): far less to
# compile there for the same statements run (4 s of CPU instead of 61 when
# made; 14 s in the parallel build of make test at 95 tests, analytic.c grown).
$(SAN_BUILD)/obj/algorithms/analytic.o: CPPFLAGS += -DAN_SPECIALIZE=0
# The exact reference (harness/truth/*.c), what it calls most in
# harness/core (scene.c: the paint's sRGB arithmetic; filter.c: the
# filters' weights and row integrals; scene_piece.c, strip.c: the curves'
# pieces and windings) and the tests' oracles and helpers (tests/*.c but
# the test programs: cone_oracle.c, gradient_oracle.c, oracle.c, ...) at
# -O2 in the sanitizer build, as in the plain one, not -O1: the sanitizer
# tests spend most of their CPU in them (perf: 73-91% in the library, 1-3%
# in libasan, in test_gradient_cone_filter, test_analytic_full and
# test_analytic_radial), with the same checks made.  They compile in 15 s
# of CPU more (34 s instead of 19.6 for the nine library files, 1.1 s
# instead of 0.9 for the oracles), for a fifth to a third less CPU in those
# tests (measured one at a time on the loaded machine: test_truth_gauss
# 27.2 s instead of 33.4, test_gradient_renderers 29.5 instead of 38.2,
# test_gradient_cone_filter 28.8 instead of 41.1, test_analytic_radial
# 11.9 instead of 16.4).
SAN_O2_OBJ := $(addprefix $(SAN_BUILD)/obj/harness/core/,scene.o filter.o scene_piece.o strip.o)
$(SAN_BUILD)/obj/harness/truth/%.o $(SAN_O2_OBJ): SAN_CFLAGS += -O2
$(SAN_BUILD)/obj/tests/%.o: SAN_CFLAGS += -O2
# In the plain build those 192 copies stay (they are its speed), with line
# tables only (-g1, CFLAGS): the locals' descriptions of every copy were a
# third of the library's largest compile, 32 s of CPU with -g and 20 s with
# -g1 (-g0: 20 s).  The polynomial pieces' copies are compiled twice, for
# AVX2 and for any x86-64 (AN_CLONES): 47 s of CPU with -g1.
$(BUILD)/bench_%: tests/bench_%.c $(LIB) | $(OIIO_SO)
	@echo '  LD    $@'
	$(Q)$(CC) $(CPPFLAGS) $(CFLAGS) $(PKG_CFLAGS) $< $(LIB) -o $@ $(LDLIBS)

# ---- fuzzing (libFuzzer; clang, not part of `make test`) ----
# The library is built again with clang into build/fuzz, instrumented for
# the fuzzer and ASan+UBSan, with LLVM's OpenMP (Debian libomp-dev).  Here
# oiio.o is linked into the targets and image.c calls it directly
# (-DAA_OIIO_STATIC, harness/core/oiio.h): no module to load.
FUZZ_BUILD   := $(BUILD)/fuzz
FUZZ_SECONDS ?= 60
FUZZ_FLAGS   := -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -g -O1
FUZZ_TARGETS := $(FUZZ_BUILD)/fuzz_spec $(FUZZ_BUILD)/fuzz_image $(FUZZ_BUILD)/fuzz_cache \
                $(FUZZ_BUILD)/fuzz_baseline $(FUZZ_BUILD)/fuzz_svg $(FUZZ_BUILD)/fuzz_stroke
FUZZ_CC            := clang
FUZZ_CXX           := clang++
FUZZ_CFLAGS        := -std=c11 $(WARN) -Wno-pass-failed -fPIC -fopenmp $(FUZZ_FLAGS)
FUZZ_CXXFLAGS      := -std=c++17 -Wall -Wextra -Werror -fPIC $(FUZZ_FLAGS)
FUZZ_ALGO_CXXFLAGS := -std=c++20 -Wall -Wextra -Werror -fPIC -fopenmp $(FUZZ_FLAGS)
$(eval $(call compile_rules,$(FUZZ_BUILD),FUZZ))
$(FUZZ_BUILD)/obj/harness/core/image.o: CPPFLAGS += -DAA_OIIO_STATIC
$(FUZZ_BUILD)/libaabench.a: $(call objs,$(FUZZ_BUILD)) $(patsubst %.cpp,$(FUZZ_BUILD)/obj/%.o,$(OIIO_SRC))
	@rm -f $@
	@echo '  AR    $@'
	$(Q)ar rcs $@ $^
$(FUZZ_BUILD)/fuzz_%: tests/fuzz/fuzz_%.c $(FUZZ_BUILD)/libaabench.a
	@echo '  LD    $@'
	$(Q)clang++ $(CPPFLAGS) -x c -std=c11 $(WARN) -fsanitize=fuzzer,address,undefined -g -O1 $< -x none \
	  $(FUZZ_BUILD)/libaabench.a -o $@ $(PKG_LIBS) $(OIIO_LIBS) -lm -ldl -fopenmp
# clang's OpenMP (omp.h, libomp) is found by building and running a program
# that uses it, so any clang version with its libomp-dev does.
fuzz:
	@mkdir -p $(FUZZ_BUILD)
	@command -v clang >/dev/null 2>&1 && \
	  printf '#include <omp.h>\nint main(void) { return omp_get_max_threads() < 1; }\n' | \
	  clang -fopenmp -x c - -o $(FUZZ_BUILD)/omp-probe 2>/dev/null && $(FUZZ_BUILD)/omp-probe || \
	  { echo "make fuzz needs clang and its OpenMP: apt-get install clang libomp-dev" >&2; exit 2; }
	@$(MAKE) --no-print-directory $(FUZZ_TARGETS)
	@for t in spec image cache baseline svg stroke; do \
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

# both passes in one make: the sanitizer build and its tests fill the
# cores while plain tests wait on their child processes, and no pass waits
# alone for its last test.  The gate is one more job of that make, its last
# prerequisite: make starts it once every test before it has started or
# waits on its build (in CI, while the sanitizer build compiles), so that
# it runs beside the tests rather than after them.  It judges errors; its
# times are informational, so three timed renders a case do (--reps 3).
test: deps-test
	@$(MAKE) --no-print-directory $(TEST_J) check-tests-both

# The regression gate: the quick suite against results/baseline.csv (each
# case timed until its median is precise, as `aabench check` does).
check-gate: $(BUILD)/aabench
	$(BUILD)/aabench check --baseline results/baseline.csv $(GATE_FLAGS)

# Remake the baseline from the quick suite (commit the result).
baseline: $(BUILD)/aabench
	$(BUILD)/aabench run --suite quick --no-images --no-plots -q --out $(BUILD)/baseline-run
	cp $(BUILD)/baseline-run/results.csv results/baseline.csv

# make check: the quick checks, for every change (under a minute once
# built): the quick tier of the tests, plain build, and the link-level
# cycles (check-cycles, below).  Each check is a prerequisite of `check`.
check: check-tests-quick

check-tests-quick:
	@$(MAKE) --no-print-directory $(TEST_J) check-tests-quick-pass

check-tests-quick-pass: $(call runs_in_order,$(QUICK_TESTS))
	@sh scripts/run-tests.sh summary $(QUICK_TESTS)

# every plain test, both tiers
check-tests:
	@$(MAKE) --no-print-directory $(TEST_J) check-tests-pass

check-tests-pass: $(call runs_in_order,$(TESTS))
	@sh scripts/run-tests.sh summary $(TESTS)

$(TEST_RUNS): %.run: % $(BUILD)/aabench $(PLUGINS)
	@sh scripts/run-tests.sh one $(BUILD) $*

# The gate as a job of make test's pass (check-tests-both): its output in
# GATE_LOG, printed after the tests' summaries, and its exit status in
# GATE_RUN; it never fails itself, so that every test still runs.
GATE_LOG := $(BUILD)/gate.log
GATE_RUN := $(BUILD)/gate.status
.PHONY: $(GATE_RUN)
$(GATE_RUN): $(BUILD)/aabench
	@echo '  GATE  aabench check --reps 3'
	@rm -f $@; $(BUILD)/aabench check --baseline results/baseline.csv --reps 3 >$(GATE_LOG) 2>&1; \
	echo $$? >$@

check-tests-both: $(call runs_in_order,$(call tests_in,$(SAN_BUILD),$(FULL_SRC)) \
                  $(call tests_in,$(BUILD),$(FULL_SRC)) $(call tests_in,$(SAN_BUILD),$(QUICK_SRC)) \
                  $(QUICK_TESTS)) $(GATE_RUN)
	@echo "plain:"; sh scripts/run-tests.sh summary $(TESTS); plain=$$?; \
	echo "under AddressSanitizer and UndefinedBehaviorSanitizer:"; \
	sh scripts/run-tests.sh summary $(SAN_TESTS); san=$$?; \
	echo "the regression gate:"; cat $(GATE_LOG); gate=$$(cat $(GATE_RUN)); \
	[ "$$plain" -eq 0 ] && [ "$$san" -eq 0 ] && [ "$$gate" = 0 ]

check-tests-san:
	@$(MAKE) --no-print-directory $(TEST_J) check-tests-san-pass

check-tests-san-pass: $(call runs_in_order,$(SAN_TESTS))
	@sh scripts/run-tests.sh summary $(SAN_TESTS)

$(SAN_TEST_RUNS): %.run: % $(SAN_BUILD)/aabench $(SAN_PLUGINS)
	@ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  sh scripts/run-tests.sh one $(SAN_BUILD) $*

# No link-level cycle between the files (scripts/check-cycles.sh, nm over
# the objects: a file uses what another defines, and back), after the
# script's self-test on two tiny objects made to form a cycle.
.PHONY: check check-cycles check-cycles-last
check: check-cycles-last
check-cycles: $(BUILD)/aabench
	@sh scripts/check-cycles.sh --self-test
	@sh scripts/check-cycles.sh $(BUILD)
# in `make check`, after the tests' pass, whose make builds everything: a
# top-level build of aabench beside that make's would write the same
# objects at once (a link then fails on a half-written file)
check-cycles-last: check-tests-quick
	@$(MAKE) --no-print-directory check-cycles

# make install into a staging folder, then the installed command run from
# outside the tree: it finds its SVG scenes under its prefix and caches
# references in $XDG_CACHE_HOME/aabench (scripts/check-install.sh).
.PHONY: check-install
check-install: all
	@sh scripts/check-install.sh $(BUILD)

# The Slurm driver on a single-node Slurm started for the check (root;
# installs slurm-wlm and munge when missing, SKIP where they cannot run).
.PHONY: check-slurm
check-slurm: $(BUILD)/aabench $(BUILD)/tests/test_shard
	@sh scripts/check-slurm.sh $(BUILD)

# The contract tests every built-in method passes (tests/test_methods.c),
# run on the methods of a plug-in, named first: make check-plugin PLUGIN=path/to/lib.so
.PHONY: check-plugin
check-plugin: $(BUILD)/tests/test_methods
	@test -n "$(PLUGIN)" || { echo "usage: make check-plugin PLUGIN=lib.so" >&2; exit 2; }
	@test -f "$(PLUGIN)" || { echo "check-plugin: no file $(PLUGIN)" >&2; exit 2; }
	@AABENCH_PLUGIN=$(abspath $(PLUGIN)) AABENCH_PLUGIN_ONLY=1 $(BUILD)/tests/test_methods

# make bench [TARGET_CI=PCT] [BUDGET=S] [REPS=N]: the timing of each figure
# (scripts/bench.sh)
bench: deps
	@$(MAKE) --no-print-directory $(BUILD)/aabench $(BENCHES)
	@TARGET_CI='$(TARGET_CI)' BUDGET='$(BUDGET)' REPS='$(REPS)' sh scripts/bench.sh $(BUILD)

# The seed papers' figures remade into results/figures, their claims
# measured (results/figures/claims.md), then the gallery checked in a
# headless browser when chromium is present.
.PHONY: figures
figures: $(BUILD)/aabench
	$(BUILD)/aabench figures
	$(BUILD)/aabench figures --claims
	@if command -v chromium >/dev/null 2>&1; then sh scripts/check-gallery.sh results/figures; \
	else echo "figures: chromium missing, gallery not checked (apt-get install chromium)"; fi

# A run's report (its index.html: tables, montages, error maps, plots) seen
# by headless Chromium, as the gallery is: the quick suite, one render a case.
.PHONY: check-report
check-report: $(BUILD)/aabench
	rm -rf $(BUILD)/report-run
	$(BUILD)/aabench run --suite quick --reps 1 -q --out $(BUILD)/report-run
	@if command -v chromium >/dev/null 2>&1; then sh scripts/check-gallery.sh $(BUILD)/report-run; \
	else echo "check-report: chromium missing, report not checked (apt-get install chromium)"; fi

# make install [PREFIX=/usr/local] [DESTDIR=staging]: the command, the
# library, and for plug-in authors the public headers (PUBLIC_HEADERS, into
# PREFIX/include/aabench/) and aabench.pc (from harness/aabench.pc.in), so that
#     cc -shared -fPIC $$(pkg-config --cflags aabench) method.c -o method.so
# builds a plug-in.  DESTDIR prefixes every path written, not those in the
# .pc file.
PUBLIC_HEADERS := harness/aabench.h
AA_VERSION = $(shell sed -n 's/^.define AA_VERSION "\(.*\)"$$/\1/p' harness/core/core.h)
install: all
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig \
	  $(DESTDIR)$(PREFIX)/include/aabench $(DESTDIR)$(OIIO_DIR)
	install -m 755 $(BUILD)/aabench $(DESTDIR)$(PREFIX)/bin/
	install -m 755 $(OIIO_SO) $(DESTDIR)$(OIIO_DIR)/
	install -d $(DESTDIR)$(OIIO_DIR)/renderers
	install -m 755 scripts/renderers/rsvg scripts/renderers/chromium scripts/renderers/resvg \
	  $(DESTDIR)$(OIIO_DIR)/renderers/
	install -m 644 scripts/renderers/resvg.js scripts/renderers/README.md $(DESTDIR)$(OIIO_DIR)/renderers/
	install -d $(DESTDIR)$(DATA_DIR)/svg
	install -m 644 patterns/svg/*.svg $(DESTDIR)$(DATA_DIR)/svg/
	install -m 644 $(LIB) $(DESTDIR)$(PREFIX)/lib/
	install -m 644 $(PUBLIC_HEADERS) $(DESTDIR)$(PREFIX)/include/aabench/
	sed -e 's|@prefix@|$(PREFIX)|' -e 's|@version@|$(AA_VERSION)|' harness/aabench.pc.in >$(BUILD)/aabench.pc
	install -m 644 $(BUILD)/aabench.pc $(DESTDIR)$(PREFIX)/lib/pkgconfig/

clean:
	rm -rf $(BUILD)

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
