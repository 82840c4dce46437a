# greenconv — top-level Makefile (GNU make).
#
#   make            same as `make lib`
#   make deps       install what is missing: gfortran, LAPACK, BLAS, FFTW3, gnuplot (apt), fpm (pip)
#   make build      deps, then `fpm build --profile release`
#   make lib        plain build with the compiler alone, no fpm: build/make/libgreenconv.a and
#                   libgreenconv.so, module files in build/make/include/, the driver
#                   build/make/greenconv (compiled with OpenMP, which makes FFTW's planner
#                   thread-safe; see src/greenconv/ext/fftw.f90)
#   make examples   the library examples against the plain build: example/c_contact.c (C),
#                   example/cxx_header.cpp (C++, when $(CXX) exists), example/legacy_f77.f
#                   (fixed-form Fortran 77 style), example/omp_threads.f90 (two OpenMP threads),
#                   example/c_patch.c and example/legacy_patch.f (a 2D multi-point patch),
#                   example/c_patch_file.c and example/legacy_patch_file.f (the shipped patch
#                   from data/patch_green.uff, against the driver's run of data/patch_road.nml)
#                   example/legacy_modes_file.f (a patch from a modes file, the accuracy asked)
#                   and example/legacy_laws.f (the contact law by name: the exponential law
#                   against the driver, the power law against the (k_c, p) doors, refusals)
#   make install    install the driver, both libraries, include/greenconv.h, the .mod files
#                   and greenconv.pc (pkg-config) under PREFIX (default /usr/local; DESTDIR too)
#   make doc        API documentation with FORD (installed with pip when missing) into
#                   build/doc/index.html, after checking that every public entity has a
#                   `!>` comment (make doc-check)
#   make run        deps, build, run every data/*.nml scene, then the benchmark's tables and
#                   charts (`make bench-data`), then draw every plot/*.gp into out/figures/
#   make bench      deps, build, run the benchmark example greenconv-bench: Tabs. 2-3 and the
#                   targets measured in one run, printed and saved in out/bench/tables.txt, the
#                   data of the speed/accuracy and stability charts in out/bench/, the driver's whole-process
#                   time on Tab. 2's largest case (text, binary) against the C printf anchor
#                   (bench/driver_output.sh, out/bench/driver_output.txt), the implicit patch
#                   against the explicit one on 1 and 2 threads and at 5,000 points (`make
#                   bench-patch`, out/bench/patch_cost.txt), the identification and sweep
#                   rows, then the benchmark's figures (the plot/*.gp that read out/bench/)
#   make bench-patch  per-step costs of exact and modal on data/tyre_patch.nml and their ratio,
#                   rounds interleaved, 1 and 2 OpenMP threads, the 5,000-point grid measured
#                   and projected (bench/patch_cost.sh on the plain build's driver)
#   make figures    only draw plot/*.gp from the existing out/*.dat (text or binary runs:
#                   plot/lib/column_file.gp picks <name>_<method>.dat or .bin)
#   make plot-test  the plot scripts that read contact runs draw the same figure from a text
#                   and a binary run (tools/test_plot_formats.sh, about 10 s; run by make test)
#   make test       deps, the layer check (`make layers`), the link check (`make links`), the doc
#                   check (`make doc-check`), `make lib`
#                   and its symbol check (tools/check_symbols.sh: no global symbol outside greenconv's
#                   prefixes), the version check (tools/check_version.sh: fpm.toml's version in the
#                   header, doc/greenconv.md, CHANGELOG.md and `greenconv --version`), check that the
#                   Makefile-built driver writes the same output as the fpm-built one, build
#                   and run the examples (each compares its results with the driver's output
#                   for data/sdof_sine.nml or data/patch_road.nml), install into a temporary prefix and build the C
#                   and Fortran 77 examples against it with pkg-config, run the fuzz test
#                   (`make fuzz` with TEST_FUZZ_CASES = 600 cases), the benchmark's smoke
#                   checks (`make bench-smoke`), the sweep and patch-file checks, then
#                   `fpm test` (its "N passed, N failed" line is the last line printed)
#   make layers     tools/check_layers.sh (no module uses one of a higher layer; module names
#                   follow their paths), then its self-test tools/test_check_layers.sh
#   make links      tools/check_links.sh (every relative link and #anchor of README.md,
#                   CHANGELOG.md and doc/*.md exists), then its self-test tools/test_check_links.sh
#   make bench-smoke  the benchmark's smoke checks: `fpm run --example greenconv-bench -- --smoke`
#                   (the stability map and the multi-point cost table on small cases)
#
#   One suite or one test of the unit tests:  fpm test -- SUITE [TEST]
#   e.g. `fpm test -- contact`, `fpm test -- sdof 'receptance at rest is 1/K'`; an unknown
#   name lists the valid ones.
#   make patch-green-check  rebuild example/write_patch_green.f90 and check that it writes
#                   data/patch_green.uff byte for byte (run by make test)
#   make fuzz       damage the shipped scene, receptance and road files FUZZ_CASES ways (default
#                   2000) and check that the driver always ends with status 0, 2 or 3 and one
#                   clean message, never a signal or a half-written file (fuzz/fuzz_main.f90)
#   make valgrind   the plain build's driver on every data/*.nml scene (n_steps cut to 2000),
#                   the examples and the C tests under valgrind; fails on an invalid access or
#                   memory "definitely lost" (tools/make_helpers.sh valgrind)
#   make thread-check  two threads through the C API (test/threads/two_threads.c: a stress
#                   run and one under helgrind) and the check that the library holds no
#                   writable static local (make statics-check, tools/check_statics.sh); see below
#   make sanitize   the library and the unit tests built twice, with -fsanitize=address,undefined
#                   and with -fcheck=all (build/sanitize-*), then the test suite and SANITIZE_FUZZ
#                   fuzz cases (default 200) on each (`make sanitize-builds`), then `make valgrind`;
#                   run before every submission; see the target below
#   make clean      remove build/ and out/
#
# The plain build takes its module order from the `use` statements of the sources
# (build/make/deps.mk, generated), so a new module in src/ needs no edit here.

SHELL := bash
.SHELLFLAGS := -eu -o pipefail -c
MAKEFLAGS += --no-builtin-rules --no-print-directory
.SUFFIXES:
.DELETE_ON_ERROR:

# ---- tools and flags -----------------------------------------------------------------

# GNU make predefines FC = f77, which `?=` would keep: take gfortran unless FC was set by
# the user (command line or environment).
ifeq ($(origin FC),default)
FC := gfortran
endif
FC ?= gfortran
FFLAGS ?= -O2 -g -std=f2018 -Wall -Wextra -Wimplicit-interface -fimplicit-none -frecursive
# The library is compiled position-independent (for libgreenconv.so) and with OpenMP: its
# only directives are the critical sections around FFTW's planner (src/greenconv/ext/fftw.f90), and
# OpenMP also keeps every local variable on the stack (re-entrant). OMPFLAGS= turns it off;
# -frecursive in FFLAGS keeps the locals on the stack then too. Neither reaches the lengths of
# deferred-length character function results, which gfortran keeps static (`make thread-check`).
PICFLAGS ?= -fPIC
OMPFLAGS ?= -fopenmp
LDLIBS ?= -llapack -lblas -lfftw3
# What a C program needs besides LDLIBS to link the static library: the Fortran runtime.
FORTRAN_RUNTIME ?= -lgfortran $(if $(OMPFLAGS),-lgomp) -lm
CFLAGS ?= -O2 -g -std=c99 -Wall -Wextra -pedantic
CXXFLAGS ?= -O2 -g -std=c++11 -Wall -Wextra -pedantic
# Fixed-form Fortran 77 style code (INTEGER*8 handles, as FFTW's legacy interface uses).
LEGACY_FFLAGS ?= -O2 -g -Wall -ffixed-form
AR ?= ar
PREFIX ?= /usr/local
DESTDIR ?=
FPM ?= fpm
export FPM
FPM_PROFILE ?= release
GNUPLOT ?= gnuplot

# pip's user scheme (a non-root `pip install fpm` outside a virtualenv) puts fpm here.
export PATH := $(PATH):$(HOME)/.local/bin

HELPER := bash tools/make_helpers.sh

# ---- paths -----------------------------------------------------------------------------

BUILD   := build/make
MODDIR  := $(BUILD)/include
LIB     := $(BUILD)/libgreenconv.a
# The shared library: real name libgreenconv.so.VERSION (fpm.toml's version), soname
# libgreenconv.so.MAJOR, and the link name libgreenconv.so.
VERSION := $(shell sed -n 's/^version *= *"\(.*\)"/\1/p' fpm.toml)
# The version's only source; src/greenconv/core/version.F90 gets it as GREENCONV_VERSION (fpm
# passes the same macro from [preprocess.cpp]). No version line, no build: nothing is guessed.
ifeq ($(VERSION),)
$(error fpm.toml has no line 'version = "x.y.z"': the build takes greenconv's version from it)
endif
VERSION_DEFINE := -DGREENCONV_VERSION=$(VERSION)
SOMAJOR := $(firstword $(subst ., ,$(VERSION)))
SHLIB   := $(BUILD)/libgreenconv.so.$(VERSION)
BIN     := $(BUILD)/greenconv
DEPFILE := $(BUILD)/deps.mk
EXDIR   := $(BUILD)/examples
EXAMPLES := $(EXDIR)/c_contact $(EXDIR)/legacy_f77 $(EXDIR)/c_patch $(EXDIR)/legacy_patch $(EXDIR)/c_patch_file \
            $(EXDIR)/legacy_patch_file $(EXDIR)/legacy_modes_file $(EXDIR)/legacy_laws $(if $(OMPFLAGS),$(EXDIR)/omp_threads) \
            $(if $(shell command -v $(CXX) 2>/dev/null),$(EXDIR)/cxx_header)

# Every Fortran source under src/ (subfolders too, as fpm does); objects mirror the tree.
SRCS := $(sort $(shell find src -name '*.f90' -o -name '*.F90' 2>/dev/null))
# The C sources under src/ (fpm compiles them too): objects beside the Fortran ones.
CSRCS := $(sort $(shell find src -name '*.c' 2>/dev/null))
OBJS := $(patsubst %,$(BUILD)/%.o,$(basename $(SRCS))) $(patsubst %.c,$(BUILD)/%.c.o,$(CSRCS))

SCENES  := $(wildcard data/*.nml)
PLOTS   := $(wildcard plot/*.gp)
# the figures drawn from the benchmark's data alone (out/bench/), which `make bench` draws
BENCH_PLOTS := $(shell grep -l 'out/bench' $(PLOTS))
FIGDIR  := out/figures
# Scenes whose Makefile-built output is compared with the fpm-built one in `make test`.
CHECK_SCENES ?= data/sdof_sine.nml

.PHONY: all lib deps build run bench bench-data bench-smoke figures bench-figures test layers links clean examples install doc doc-check \
        fuzz valgrind sanitize sanitize-builds sanitize-ci plot-test thread-test thread-stress thread-helgrind thread-readers thread-ident thread-check \
        statics-check

all: lib

# ---- deps ------------------------------------------------------------------------------

deps:
	@$(HELPER) deps

# ---- fpm build -------------------------------------------------------------------------

build: deps
	$(FPM) build --profile $(FPM_PROFILE)

# ---- plain build (no fpm) --------------------------------------------------------------

lib: $(LIB) $(SHLIB) $(BIN)

# Objects are rebuilt when the compile command changes (the stamp is rewritten only then).
COMPILE := $(FC) $(FFLAGS) $(PICFLAGS) $(OMPFLAGS)
$(BUILD)/compile.cmd: FORCE
	@mkdir -p $(@D)
	@echo '$(COMPILE)' | cmp -s - $@ || echo '$(COMPILE)' > $@

$(BUILD)/%.o: %.f90 $(BUILD)/compile.cmd | $(MODDIR)
	@mkdir -p $(@D)
	$(FC) $(FFLAGS) $(PICFLAGS) $(OMPFLAGS) -J$(MODDIR) -c $< -o $@

$(BUILD)/%.o: %.F90 $(BUILD)/compile.cmd | $(MODDIR)
	@mkdir -p $(@D)
	$(FC) $(FFLAGS) $(PICFLAGS) $(OMPFLAGS) $(VERSION_DEFINE) -J$(MODDIR) -c $< -o $@

# A new version in fpm.toml rebuilds the module that holds it.
$(BUILD)/src/greenconv/core/version.o: fpm.toml

$(BUILD)/%.c.o: %.c $(BUILD)/compile.cmd
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(PICFLAGS) -c $< -o $@

$(LIB): $(OBJS)
	@rm -f $@
	$(AR) rcs $@ $^

$(SHLIB): $(OBJS)
	$(FC) -shared $(OMPFLAGS) -Wl,-soname,libgreenconv.so.$(SOMAJOR) -o $@ $^ $(LDLIBS)
	@ln -sf $(@F) $(BUILD)/libgreenconv.so.$(SOMAJOR)
	@ln -sf libgreenconv.so.$(SOMAJOR) $(BUILD)/libgreenconv.so

$(BIN): app/main.f90 $(LIB)
	$(FC) $(FFLAGS) $(OMPFLAGS) -I$(MODDIR) -o $@ $< $(LIB) $(LDLIBS)

$(MODDIR):
	@mkdir -p $@

# Module dependencies "a.o: b.o" (b.f90 defines a module that a.f90 uses). Regenerated
# when a source changes, and also when a source was added or removed since the last time
# (deps.mk records the list as DEPS_SRCS). Only read for goals that compile.
ifneq ($(filter all lib examples install fuzz ctest valgrind mpi sweep-test sweep-bench patch-green-check plot-test $(BUILD)/%,$(or $(MAKECMDGOALS),all)),)
-include $(DEPFILE)
endif

$(DEPFILE): $(SRCS) tools/make_helpers.sh $(if $(filter-out $(SRCS),$(DEPS_SRCS))$(filter-out $(DEPS_SRCS),$(SRCS)),FORCE)
	@mkdir -p $(@D)
	@$(HELPER) f90deps $(BUILD) $(SRCS) > $@.tmp && mv $@.tmp $@

.PHONY: FORCE
FORCE:

# ---- examples of the library (C, C++, Fortran 77 style, OpenMP) ---------------------------

examples: $(EXAMPLES)

$(EXDIR)/c_contact: example/c_contact.c include/greenconv.h $(LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -Iinclude -o $@ $< $(LIB) $(LDLIBS) $(FORTRAN_RUNTIME)

$(EXDIR)/c_patch: example/c_patch.c include/greenconv.h $(LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -Iinclude -o $@ $< $(LIB) $(LDLIBS) $(FORTRAN_RUNTIME)

$(EXDIR)/legacy_patch: example/legacy_patch.f $(LIB)
	@mkdir -p $(@D)
	$(FC) $(LEGACY_FFLAGS) $(OMPFLAGS) -I$(MODDIR) -J$(@D) -o $@ $< $(LIB) $(LDLIBS)

$(EXDIR)/c_patch_file: example/c_patch_file.c include/greenconv.h $(LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -Iinclude -o $@ $< $(LIB) $(LDLIBS) $(FORTRAN_RUNTIME)

$(EXDIR)/legacy_patch_file: example/legacy_patch_file.f $(LIB)
	@mkdir -p $(@D)
	$(FC) $(LEGACY_FFLAGS) $(OMPFLAGS) -I$(MODDIR) -J$(@D) -o $@ $< $(LIB) $(LDLIBS)

$(EXDIR)/legacy_modes_file: example/legacy_modes_file.f $(LIB)
	@mkdir -p $(@D)
	$(FC) $(LEGACY_FFLAGS) $(OMPFLAGS) -I$(MODDIR) -J$(@D) -o $@ $< $(LIB) $(LDLIBS)

$(EXDIR)/legacy_laws: example/legacy_laws.f $(LIB)
	@mkdir -p $(@D)
	$(FC) $(LEGACY_FFLAGS) $(OMPFLAGS) -I$(MODDIR) -J$(@D) -o $@ $< $(LIB) $(LDLIBS)

$(EXDIR)/cxx_header: example/cxx_header.cpp include/greenconv.h $(LIB)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) -Iinclude -o $@ $< $(LIB) $(LDLIBS) $(FORTRAN_RUNTIME)

$(EXDIR)/legacy_f77: example/legacy_f77.f $(LIB)
	@mkdir -p $(@D)
	$(FC) $(LEGACY_FFLAGS) $(OMPFLAGS) -I$(MODDIR) -J$(@D) -o $@ $< $(LIB) $(LDLIBS)

# The generator of data/patch_green.uff (a 4 x 3 patch's Green's matrix with 1 % noise,
# example/write_patch_green.f90): `make patch-green-check` rebuilds it and checks that it
# writes the shipped file byte for byte, so the shipped data stays what its header says.
$(EXDIR)/write_patch_green: example/write_patch_green.f90 $(LIB)
	@mkdir -p $(@D)
	$(FC) $(FFLAGS) $(OMPFLAGS) -I$(MODDIR) -J$(@D) -o $@ $< $(LIB) $(LDLIBS)

.PHONY: patch-green-check
patch-green-check: $(EXDIR)/write_patch_green
	@tmp=$$(mktemp -d); trap 'rm -rf "$$tmp"' EXIT; \
	    $(EXDIR)/write_patch_green "$$tmp/patch_green.uff" > /dev/null; \
	    if cmp -s "$$tmp/patch_green.uff" data/patch_green.uff; then \
	        echo "greenconv: data/patch_green.uff: regenerated byte for byte by example/write_patch_green.f90"; \
	    else \
	        echo "greenconv: data/patch_green.uff differs from what example/write_patch_green.f90 writes" >&2; exit 1; \
	    fi

$(EXDIR)/omp_threads: example/omp_threads.f90 $(LIB)
	@mkdir -p $(@D)
	$(FC) $(FFLAGS) $(OMPFLAGS) -I$(MODDIR) -J$(@D) -o $@ $< $(LIB) $(LDLIBS)

# ---- C API tests (test/c) ----------------------------------------------------------------
# One C program per behaviour of include/greenconv.h, built against the plain build's static
# library and run from the top folder (they read data/). Each prints one line per check,
# "ok: ..." or "FAIL: ...", and exits non-zero on a failure; `make ctest` ends with the
# checks' "N passed, N failed" line and fails when a check failed or a program crashed.

CTEST_DIR := $(BUILD)/ctest
CTESTS := $(patsubst test/c/%.c,$(CTEST_DIR)/%,$(wildcard test/c/*.c))

.PHONY: ctest
ctest: $(CTESTS)
	@passed=0; failed=0; \
	for program in $(CTESTS); do \
	    echo "C test $${program##*/}"; \
	    if output=$$("$$program" 2>&1); then status=0; else status=$$?; fi; \
	    printf '%s\n' "$$output"; \
	    passed=$$((passed + $$(printf '%s\n' "$$output" | grep -c '^ok: ' || true))); \
	    failed=$$((failed + $$(printf '%s\n' "$$output" | grep -c '^FAIL: ' || true))); \
	    if [ "$$status" -ne 0 ] && ! printf '%s\n' "$$output" | grep -q '^FAIL: '; then \
	        echo "FAIL: $$program exited with status $$status"; failed=$$((failed + 1)); \
	    fi; \
	done; \
	echo "C tests: $$passed passed, $$failed failed"; \
	[ "$$failed" -eq 0 ]

$(CTEST_DIR)/%: test/c/%.c test/c/check.h include/greenconv.h $(LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -Iinclude -o $@ $< $(LIB) $(LDLIBS) $(FORTRAN_RUNTIME)

# ---- two threads ---------------------------------------------------------------------------
# test/threads/two_threads.c: two POSIX threads, each with its own convolvers, build, step,
# are refused (an unknown method 'direc' / 'fftx') and free, THREAD_CALLS API calls in all;
# every status, message and value must be what one thread alone gets. `make thread-test` runs
# TEST_THREAD_CALLS calls, `make thread-stress` STRESS_THREAD_CALLS, `make thread-helgrind`
# HELGRIND_THREAD_CALLS under valgrind's helgrind (any race reported fails; under a minute),
# `make thread-check` all three with the static-length symbol check (tools/check_symbols.sh
# --static-locals). gfortran keeps the length of a deferred-length character function result
# in static storage at each call site, which threads share; the texts on the C doors' paths
# (core/text.f90's numbers, conv/methods.f90's names and lists, api/doors.f90's C strings)
# have specification-length results instead, so `make test` runs the stress and helgrind
# checks. No such call site is left anywhere in the library (`make statics-check`), and `make
# test` runs the static check too.

THREAD_TEST := $(BUILD)/threads/two_threads
TEST_THREAD_CALLS ?= 20000
STRESS_THREAD_CALLS ?= 200000
HELGRIND_THREAD_CALLS ?= 4000
# make test: two threads, 200,000 calls under helgrind (about 10 s).
TEST_HELGRIND_THREAD_CALLS ?= 200000

$(THREAD_TEST): test/threads/two_threads.c test/c/check.h include/greenconv.h $(LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -D_POSIX_C_SOURCE=200809L -pthread -Iinclude -o $@ $< $(LIB) $(LDLIBS) $(FORTRAN_RUNTIME)

# test/threads/two_readers.c: two threads read universal files at once through the C doors
# (a modes file, an FRF identified, a missing file refused), every value and message as with one
# thread. A file may be connected to one Fortran unit at a time ("File already opened in another
# unit" would refuse the second thread to open the same file), so the readers hold the
# critical section greenconv_input_files while a file is open. Not run under
# helgrind: libgomp's critical sections are futex locks helgrind does not see, so it reports
# the accesses they order (and libgfortran's own unit table) as races.
READER_TEST := $(BUILD)/threads/two_readers
READER_ROUNDS ?= 30

$(READER_TEST): test/threads/two_readers.c test/c/check.h include/greenconv.h $(LIB)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -D_POSIX_C_SOURCE=200809L -pthread -Iinclude -o $@ $< $(LIB) $(LDLIBS) $(FORTRAN_RUNTIME)

thread-readers: $(READER_TEST)
	$(READER_TEST) $(READER_ROUNDS)

# test/threads/ident_threads.f90: the maximum-likelihood identification (pyuff's measured beam
# FRF 1, sdypy's accelerance H_51) on one thread, on two and in two host threads: the same poles,
# residues and chi^2 bit for bit (the BLAS/LAPACK calls of ext/lapack.f90 and ident/dense.f90 are
# made serially, `lapack_serial_begin`; before, FRF 1 gave 13 poles on one thread, 11 on two).
IDENT_THREAD_TEST := $(BUILD)/threads/ident_threads

$(IDENT_THREAD_TEST): test/threads/ident_threads.f90 $(LIB)
	@mkdir -p $(@D)
	$(FC) $(FFLAGS) $(OMPFLAGS) -I$(MODDIR) -J$(@D) -o $@ $< $(LIB) $(LDLIBS)

thread-ident: $(IDENT_THREAD_TEST)
	$(IDENT_THREAD_TEST)

thread-test: $(THREAD_TEST)
	$(THREAD_TEST) $(TEST_THREAD_CALLS)

thread-stress: $(THREAD_TEST)
	$(THREAD_TEST) $(STRESS_THREAD_CALLS)

thread-helgrind: $(THREAD_TEST)
	valgrind --tool=helgrind --error-exitcode=99 $(THREAD_TEST) $(HELGRIND_THREAD_CALLS)

thread-check: $(SHLIB)
	@status=0; \
	$(MAKE) statics-check || status=1; \
	$(MAKE) thread-stress || status=1; \
	$(MAKE) thread-helgrind || status=1; \
	exit $$status

# No writable static local in the library's objects (tools/check_statics.sh: each `slen.*`
# and any other static that is not a module variable or an OpenMP critical lock, by file).
# Part of `make test`: 0 are left.
statics-check: $(LIB)
	bash tools/check_statics.sh $(BUILD)/src

# ---- fuzz test of the driver -------------------------------------------------------------

FUZZ := $(BUILD)/greenconv-fuzz
FUZZ_CASES ?= 2000
# make test runs fewer (each of the 12 damage kinds still about 50 times), to stay well under
# 15 minutes; `make fuzz` alone runs FUZZ_CASES.
TEST_FUZZ_CASES ?= 600
FUZZ_SEED ?= 2011

$(FUZZ): fuzz/mutation_mod.f90 fuzz/fuzz_main.f90 $(LIB)
	@mkdir -p $(BUILD)/fuzz
	$(FC) $(FFLAGS) $(OMPFLAGS) -I$(MODDIR) -J$(BUILD)/fuzz -o $@ fuzz/mutation_mod.f90 fuzz/fuzz_main.f90 \
	    $(LIB) $(LDLIBS)

fuzz: $(BIN) $(FUZZ)
	@$(HELPER) fuzz $(BIN) $(FUZZ) $(FUZZ_CASES) $(FUZZ_SEED)

# ---- MPI driver for sweep scenes ---------------------------------------------------------
# build/make/greenconv-mpi: mpi/greenconv_mpi.f90 compiled with Debian's OpenMPI (mpif90)
# against the plain build's library, which itself needs no MPI. `make sweep-test` runs the
# sweep checks (tools/test_sweep.sh: 1 and 2 ranks and the serial driver give the same table,
# resume, a failing variant, variant order); `make sweep-bench` the throughput on 1 and 2 ranks
# ("speed-up 2 ranks / 1 rank = X", beside a control of the machine's capacity) and the cost of
# rerunning a complete sweep ("rerun of a complete sweep = Y of a run").
# As root (CI), mpirun needs OMPI_ALLOW_RUN_AS_ROOT(_CONFIRM), which the scripts set.

MPIFC ?= mpif90
MPIRUN ?= mpirun
export MPIRUN
MPI_BIN := $(BUILD)/greenconv-mpi

.PHONY: mpi sweep-test sweep-bench
mpi: $(MPI_BIN)

$(MPI_BIN): mpi/greenconv_mpi.f90 $(LIB)
	@mkdir -p $(BUILD)/mpi
	$(MPIFC) $(FFLAGS) $(OMPFLAGS) -I$(MODDIR) -J$(BUILD)/mpi -o $@ $< $(LIB) $(LDLIBS)

sweep-test: $(BIN) $(MPI_BIN)
	@bash tools/test_sweep.sh $(BIN) $(MPI_BIN)

sweep-bench: $(MPI_BIN)
	@bash tools/bench_sweep.sh $(MPI_BIN)

# ---- sanitizers and valgrind ---------------------------------------------------------------

SANITIZE_FUZZ ?= 200
TEST_SANITIZE_FUZZ ?= 50

# `make sanitize` is the whole routine run before every submission: both sanitizer builds
# (ASan+UBSan with -fcheck=all at -O1, and -fcheck=all alone at -O0) with SANITIZE_FUZZ fuzz
# cases each, then valgrind on every shipped scene, the examples and the C tests (valgrind takes
# about an hour on two shared cores). CI (.ci/run) runs the first of them, which holds the
# second's checks, on the C tests (every door, the scenes through gc_run_scene) and
# TEST_SANITIZE_FUZZ fuzz cases (`make sanitize-ci`, about 10 minutes) before `make test`; the
# unit tests under it (an instrumented build of every test program, its longest part) are left
# to `make sanitize`.
sanitize:
	@$(MAKE) sanitize-builds
	@$(MAKE) valgrind

sanitize-builds:
	@MAKE="$(MAKE)" $(HELPER) sanitize $(SANITIZE_FUZZ)

sanitize-ci: deps
	@MAKE="$(MAKE)" $(HELPER) sanitize $(TEST_SANITIZE_FUZZ) --no-unit asan

valgrind: $(BIN) $(EXAMPLES) $(CTESTS)
	@$(HELPER) valgrind $(BIN) $(EXAMPLES) $(CTESTS)

# ---- install ---------------------------------------------------------------------------

# PREFIX/bin/greenconv, PREFIX/lib/libgreenconv.{a,so*}, PREFIX/include/greenconv.h, the
# module files in PREFIX/include/greenconv/ and PREFIX/lib/pkgconfig/greenconv.pc, whose
# Cflags serve C (the header) and Fortran (-I for the .mod files) alike.
install: $(LIB) $(SHLIB) $(BIN)
	@$(HELPER) install "$(DESTDIR)" "$(PREFIX)" "$(VERSION)" "$(BUILD)" \
	    "$(strip $(FORTRAN_RUNTIME) $(LDLIBS))"

# ---- API documentation -----------------------------------------------------------------

doc-check:
	@$(HELPER) doc-check $(SRCS)

doc: doc-check
	@$(HELPER) doc

# ---- run the scenes and draw the figures -----------------------------------------------

run: build
	@for scene in $(SCENES); do \
	    echo "greenconv: running $$scene"; \
	    $(FPM) run greenconv --profile $(FPM_PROFILE) -- "$$scene"; \
	done
	@$(MAKE) bench-data
	@$(MAKE) figures

bench: build
	@$(MAKE) bench-data
	@$(MAKE) bench-patch
	@$(MAKE) bench-ident
	@$(MAKE) sweep-bench
	@$(MAKE) bench-figures

# The tables go to a temporary file renamed when complete, like every other output.
bench-data:
	@mkdir -p out/bench
	@echo "greenconv: running the benchmark (about a minute)"
	@mkdir -p build
	@$(CC) -O2 -std=c99 -Wall -Wextra -pedantic bench/anchor/printf_rows.c -o build/printf_rows -lm
	@$(FPM) run --example greenconv-bench --profile $(FPM_PROFILE) | tee out/bench/tables.txt.part
	@mv out/bench/tables.txt.part out/bench/tables.txt
	@$(FPM) build --profile $(FPM_PROFILE) > /dev/null
	@bash bench/driver_output.sh "$$($(FPM) run greenconv --profile $(FPM_PROFILE) --runner echo | tail -1)" \
	    build/printf_rows | tee out/bench/driver_output.txt.part
	@mv out/bench/driver_output.txt.part out/bench/driver_output.txt
	@echo "greenconv: tables saved in out/bench/tables.txt and out/bench/driver_output.txt"

# The implicit patch against the explicit one: the plain build's driver (OpenMP), whole
# processes, so the two methods are timed alike and the 5,000-point run's memory is measured.
.PHONY: bench-patch
bench-patch: lib
	@mkdir -p out/bench
	@echo "greenconv: the implicit patch against the explicit one (a few minutes)"
	@bash bench/patch_cost.sh $(BIN) | tee out/bench/patch_cost.txt.part
	@mv out/bench/patch_cost.txt.part out/bench/patch_cost.txt

# Identification against a peer: greenconv's ML fit and sdypy-EMA's LSCE and LSCF on
# noisy receptances at 0.1, 1 and 3 %, errors in Cramer-Rao standard deviations. The script
# pip-installs sdypy-EMA into build/ident_peer/venv on its first run (needs python3 -m venv and
# PyPI); the Markdown table goes to out/bench/ident_peer.md.
.PHONY: bench-ident
bench-ident: lib
	@mkdir -p out/bench
	@echo "greenconv: identification against sdypy-EMA (about a minute)"
	@python3 bench/ident_peer.py > out/bench/ident_peer.md.part
	@mv out/bench/ident_peer.md.part out/bench/ident_peer.md
	@cat out/bench/ident_peer.md

# `make figures` draws every plot/*.gp (the scenes' after `make run`), `make bench-figures` those
# of the benchmark's data.
figures: DRAW = $(PLOTS)
bench-figures: DRAW = $(BENCH_PLOTS)
figures bench-figures:
	@mkdir -p $(FIGDIR)
	@for script in $(DRAW); do \
	    echo "greenconv: plotting $$script"; \
	    $(GNUPLOT) -e "figdir='$(FIGDIR)'" "$$script"; \
	done
	@echo "greenconv: figures are in $(FIGDIR)/:"; ls -1 $(FIGDIR)/*.png | sed 's/^/    /'

# ---- tests -----------------------------------------------------------------------------

# The plot scripts on a text and a binary run of the shipped scenes: the same figure data
# (gnuplot's `set table`) and the same PNG bytes.
plot-test: $(BIN)
	@bash tools/test_plot_formats.sh $(BIN)

# The plain build and the make-vs-fpm comparison come first, so that the last line
# printed is fpm test's "N passed, N failed" (the helper runs `fpm test` and, when it
# fails, repeats that line after fpm's error messages).
test: deps
	@$(MAKE) layers
	@$(MAKE) links
	@$(MAKE) doc-check
	@$(MAKE) lib
	@bash tools/check_symbols.sh $(LIB) $(SHLIB)
	@$(MAKE) statics-check
	@bash tools/check_version.sh $(BIN)
	@$(HELPER) same-output $(BIN) $(CHECK_SCENES)
	@$(MAKE) examples
	@$(HELPER) examples $(BIN) $(EXAMPLES)
	@$(MAKE) plot-test
	@$(MAKE) ctest
	@$(MAKE) thread-stress
	@$(MAKE) thread-helgrind HELGRIND_THREAD_CALLS=$(TEST_HELGRIND_THREAD_CALLS)
	@$(MAKE) thread-readers
	@$(MAKE) thread-ident
	@MAKE="$(MAKE)" CC="$(CC)" FC="$(FC)" $(HELPER) install-test $(BIN)
	@$(MAKE) fuzz FUZZ_CASES=$(TEST_FUZZ_CASES)
	@$(MAKE) bench-smoke
	@$(MAKE) sweep-test
	@$(MAKE) patch-green-check
	@echo "fpm test"
	@$(HELPER) fpm-test

# The layering of src/ (cheap, so `make test` runs it first), and proof that the check fails
# on a planted violation.
layers:
	@echo "greenconv: layer check (tools/check_layers.sh)"
	@bash tools/check_layers.sh
	@bash tools/test_check_layers.sh

# The Markdown pages' relative links and anchors (README.md, CHANGELOG.md, doc/*.md; a second),
# and proof that the check fails on planted dead links.
links:
	@echo "greenconv: link check (tools/check_links.sh)"
	@bash tools/check_links.sh
	@bash tools/test_check_links.sh

# The benchmark's code lives in bench/, which `fpm test` cannot see: its checks run through
# the benchmark program (fpm's default profile, the build `fpm test` uses).
bench-smoke:
	@echo "greenconv: smoke checks of the benchmark (greenconv-bench --smoke)"
	@$(FPM) run --example greenconv-bench -- --smoke

# ---- clean -----------------------------------------------------------------------------

clean:
	rm -rf build out
