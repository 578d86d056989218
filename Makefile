# offbench - build, test, run.  See README.md and docs/.
#   make            build ./offbench
#   make test       build and run every test; last line "N passed, N failed"
#   make run        the default job on the embedded data, into out/run
#   make tables     reproduce the published tables into results/, plots, results/TABLES.md
#   make docs       the generated parts of README.md and docs/: contents, command reference,
#                   the figures quoted from the committed results (scripts/docs.py)
#   make nightly    the nightly run: quality against results/baseline/, timing against this
#                   machine's baseline (report and status in out/nightly; make exits 2 on 1, 2 or 3)
#   make accept-baseline  the nightly run just made becomes this machine's timing baseline
#   make accept-committed-baseline  ... becomes the committed baseline results/baseline/
#   make nightly-wall  results/baseline/nightly_wall.txt (the stages' wall time, make docs
#                   quotes it) from the night in out/nightly (NIGHTLY_OUT=DIR)
#   make report     the HTML report of the nightly history (out/history/site/index.html)
#   make report-screenshot  results/report.png from the test's synthetic history (Chromium)
#   make SAN=1 test the same under ASan + UBSan (objects in build-san/)
#   make perf       scaling checks that compare times (readers linear in their input)
#   make MPI=1      ./offbench built with Open MPI (mpirun -n P ./offbench run ...)
#   make fuzz       libFuzzer on the curve-file, compare and resume readers (clang; FUZZ_SECONDS each)
#   make deps       check for (and, as root with apt-get, install) what the build needs
#   make check-method M=NAME  the method contract (methods/CONTRACT.md) on one method
#                   (an external one with EXTERNAL='NAME=COMMAND' or
#                   METHODS_FILE=methods/cad.methods)
#   make lib        build/liboffbench.so (the C API, include/offbench.h) and
#                   build/offbench-sisl-server (the sisl method's server for it)
#   make man        the manual page, build/offbench.1, from the commands' --help
#   make install PREFIX=/usr/local [DESTDIR=]  the program, its manual page, the
#                   bash and zsh completions, liboffbench (lib/, include/offbench.h,
#                   lib/offbench/offbench-sisl-server) (make uninstall removes them)
#   make occt-example  OpenCASCADE's offsets beside offbench's methods, one table
#                   (docs/cad-example.md; Debian's libocct-foundation-dev,
#                   libocct-modeling-data-dev and g++), into out/occt
#   make occt-worker   build/occt_worker: OpenCASCADE as an external method
#                   (--external occt=build/occt_worker; the same packages)
#   make lib2geom-worker  build/lib2geom_worker: lib2geom's offset as an
#                   external method (Debian's lib2geom-dev and g++)

CC      ?= gcc
SAN     ?= 0
OPT     ?= -O2
# -fPIC: the same objects make ./offbench and build/liboffbench.so (make lib);
# the default job's rows are identical with and without it (scripts/same_rows.py)
CFLAGS_COMMON = -std=c11 -g -Wall -Wextra -Wshadow -fopenmp -fPIC -D_POSIX_C_SOURCE=200809L
ifeq ($(MPI),1)
  # mpirun -n P ./offbench run ...: Open MPI (mpicc), objects in build-mpi/
  CC      := mpicc
  BUILD   := build-mpi
  SANFLAGS := -DOB_MPI
  BIN     := offbench
else ifeq ($(SAN),fuzz)
  # libFuzzer targets (make fuzz): clang, ASan + UBSan, objects in build-fuzz/
  BUILD   := build-fuzz
  OPT     := -O1
  SANFLAGS := -fsanitize=address,undefined,fuzzer-no-link -fno-omit-frame-pointer
  BIN     := $(BUILD)/offbench
else ifeq ($(SAN),1)
  BUILD   := build-san
  OPT     := -O1
  SANFLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
  BIN     := $(BUILD)/offbench
else
  BUILD   := build
  SANFLAGS :=
  BIN     := offbench
endif
CFLAGS  += $(CFLAGS_COMMON) $(OPT) $(SANFLAGS)
LDFLAGS += -fopenmp $(SANFLAGS)
LDLIBS  += -lsisl -lflint -lgmp -lexpat -lnettle -lm -ldl

LIB_SRC  := $(sort $(wildcard methods/*.c methods/*/*.c) $(filter-out host/main.c host/lib/sisl_server_main.c,$(wildcard host/*.c host/*/*.c)))
LIB_OBJ  := $(patsubst %.c,$(BUILD)/%.o,$(LIB_SRC)) $(BUILD)/embedded_data.o $(BUILD)/embedded_kernels.o \
            $(BUILD)/embedded_published.o
TEST_SRC := $(sort $(wildcard tests/*/test_*.c))
TEST_BIN := $(patsubst tests/%.c,$(BUILD)/tests/%,$(TEST_SRC))
TEST_SH  := $(sort $(wildcard tests/e2e/e2e_*.sh))
DATASETS := $(sort $(wildcard datasets/*.curves))
KERNELS  := kernels/metric_core.h kernels/measure.cl
PUBLISHED := results/published/published_tables.csv results/published/offset_atlas.csv

.PHONY: all test perf soak run deps clean bench tables docs nightly accept-baseline accept-committed-baseline nightly-wall report \
        report-screenshot fuzz fuzz-run check-method man lib install uninstall occt-bin occt-worker occt-trimmed occt-example lib2geom-worker FORCE
all: $(BIN)

$(BUILD)/.deps-ok: scripts/deps.sh
	@MPI=$(MPI) sh scripts/deps.sh
	@mkdir -p $(BUILD) && touch $@

deps:
	@MPI=$(MPI) sh scripts/deps.sh

# Build facts recorded in meta.json; rewritten only when they change.
$(BUILD)/buildinfo.h: FORCE
	@mkdir -p $(BUILD)
	@{ echo "#define OB_GIT_COMMIT \"$$(git rev-parse --verify -q HEAD 2>/dev/null || echo unknown)\""; \
	   echo "#define OB_GIT_DIRTY $$(if git diff --quiet HEAD -- 2>/dev/null; then echo 0; else echo 1; fi)"; \
	   echo "#define OB_CFLAGS \"$(strip $(CFLAGS))\""; \
	   printf '#define OB_DATASETS_DIR "%s"\n' "$$(printf '%s' '$(CURDIR)/datasets' | sed 's/[\\"]/\\&/g')"; \
	   echo "#define OB_GIT_DATE \"$$(git log -1 --format=%cd --date=format:%Y.%m.%d 2>/dev/null || echo unknown)\""; \
	   for p in SISL:libsisl-dev FLINT:libflint-dev OCL_ICD:ocl-icd-libopencl1; do \
	     echo "#define OB_PKG_$${p%%:*} \"$$(dpkg-query -W -f='$${Version}' $${p#*:} 2>/dev/null | head -n 1 | tr -d '"\\' || true)\""; \
	   done; } > $@.tmp
	@cmp -s $@.tmp $@ && rm -f $@.tmp || mv $@.tmp $@

$(BUILD)/embedded_data.c: $(DATASETS) scripts/embed_data.sh
	@mkdir -p $(BUILD)
	sh scripts/embed_data.sh ob_embedded_files $(DATASETS) > $@

$(BUILD)/embedded_published.c: $(PUBLISHED) scripts/embed_data.sh
	@mkdir -p $(BUILD)
	sh scripts/embed_data.sh ob_embedded_published $(PUBLISHED) > $@

$(BUILD)/embedded_kernels.c: $(KERNELS) scripts/embed_data.sh
	@mkdir -p $(BUILD)
	sh scripts/embed_data.sh ob_embedded_kernels $(KERNELS) > $@

# The compiler flags the objects were built with: a change (such as -fPIC,
# which the shared library needs) rebuilds them all
$(BUILD)/.cflags: FORCE
	@mkdir -p $(BUILD)
	@echo '$(CC) $(CFLAGS)' > $@.tmp; cmp -s $@.tmp $@ && rm -f $@.tmp || mv $@.tmp $@

$(BUILD)/%.o: %.c $(BUILD)/.deps-ok $(BUILD)/.cflags
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -MMD -MP -I. -I$(BUILD) -c $< -o $@

# The metric core's lane loops (kernels/metric_core.h, OBC_SIMD) hold sqrt:
# without errno to set, it is one instruction and the loops vectorize.  Not a
# fast-math flag: every result keeps its bits
# (private: not passed on to prerequisites; the test compiles the core too).
$(BUILD)/methods/metrics/metric_sampled.o: private CFLAGS += -fno-math-errno
$(BUILD)/tests/unit/test_table_lanes: private CFLAGS += -fno-math-errno

$(BUILD)/embedded_%.o: $(BUILD)/embedded_%.c
	$(CC) $(CFLAGS) -c $< -o $@

$(BUILD)/host/io/output.o $(BUILD)/host/run/journal.o $(BUILD)/host/main.o $(BUILD)/host/io/export_dir.o: $(BUILD)/buildinfo.h

$(BUILD)/libob.a: $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

# liboffbench (include/offbench.h): the library's objects as one shared
# library exporting only obx_* (host/lib/offbench.map), SONAME
# liboffbench.so.MAJOR; and the program sisl's fits run in when the library
# is loaded by a program that does not link the method (python):
# host/lib/sisl_exe.h.  The method's object is named so that its
# constructor, which serves, is linked.
OBX_VER  := $(shell sed -n 's/^\#define OBX_VERSION "\(.*\)"/\1/p' include/offbench.h)
OBX_SO   := $(BUILD)/liboffbench.so.$(OBX_VER)
OBX_SONAME := liboffbench.so.$(firstword $(subst ., ,$(OBX_VER)))
lib: $(BUILD)/liboffbench.so $(BUILD)/offbench-sisl-server

$(OBX_SO): $(LIB_OBJ) host/lib/offbench.map
	$(CC) -shared -Wl,-soname,$(OBX_SONAME) -Wl,--version-script=host/lib/offbench.map $(LDFLAGS) \
	    -o $@ $(LIB_OBJ) $(LDLIBS)

$(BUILD)/liboffbench.so: $(OBX_SO)
	ln -sf $(notdir $(OBX_SO)) $(BUILD)/$(OBX_SONAME)
	ln -sf $(OBX_SONAME) $@

# the server (its constructor serves: methods/sisl/server.c) and SISL
$(BUILD)/offbench-sisl-server: $(BUILD)/host/lib/sisl_server_main.o $(BUILD)/methods/sisl/server.o $(BUILD)/libob.a
	$(CC) $(LDFLAGS) -o $@ $(filter %.o %.a,$^) $(LDLIBS)

# test_api links the shared library, as a user would
$(BUILD)/tests/unit/test_api: tests/unit/test_api.c include/offbench.h $(BUILD)/liboffbench.so \
                              $(BUILD)/offbench-sisl-server tests/check.h $(BIN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -I. -o $@ $< -L$(BUILD) -loffbench -Wl,-rpath,$(abspath $(BUILD)) $(LDFLAGS)

# ./offbench is built with or without MPI: relink when that changes
.offbench-flavor: FORCE
	@echo "$(BUILD)" > $@.tmp; cmp -s $@.tmp $@ && rm -f $@.tmp || mv $@.tmp $@

$(BIN): $(BUILD)/host/main.o $(BUILD)/libob.a $(if $(filter offbench,$(BIN)),.offbench-flavor)
	$(CC) $(LDFLAGS) -o $@ $(filter %.o %.a,$^) $(LDLIBS)

$(BUILD)/tests/%: tests/%.c $(BUILD)/libob.a tests/check.h tests/testlib.h host/san_options.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -I. -o $@ $< $(BUILD)/libob.a $(LDFLAGS) $(LDLIBS)

test: $(BIN) $(TEST_BIN)
	@OFFBENCH=$(abspath $(BIN)) sh tests/run_all.sh $(TEST_BIN) $(TEST_SH)

# The method contract's broken test methods (not in the library)
$(BUILD)/tests/methods/test_methods: tests/methods/contract_fixtures.h

# The method contract (methods/CONTRACT.md) on one method: a registered one,
# template (methods/TEMPLATE.c) or a fixture of
# tests/methods/contract_fixtures.h.  Failures name the rule and what to do.
check-method: $(BUILD)/tests/methods/test_methods
	@if [ -z "$(M)" ]; then \
	    echo "usage: make check-method M=NAME (a name from ./offbench list methods, or template)" >&2; exit 2; fi
	@$(BUILD)/tests/methods/test_methods $(if $(EXTERNAL),--external '$(EXTERNAL)') \
	    $(if $(METHODS_FILE),--methods-file '$(METHODS_FILE)') --method '$(M)'

# The manual page, generated from the program's own --help (scripts/manpage.sh).
MAN := $(BUILD)/offbench.1
man: $(MAN)

$(MAN): $(BIN) scripts/manpage.sh
	sh scripts/manpage.sh ./$(BIN) > $@.tmp && mv $@.tmp $@

# make install PREFIX=... DESTDIR=...: the program (with its data and kernels
# built in), the manual page and the shell completions; and the library
# (make lib): liboffbench.so.VERSION with its SONAME and .so links, its
# header, and the sisl method's server in LIBDIR/offbench/, where the
# library looks for it (host/lib/sisl_exe.h).  scripts/install.sh does the
# work, every path quoted (a PREFIX may hold spaces or glob characters; the
# paths reach it through the environment, never through a command line):
# install writes each file's path to the manifest
# PREFIX/share/offbench/install-manifest.txt, and make uninstall removes
# exactly the files it lists, then the manifest (directories are left;
# without a manifest it removes nothing).  The loader finds the library
# by name in a PREFIX outside its default directories only after ldconfig
# (or with LD_LIBRARY_PATH; python: OFFBENCH_LIB), docs/python.md.
PREFIX      ?= /usr/local
BINDIR      := $(PREFIX)/bin
MAN1DIR     := $(PREFIX)/share/man/man1
BASHCOMPDIR := $(PREFIX)/share/bash-completion/completions
ZSHCOMPDIR  := $(PREFIX)/share/zsh/site-functions
LIBDIR      := $(PREFIX)/lib
INCLUDEDIR  := $(PREFIX)/include
LIBEXECDIR  := $(LIBDIR)/offbench
MANIFEST    := $(PREFIX)/share/offbench/install-manifest.txt

install uninstall: export OB_DESTDIR = $(DESTDIR)
install uninstall: export OB_MANIFEST = $(MANIFEST)
install: export OB_BINDIR = $(BINDIR)
install: export OB_MAN1DIR = $(MAN1DIR)
install: export OB_BASHCOMPDIR = $(BASHCOMPDIR)
install: export OB_ZSHCOMPDIR = $(ZSHCOMPDIR)
install: export OB_LIBDIR = $(LIBDIR)
install: export OB_INCLUDEDIR = $(INCLUDEDIR)
install: export OB_LIBEXECDIR = $(LIBEXECDIR)
install: export OB_BIN = $(BIN)
install: export OB_MAN = $(MAN)
install: export OB_SO = $(OBX_SO)
install: export OB_SONAME = $(OBX_SONAME)
install: export OB_SISL_SERVER = $(BUILD)/offbench-sisl-server

install: $(BIN) $(MAN) lib
	sh scripts/install.sh install

uninstall:
	sh scripts/install.sh uninstall

# Scaling checks that compare times (not in `make test`: the machines are
# shared): each reader is linear in its input (tests/perf/perf_linear.c).
perf: $(BUILD)/tests/perf/perf_linear
	@$(BUILD)/tests/perf/perf_linear

# The soak test, longer than in `make test` (docs/contributing.md "Testing").
SOAK_KILLS ?= 200
SOAK_RUN   ?= --random 40:5 --methods tiller,cobb,ahn,zhao,lee --tols 1e-2,1e-3,1e-4 --backend cpu
soak: $(BIN)
	@OFFBENCH=$(abspath $(BIN)) SOAK_KILLS=$(SOAK_KILLS) SOAK_RUN="$(SOAK_RUN)" $(if $(SOAK_SEED),SOAK_SEED=$(SOAK_SEED)) SOAK_VERBOSE=1 sh tests/e2e/e2e_soak.sh

run: $(BIN)
	./$(BIN) run --out out/run --force
	@echo "wrote out/run/results.csv and out/run/meta.json"

# The published tables, cell by cell, their plots, and the section of
# results/TABLES.md generated from them (needs Debian's python3-matplotlib for the plots).
tables: $(BIN)
	./$(BIN) tables --certify=tight --out results/tables
	/usr/bin/python3 scripts/plot_tables.py results/tables/tables.csv results/plots
	/usr/bin/python3 scripts/readme_tables.py results/tables/tables.md results/TABLES.md

# The generated parts of README.md, docs/*.md and results/TABLES.md: each
# docs file's contents, the command reference (each command's --help) and
# the figures read from the committed results under results/ (the nightly
# baseline, results/tables/, results/docs/); tests/e2e/e2e_docs.sh fails
# when they are not current.
docs: $(BIN)
	/usr/bin/python3 scripts/docs.py --offbench $(abspath $(BIN))

bench: $(BIN)
	./$(BIN) bench --out out/bench

# The CAD-kernel example (docs/cad-example.md): examples/occt/occt_offset.cpp
# against OpenCASCADE (C++, so not part of the C build; nothing else needs
# it), then scripts/occt_table.py: OCCT's offsets measured and put beside
# offbench's methods in out/occt/table.md.  OCCT_INC and OCCT_BIN move the
# headers and the program (tests/e2e/e2e_occt.sh builds into its scratch).
OCCT_INC  ?= /usr/include/opencascade
OCCT_BIN  ?= $(BUILD)/occt_offset
OCCT_LIBS := -lTKernel -lTKMath -lTKG2d -lTKGeomBase
# The external-method worker (examples/occt/occt_worker.cpp,
# docs/external-methods.md): the same headers and libraries; OCCT_WORKER
# moves it (tests/e2e/e2e_occt_method.sh builds into its scratch)
OCCT_WORKER ?= $(BUILD)/occt_worker
# both programs: stop naming the packages when the headers are missing
define occt_cxx
	@test -f '$(OCCT_INC)/Geom2d_OffsetCurve.hxx' || { \
	    echo "$(notdir $@): OpenCASCADE's headers are not in $(OCCT_INC):" \
	         "install Debian's libocct-foundation-dev and libocct-modeling-data-dev" \
	         "(sudo apt-get install libocct-foundation-dev libocct-modeling-data-dev g++)" >&2; exit 1; }
	@mkdir -p $(dir $@)
	$(CXX) -std=c++17 -O2 -Wall -Wextra -isystem '$(OCCT_INC)' -o $@ $< $(OCCT_LIBS)
endef
occt-bin: $(OCCT_BIN)
occt-worker: $(OCCT_WORKER)
# OCCT's trimmed offset (examples/occt/occt_trimmed.cpp, for measure
# --trimmed): BRepOffsetAPI_MakeOffset, in Debian's
# libocct-modeling-algorithms-dev besides the packages above
OCCT_TRIMMED ?= $(BUILD)/occt_trimmed
occt-trimmed: $(OCCT_TRIMMED)

$(OCCT_TRIMMED): examples/occt/occt_trimmed.cpp
	@test -f '$(OCCT_INC)/BRepOffsetAPI_MakeOffset.hxx' || { \
	    echo "$(notdir $@): OpenCASCADE's offset algorithms are not in $(OCCT_INC):" \
	         "install Debian's libocct-modeling-algorithms-dev" \
	         "(sudo apt-get install libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev g++)" >&2; exit 1; }
	@mkdir -p $(dir $@)
	$(CXX) -std=c++17 -O2 -Wall -Wextra -isystem '$(OCCT_INC)' -o $@ $< $(OCCT_LIBS) -lTKG3d -lTKBRep -lTKTopAlgo \
	    -lTKGeomAlgo -lTKOffset

$(OCCT_BIN): examples/occt/occt_offset.cpp examples/occt/occt_common.hpp
	$(occt_cxx)

$(OCCT_WORKER): examples/occt/occt_worker.cpp examples/occt/occt_common.hpp examples/workers/protocol.hpp
	$(occt_cxx)

# The graphics library's offset as an external method
# (examples/lib2geom/lib2geom_worker.cpp, docs/cad-example.md): Debian's
# lib2geom-dev (found by pkg-config) and g++; LIB2GEOM_WORKER moves it.
LIB2GEOM_WORKER ?= $(BUILD)/lib2geom_worker
lib2geom-worker: $(LIB2GEOM_WORKER)

$(LIB2GEOM_WORKER): examples/lib2geom/lib2geom_worker.cpp examples/workers/protocol.hpp
	@pkg-config --exists 2geom 2>/dev/null || { \
	    echo "$(notdir $@): lib2geom is not installed (pkg-config finds no 2geom):" \
	         "install Debian's lib2geom-dev (sudo apt-get install lib2geom-dev g++)" >&2; exit 1; }
	@mkdir -p $(dir $@)
	$(CXX) -std=c++17 -O2 -Wall -Wextra $$(pkg-config --cflags 2geom | sed 's/-I/-isystem /g') \
	    -DLIB2GEOM_VERSION='"'"$$(pkg-config --modversion 2geom)"'"' -o $@ $< $$(pkg-config --libs 2geom)

occt-example: $(OCCT_BIN) $(BIN)
	/usr/bin/python3 scripts/occt_table.py --offbench ./$(BIN) --occt $(OCCT_BIN) --out out/occt

# The nightly regression run (docs/nightly.md "Nightly regression runs").  Its
# status, 0 no regression, 1 regression, 2 error, 3 not comparable, is
# printed and written to out/nightly/status; make itself can only exit 0 or
# 2 (any failing recipe is make's exit 2), so CI runs scripts/nightly.sh
# directly, or reads out/nightly/status after `make nightly`.
nightly:
	@sh scripts/nightly.sh --out out/nightly; s=$$?; \
	  echo "make nightly: scripts/nightly.sh exited $$s (0 no regression, 1 regression, 2 error, 3 not comparable; in out/nightly/status too)$$([ $$s -eq 0 ] || echo '; make exits 2 for it')" >&2; \
	  exit $$s

# Accepting on purpose, without running again: the run `make nightly` just
# made becomes this machine's timing baseline (kept outside the repository:
# scripts/nightly.sh --help), or the committed baseline results/baseline/
# (then review and commit it).
accept-baseline:
	sh scripts/nightly.sh --accept --out out/nightly

accept-committed-baseline:
	sh scripts/nightly.sh --accept-committed --out out/nightly

# How long the night just made took, stage by stage, for docs/nightly.md
# (make docs quotes the file): regenerate it from a full night.
NIGHTLY_OUT ?= out/nightly
nightly-wall:
	/usr/bin/python3 scripts/nightly_wall.py $(NIGHTLY_OUT) --out results/baseline/nightly_wall.txt

# The nightly history's HTML report (nightly.sh rebuilds it after each run;
# NIGHTLY_HISTORY as there), and the screenshot of it in docs/nightly.md.
NIGHTLY_HISTORY ?= out/history
report:
	/usr/bin/python3 scripts/report.py $(NIGHTLY_HISTORY) --out $(NIGHTLY_HISTORY)/site

report-screenshot: $(BIN)
	sh scripts/report_screenshot.sh $(abspath $(BIN)) results/report.png

# Fuzzing (needs clang with libFuzzer: Debian's clang): each target runs
# FUZZ_SECONDS (default 60) from its seed corpus; a crash stops it, leaves
# build-fuzz/crash-* and fails the target.  New corpus entries stay in
# build-fuzz/corpus-*; the seeds are in tests/.
FUZZ_SECONDS ?= 60
FUZZ_TARGETS := curves compare journal
FUZZ_SEEDS_curves := tests/data/bad_curves datasets
FUZZ_SEEDS_compare := tests/fuzz/seeds_compare tests/data/bad_compare
FUZZ_SEEDS_journal := tests/fuzz/seeds_journal
FUZZ_DICT_curves := -dict=tests/fuzz/curves.dict

fuzz:
	$(MAKE) SAN=fuzz CC=clang fuzz-run

fuzz-run: $(patsubst %,$(BUILD)/fuzz/fuzz_%,$(FUZZ_TARGETS))
	@for t in $(FUZZ_TARGETS); do \
	    mkdir -p $(BUILD)/corpus-$$t; \
	    echo "fuzz: $$t for $(FUZZ_SECONDS) s"; \
	    seeds=""; dict=""; \
	    case $$t in curves) seeds="$(FUZZ_SEEDS_curves)"; dict="$(FUZZ_DICT_curves)";; \
	                compare) seeds="$(FUZZ_SEEDS_compare)";; \
	                journal) seeds="$(FUZZ_SEEDS_journal)";; esac; \
	    $(BUILD)/fuzz/fuzz_$$t $$dict -max_total_time=$(FUZZ_SECONDS) -max_len=65536 -print_final_stats=1 \
	        -artifact_prefix=$(BUILD)/crash-$$t- $(BUILD)/corpus-$$t $$seeds > $(BUILD)/fuzz-$$t.log 2>&1 \
	        || { tail -n 40 $(BUILD)/fuzz-$$t.log; echo "fuzz: $$t FAILED (see $(BUILD)/fuzz-$$t.log)"; exit 1; }; \
	    grep -E "stat::number_of_executed_units|stat::new_units_added" $(BUILD)/fuzz-$$t.log | sed "s/^/fuzz: $$t: /"; \
	done

$(BUILD)/fuzz/fuzz_%: tests/fuzz/fuzz_%.c $(BUILD)/libob.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -fsanitize=fuzzer -I. -o $@ $< $(BUILD)/libob.a $(LDFLAGS) $(LDLIBS)

clean:
	rm -rf build build-san build-fuzz build-mpi offbench out .offbench-flavor

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
