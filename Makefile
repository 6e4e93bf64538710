# clothode: particle cloth as a stiff ODE, integrators side by side.
#   make demo    install missing packages, build, run `hang`, draw plots/demo.png
#   make test    install missing packages, build, run the test suite
#   make SAN=1 test   the same under AddressSanitizer + UndefinedBehaviorSanitizer
#   make bench   build, run the benchmark workloads, write results/bench.csv

CC      ?= cc
SHELL   := /bin/bash
SAN     ?= 0
BUILD   := build$(if $(filter 1,$(SAN)),-san,)

CPPFLAGS := -Isrc -I/usr/include/suitesparse -D_XOPEN_SOURCE=700
CFLAGS   := -std=c11 -Wall -Wextra -Werror -g -fopenmp
ifeq ($(SAN),1)
CFLAGS  += -O1 -fsanitize=address,undefined -fno-omit-frame-pointer \
           -fno-sanitize-recover=undefined
LDFLAGS += -fsanitize=address,undefined
else
CFLAGS  += -O2
endif
# the build ID, a hash of each linked file's contents, names the binary
# in run.json (cli/version.c)
LDFLAGS += -fopenmp -Wl,--build-id=sha1
LDLIBS := -lsundials_cvode -lsundials_ida -lsundials_kinsol \
          -lsundials_arkode \
          -lsundials_nvecserial -lsundials_sunmatrixsparse \
          -lsundials_sunmatrixdense \
          -lsundials_sunlinsolklu -lsundials_sunlinsolspgmr \
          -lsundials_sunlinsolpcg -lsundials_sunnonlinsolfixedpoint \
          -lklu -lcholmod -lamd -lcolamd -lbtf \
          -lsuitesparseconfig -lgsl -llapacke -llapack -lblas -linih -lm
# run.json (src/cli/manifest.c): JSON by jansson, SHA-256 by nettle
LDLIBS += -ljansson -lnettle -ldl

# The library holds the numerics; the benchmark harness (src/bench) is a
# program of its own on it, clothode-bench.
# The files NAME_petsc.c form the plug-in clothode-petsc.so (linalg/plugin.h).
PETSC_SRC := $(wildcard src/*/*_petsc.c)
LIB_SRC  := $(filter-out src/cli/main.c src/bench/% $(PETSC_SRC),\
                         $(wildcard src/*/*.c))
LIB_OBJ  := $(LIB_SRC:%.c=$(BUILD)/%.o)
CLI_OBJ  := $(BUILD)/src/cli/main.o
BENCH_SRC := $(filter-out src/bench/main.c,$(wildcard src/bench/*.c))
BENCH_OBJ := $(BENCH_SRC:%.c=$(BUILD)/%.o)
BENCHBIN := $(BUILD)/clothode-bench
TEST_SRC := $(wildcard tests/test_*.c)
TEST_OBJ := $(TEST_SRC:%.c=$(BUILD)/%.o)
BIN      := $(BUILD)/clothode
TESTBIN  := $(BUILD)/clothode-tests
JOBS     ?= 2

PREFIX  ?= /usr/local
VERSION := 0.1

.PHONY: all deps demo test bench report paper install uninstall clean fuzz \
        memcheck FORCE

all: $(BIN)

deps:
	@scripts/install-deps.sh

# Every object depends on the flags it is compiled with: a make with other
# CC, CPPFLAGS or CFLAGS rebuilds them all, so that the flags `clothode
# --version` and run.json name are those of every object (the stamp
# changes only when they do).
$(BUILD)/flags.stamp: FORCE
	@mkdir -p $(BUILD)
	@echo '$(CC) $(CPPFLAGS) $(CFLAGS)' > $@.new
	@cmp -s $@.new $@ && rm -f $@.new || mv -f $@.new $@

$(BUILD)/%.o: %.c $(BUILD)/flags.stamp
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS) -MMD -MP -c $< -o $@

# The pair kernels (src/forces/pairkern.h): GCC vectorises their sqrt and
# selects only without errno and FP-trap semantics; no value changes.
KERNEL_SRC := src/forces/pairkern.c \
              src/forces/type1.c src/forces/type2.c src/forces/springs.c \
              src/forces/pairdamp.c src/forces/pairgather.c
$(KERNEL_SRC:%.c=$(BUILD)/%.o): CFLAGS += -fno-math-errno -fno-trapping-math

# The version, git commit (`git describe --always --dirty`, "unknown"
# outside a git checkout), compiler and flags that `clothode --version` and
# run.json name (src/cli/version.c); the header changes only when they do.
$(BUILD)/buildinfo.h: FORCE
	@mkdir -p $(BUILD)
	@c=$$(git describe --always --dirty 2>/dev/null) || c=; \
	{ printf '#define CL_BUILD_VERSION "%s"\n' '$(VERSION)'; \
	  printf '#define CL_BUILD_COMMIT "%s"\n' "$${c:-unknown}"; \
	  printf '#define CL_BUILD_CC "%s"\n' '$(CC)'; \
	  printf '#define CL_BUILD_FLAGS "%s"\n' '$(BUILD_FLAGS)'; \
	} > $@.new
	@cmp -s $@.new $@ && rm -f $@.new || mv -f $@.new $@
BUILD_FLAGS := $(CPPFLAGS) $(CFLAGS) (pair kernels also -fno-math-errno \
               -fno-trapping-math)
$(BUILD)/src/cli/version.o: $(BUILD)/buildinfo.h
$(BUILD)/src/cli/version.o: CPPFLAGS += -I$(BUILD)
FORCE:

# The PETSc plug-in: position-independent objects in $(BUILD)/pic, PETSc's
# and MPI's headers as system headers (their warnings are not ours).
PETSC_OBJ    := $(PETSC_SRC:%.c=$(BUILD)/pic/%.o)
PETSC_SO     := $(BUILD)/clothode-petsc.so
PETSC_CFLAGS := $(patsubst -I%,-isystem %,\
                  $(shell pkg-config --cflags petsc mpi 2>/dev/null))
PETSC_LIBS   := $(shell pkg-config --libs petsc mpi 2>/dev/null)

$(BUILD)/pic/%.o: %.c $(BUILD)/flags.stamp
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(PETSC_CFLAGS) $(CFLAGS) -fPIC -MMD -MP -c $< -o $@

$(PETSC_SO): $(PETSC_OBJ)
	$(CC) $(LDFLAGS) -shared $^ $(PETSC_LIBS) -o $@

# The plug-in interface version (linalg/plugin.h): the SHA-256 of the
# preprocessed text of the headers src/*/*_abi.h (the types of every entry
# point, and what they include), its runs of white space made one space so
# that a blank line or an indentation changes nothing; remade whenever one
# of them changes.
ABI_HDR := $(wildcard src/*/*_abi.h)
ABI_USE := $(BUILD)/src/linalg/plugin.o \
           $(BUILD)/pic/src/linalg/pluginabi_petsc.o $(BUILD)/tests/test_plugin.o
$(BUILD)/pluginabi.h: $(ABI_HDR)
	@mkdir -p $(BUILD)
	@set -o pipefail; h=$$(printf '#include "%s"\n' $(ABI_HDR:src/%=%) | \
	    $(CC) $(CPPFLAGS) -E -P -MMD -MP -MF $@.d -MT $@ -x c - | \
	    tr -s '[:space:]' ' ' | sha256sum) && \
	printf '#define CL_PLUGIN_ABI "%.16s"\n' "$$h" > $@
$(ABI_USE): $(BUILD)/pluginabi.h
$(ABI_USE): CPPFLAGS += -I$(BUILD)

# Test plug-ins (tests/test_plugin.c) from tests/plugins/probe.c: with
# this build's interface version, with a wrong one, and with none.
TESTPLUG_DIR := $(BUILD)/test-plugins
TESTPLUG := $(TESTPLUG_DIR)/right/clothode-probe.so \
            $(TESTPLUG_DIR)/wrong/clothode-petsc.so \
            $(TESTPLUG_DIR)/none/clothode-petsc.so
$(TESTPLUG_DIR)/right/%: PROBE_ABI := -include $(BUILD)/pluginabi.h \
                                      -DPROBE_ABI=CL_PLUGIN_ABI
$(TESTPLUG_DIR)/wrong/%: PROBE_ABI := -DPROBE_ABI='"0123456789abcdef"'
$(TESTPLUG): tests/plugins/probe.c $(BUILD)/pluginabi.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -fPIC -shared $(LDFLAGS) $(PROBE_ABI) $< -o $@
$(BUILD)/tests/test_plugin.o: CPPFLAGS += \
    -DCL_TEST_PLUGINS='"$(abspath $(TESTPLUG_DIR))"'

$(BUILD)/libclothode.a: $(LIB_OBJ)
	rm -f $@
	ar rcs $@ $^

$(BIN): $(CLI_OBJ) $(BUILD)/libclothode.a | $(PETSC_SO)
	$(CC) $(LDFLAGS) $^ $(LDLIBS) -o $@

$(BENCHBIN): $(BUILD)/src/bench/main.o $(BENCH_OBJ) $(BUILD)/libclothode.a | $(PETSC_SO)
	$(CC) $(LDFLAGS) $^ $(LDLIBS) -o $@

$(TESTBIN): $(TEST_OBJ) $(BENCH_OBJ) $(BUILD)/libclothode.a | $(PETSC_SO) \
            $(TESTPLUG)
	$(CC) $(LDFLAGS) $^ -lcriterion $(LDLIBS) -o $@

demo: deps
	$(MAKE) $(BIN)
	scripts/demo.sh $(BIN)

# Sanitizer reports from Criterion's worker processes (LeakSanitizer at
# exit) do not fail a test by themselves: the log is checked for them.
test: deps
	scripts/check-layers.sh
	SAN=$(SAN) JOBS=$(JOBS) scripts/check-walkthroughs.sh
	$(MAKE) $(BIN) $(BENCHBIN) $(TESTBIN)
	set -o pipefail; CLOTHODE=$(BIN) CLOTHODE_BENCH=$(BENCHBIN) \
	    $(TESTBIN) --jobs $(JOBS) 2>&1 | \
	    tee $(BUILD)/test.log
	@! grep -E "(Address|Leak|UndefinedBehavior)Sanitizer|runtime error:" \
	    $(BUILD)/test.log || (echo "sanitizer reports above" >&2; exit 1)

# Benchmarks (README "Benchmarks"): the full set (workloads 0-9 under 20
# minutes on two cores, 10 and 11 tens of minutes each at their largest
# sizes); table on stdout, results/bench.csv.
bench: deps
	$(MAKE) $(BENCHBIN)
	$(BENCHBIN)

# Reports (README "Reports"): the analyses on the default problems, CSV
# tables in results/report/, figures in plots/ (about six minutes).
report: deps
	$(MAKE) $(BIN)
	scripts/report.sh $(BIN)

# The paper (README "Reports"): paper/paper.pdf from the report's tables
# and figures (the report is made first if it is missing).
paper: deps
	@scripts/install-deps.sh paper
	$(MAKE) $(BIN)
	test -f results/report/sensitivity.txt || scripts/report.sh $(BIN)
	scripts/paper-tables.sh
	mkdir -p $(BUILD)/paper
	cd paper && for pass in 1 2; do \
	    pdflatex -interaction=nonstopmode -halt-on-error \
	        -output-directory=../$(BUILD)/paper paper.tex > /dev/null || \
	    { tail -30 ../$(BUILD)/paper/paper.log; exit 1; }; done
	cp $(BUILD)/paper/paper.pdf paper/paper.pdf
	@echo "paper: paper/paper.pdf"

# make install PREFIX=DIR (README "Installing"): the command, the library
# with its headers and pkg-config file, the problems, the man page.
# The installed library's plug-in lookup knows PREFIX/lib/clothode
# (linalg/plugin.h): its copy of plugin.o is built with that folder.
INSTALL_TMP := $(BUILD)/install
INSTALLED   := bin/clothode lib/libclothode.a lib/clothode/clothode-petsc.so \
               include/clothode share/clothode share/man/man1/clothode.1 \
               lib/pkgconfig/clothode.pc

# PREFIX must be absolute: the installed library and clothode.pc record it
ABSOLUTE_PREFIX = @case "$(PREFIX)" in /*) ;; *) echo "make $@: \
	PREFIX=$(PREFIX): expected an absolute path" >&2; exit 2;; esac

install: $(BIN)
	$(ABSOLUTE_PREFIX)
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig \
	    $(DESTDIR)$(PREFIX)/share/clothode $(DESTDIR)$(PREFIX)/share/man/man1
	install -m 755 $(BIN) $(DESTDIR)$(PREFIX)/bin/clothode
	mkdir -p $(INSTALL_TMP)
	$(CC) $(CPPFLAGS) -I$(BUILD) $(CFLAGS) \
	    -DCL_PLUGIN_INSTALL_DIR='"$(PREFIX)/lib/clothode"' \
	    -c src/linalg/plugin.c -o $(INSTALL_TMP)/plugin.o
	cp $(BUILD)/libclothode.a $(INSTALL_TMP)/libclothode.a
	ar rs $(INSTALL_TMP)/libclothode.a $(INSTALL_TMP)/plugin.o
	install -m 644 $(INSTALL_TMP)/libclothode.a $(DESTDIR)$(PREFIX)/lib/
	install -D -m 755 $(PETSC_SO) \
	    $(DESTDIR)$(PREFIX)/lib/clothode/clothode-petsc.so
	rm -rf $(DESTDIR)$(PREFIX)/include/clothode
	for h in $(filter-out src/bench/%,$(wildcard src/*/*.h)); do \
	    install -D -m 644 $$h \
	        $(DESTDIR)$(PREFIX)/include/clothode/$${h#src/}; \
	done
	rm -rf $(DESTDIR)$(PREFIX)/share/clothode/problems
	cp -R problems $(DESTDIR)$(PREFIX)/share/clothode/
	install -m 644 docs/clothode.1 $(DESTDIR)$(PREFIX)/share/man/man1/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' \
	    -e 's|@LIBS@|$(filter -fsanitize%,$(LDFLAGS)) $(LDLIBS)|' \
	    scripts/clothode.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/clothode.pc

uninstall:
	$(ABSOLUTE_PREFIX)
	rm -rf $(INSTALLED:%=$(DESTDIR)$(PREFIX)/%)
	-rmdir $(DESTDIR)$(PREFIX)/lib/clothode 2>/dev/null

# Fuzzing (README "Fuzzing"): libFuzzer harnesses tests/fuzz/fuzz_*.c on
# the readers, built by clang-14 with ASan + UBSan into build-fuzz/; each
# runs FUZZ_SECONDS from its seed corpus tests/fuzz/NAME/ (new inputs go to
# build-fuzz/corpus/NAME/), leaks detected; a crash stops make.
FUZZ_SECONDS ?= 60
FUZZ_CC      := clang-14
FUZZ_FLAGS   := -std=c11 -g -O1 -Wall -Wextra -Werror -fno-omit-frame-pointer \
                -fsanitize=fuzzer,address,undefined \
                -fno-sanitize-recover=undefined
FUZZ_LIB     := $(wildcard src/core/*.c src/io/*.c) src/linalg/bpattern.c
FUZZ_NAMES   := config state obj mtx

build-fuzz/fuzz_%: tests/fuzz/fuzz_%.c tests/fuzz/fuzz.h $(FUZZ_LIB) \
                   $(wildcard src/*/*.h)
	@mkdir -p build-fuzz
	$(FUZZ_CC) $(CPPFLAGS) $(FUZZ_FLAGS) $< $(FUZZ_LIB) -linih -lnettle -ljansson -lm -o $@

fuzz:
	@scripts/install-deps.sh fuzz
	$(MAKE) $(FUZZ_NAMES:%=build-fuzz/fuzz_%)
	set -e; for h in $(FUZZ_NAMES); do \
	    mkdir -p build-fuzz/corpus/$$h; \
	    echo "fuzz: $$h, $(FUZZ_SECONDS) s"; \
	    ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	    build-fuzz/fuzz_$$h -max_total_time=$(FUZZ_SECONDS) \
	        -print_final_stats=1 -artifact_prefix=build-fuzz/$$h- \
	        build-fuzz/corpus/$$h tests/fuzz/$$h 2>&1 | \
	        tee build-fuzz/$$h.log | grep -E "^stat::number_of_executed_units|ERROR|SUMMARY"; \
	    test $${PIPESTATUS[0]} -eq 0; \
	done

# A short hang run under valgrind's memcheck (README "Fuzzing").
memcheck: $(BIN)
	valgrind --tool=memcheck --leak-check=full --error-exitcode=1 \
	    $(BIN) run hang --t-end 0.05 --frames 1 --out $(BUILD)/memcheck \
	    --quiet

clean:
	rm -rf build build-san build-fuzz

-include $(LIB_OBJ:.o=.d) $(CLI_OBJ:.o=.d) $(TEST_OBJ:.o=.d) \
    $(BENCH_OBJ:.o=.d) $(BUILD)/src/bench/main.d $(PETSC_OBJ:.o=.d) \
    $(BUILD)/pluginabi.h.d
