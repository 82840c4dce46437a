# greenconv — top-level Makefile (GNU make).
#
#   make            same as `make lib`
#   make deps       install what is missing: gfortran, LAPACK, BLAS, FFTW3, gnuplot (apt), fpm (pip)
#   make build      deps, then `fpm build --profile release`
#   make lib        plain build with the compiler alone, no fpm: build/make/libgreenconv.a,
#                   module files in build/make/include/, the driver build/make/greenconv
#   make run        deps, build, run every data/*.nml scene, then the benchmark (`make bench`),
#                   then draw every plot/*.gp into out/figures/
#   make bench      deps, build, run the benchmark example greenconv-bench: Tabs. 2-3 and the
#                   targets measured in one run, printed and saved in out/bench/tables.txt, the
#                   data of the speed/accuracy and stability charts in out/bench/, then the figures
#   make figures    only draw plot/*.gp from the existing out/*.dat
#   make test       deps, `make lib`, check that the Makefile-built driver writes the same
#                   output as the fpm-built one, then `fpm test` (its "N passed, N failed"
#                   line is the last line printed)
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
FFLAGS ?= -O2 -g -std=f2018 -Wall -Wextra -Wimplicit-interface -fimplicit-none
LDLIBS ?= -llapack -lblas -lfftw3
AR ?= ar
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
BIN     := $(BUILD)/greenconv
DEPFILE := $(BUILD)/deps.mk

# Every Fortran source under src/ (subfolders too, as fpm does); objects mirror the tree.
SRCS := $(sort $(shell find src -name '*.f90' -o -name '*.F90' 2>/dev/null))
OBJS := $(patsubst %,$(BUILD)/%.o,$(basename $(SRCS)))

SCENES  := $(wildcard data/*.nml)
PLOTS   := $(wildcard plot/*.gp)
FIGDIR  := out/figures
# Scenes whose Makefile-built output is compared with the fpm-built one in `make test`.
CHECK_SCENES ?= data/sdof_sine.nml

.PHONY: all lib deps build run bench bench-data figures test clean

all: lib

# ---- deps ------------------------------------------------------------------------------

deps:
	@$(HELPER) deps

# ---- fpm build -------------------------------------------------------------------------

build: deps
	$(FPM) build --profile $(FPM_PROFILE)

# ---- plain build (no fpm) --------------------------------------------------------------

lib: $(LIB) $(BIN)

$(BUILD)/%.o: %.f90 | $(MODDIR)
	@mkdir -p $(@D)
	$(FC) $(FFLAGS) -J$(MODDIR) -c $< -o $@

$(BUILD)/%.o: %.F90 | $(MODDIR)
	@mkdir -p $(@D)
	$(FC) $(FFLAGS) -J$(MODDIR) -c $< -o $@

$(LIB): $(OBJS)
	@rm -f $@
	$(AR) rcs $@ $^

$(BIN): app/main.f90 $(LIB)
	$(FC) $(FFLAGS) -I$(MODDIR) -o $@ $< $(LIB) $(LDLIBS)

$(MODDIR):
	@mkdir -p $@

# Module dependencies "a.o: b.o" (b.f90 defines a module that a.f90 uses). Regenerated
# when a source changes, and also when a source was added or removed since the last time
# (deps.mk records the list as DEPS_SRCS). Only read for goals that compile.
ifneq ($(filter all lib $(BUILD)/%,$(or $(MAKECMDGOALS),all)),)
-include $(DEPFILE)
endif

$(DEPFILE): $(SRCS) tools/make_helpers.sh $(if $(filter-out $(SRCS),$(DEPS_SRCS))$(filter-out $(DEPS_SRCS),$(SRCS)),FORCE)
	@mkdir -p $(@D)
	@$(HELPER) f90deps $(BUILD) $(SRCS) > $@.tmp && mv $@.tmp $@

.PHONY: FORCE
FORCE:

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
	@$(MAKE) figures

# The tables go to a temporary file renamed when complete, like every other output.
bench-data:
	@mkdir -p out/bench
	@echo "greenconv: running the benchmark (about a minute)"
	@$(FPM) run --example greenconv-bench --profile $(FPM_PROFILE) | tee out/bench/tables.txt.part
	@mv out/bench/tables.txt.part out/bench/tables.txt
	@echo "greenconv: tables saved in out/bench/tables.txt"

figures:
	@mkdir -p $(FIGDIR)
	@for script in $(PLOTS); do \
	    echo "greenconv: plotting $$script"; \
	    $(GNUPLOT) -e "figdir='$(FIGDIR)'" "$$script"; \
	done
	@echo "greenconv: figures are in $(FIGDIR)/:"; ls -1 $(FIGDIR)/*.png | sed 's/^/    /'

# ---- tests -----------------------------------------------------------------------------

# The plain build and the make-vs-fpm comparison come first, so that the last line
# printed is fpm test's "N passed, N failed" (the helper runs `fpm test` and, when it
# fails, repeats that line after fpm's error messages).
test: deps
	@$(MAKE) lib
	@$(HELPER) same-output $(BIN) $(CHECK_SCENES)
	@echo "fpm test"
	@$(HELPER) fpm-test

# ---- clean -----------------------------------------------------------------------------

clean:
	rm -rf build out
