# Quick start: `make render` and `make test` work on a fresh Debian 12 machine.
# Both install only the Debian packages that are missing, then build Release.
BUILD ?= build
JOBS ?= 2
SHOWCASE ?= scenes/showcase.json
OUT ?= out
PKGS := cmake ninja-build g++ pkg-config libtbb-dev libembree-dev libglm-dev \
        libopenimageio-dev openimageio-tools libnanoflann-dev libbenchmark-dev \
        libgtest-dev nlohmann-json3-dev libcli11-dev libtinyobjloader-dev libtinygltf-dev libfmt-dev zlib1g-dev libpng-dev libopenexr-dev \
        libopenvdb-dev python3-openvdb fonts-dejavu-core python3 python3-matplotlib
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: all deps configure build renderer render test test-fast bench bench-startup scaling bench-profile gallery gallery-docs \
        convergence clean san-deps fuzz test-asan test-tsan test-slurm bench-farm
all: build

# Installs those of the packages in $(1) that are missing.
define install_missing
	@missing=$$(for p in $(1); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'install ok installed' || echo $$p; \
	done); \
	if [ -n "$$missing" ]; then \
	  echo "Installing missing packages:" $$missing; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; \
	fi
endef

deps:
	$(call install_missing,$(PKGS))

$(BUILD)/build.ninja: CMakeLists.txt | deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release

configure: deps $(BUILD)/build.ninja

build: configure
	cmake --build $(BUILD) -j $(JOBS)

renderer: configure
	cmake --build $(BUILD) -j $(JOBS) --target penumbra

render: renderer
	@mkdir -p $(OUT)
	$(BUILD)/penumbra render $(SHOWCASE) -o $(OUT)/showcase.png
	@echo "Image written to $(abspath $(OUT)/showcase.png)"

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The stage tests only (label unit, tests/CMakeLists.txt): seconds, not minutes.
test-fast: build
	cd $(BUILD) && ctest -L unit -j $(JOBS) --output-on-failure

# A jobs file on a real single-node Slurm cluster (docs/TESTING.md): installs Debian's slurm-wlm
# and munge when missing, starts private munged/slurmctld/slurmd daemons, stops them by PID.
test-slurm: renderer
	tests/farm/test_slurm.sh $(BUILD)/penumbra

# CPU seconds of each of 4 shards against one process (docs/PERFORMANCE.md, "Farm balance").
bench-farm: renderer
	scripts/farm/bench_farm.sh $(BUILD)/penumbra

# Benchmark suite (docs/PERFORMANCE.md, "Benchmark suite and 1-vs-2-core scaling"): each
# executable writes Google Benchmark JSON to $(BENCH_OUT)/NAME.json and its console output to
# NAME.log; the tables are printed from the JSON. A few minutes in all. Results stay out of
# the checkout (the cache folder `penumbra bench` writes its JSON to by default).
BENCH_OUT ?= $(or $(XDG_CACHE_HOME),$(HOME)/.cache)/penumbra/bench
GATHER_FILTER := (Knn50|Classify)/1M/.*morton:1/leaf:48/threads:[12]/shuffled:0
# Three repetitions with 1- and 2-thread runs interleaved; the tables take the fastest.
BENCH_REPS ?= 3
define run_bench
	@mkdir -p $(BENCH_OUT)
	@echo "== $(1) $(2)"
	@$(BUILD)/bench/$(1) --benchmark_out=$(BENCH_OUT)/$(1).json --benchmark_out_format=json \
	  --benchmark_repetitions=$(BENCH_REPS) --benchmark_enable_random_interleaving=true $(2) \
	  > $(BENCH_OUT)/$(1).log 2>&1 || { tail -n 20 $(BENCH_OUT)/$(1).log; exit 1; }
endef

bench: build
	$(call run_bench,bench_rays,)
	$(call run_bench,bench_photons,)
	$(call run_bench,bench_gather,--benchmark_filter='$(GATHER_FILTER)')
	$(call run_bench,bench_render,--benchmark_filter='BM_(Scene|Control)')
	$(call run_bench,bench_load,)
	$(call run_bench,bench_gate,--benchmark_repetitions=1)
	@scripts/bench_table.py bench $(BENCH_OUT)
	@echo "JSON and logs in $(BENCH_OUT)"

# Start-up: --version, plan and check of fig03, 20 runs each, median wall and CPU seconds;
# OLD=path/to/penumbra runs an older binary in turns with this one.
bench-startup: renderer
	scripts/bench_startup.py $(BUILD)/penumbra $(OLD)

# Per scene and stage (stats.time.* through runRender), 1 and 2 threads, and the speed-up.
scaling: build
	$(call run_bench,bench_photons,)
	$(call run_bench,bench_render,--benchmark_filter='BM_(Scene|Control)')
	@scripts/bench_table.py scaling $(BENCH_OUT)
	@echo "JSON and logs in $(BENCH_OUT)"

# Share of each benchmarked render's time inside Embree and nanoflann (perf samples),
# against the libraries' raw rates on the same rays and points (about 3 minutes).
bench-profile: build
	scripts/profile_render.py $(BUILD) $(BENCH_OUT)/profile

# Writes only into out/gallery; gallery-docs also refreshes the images and table in docs/.
gallery: renderer
	scripts/gallery.sh $(BUILD)/penumbra $(OUT)/gallery

gallery-docs: renderer
	scripts/gallery.sh $(BUILD)/penumbra $(OUT)/gallery --docs

# Error against time of the physical model on the convergence scene (docs/PERFORMANCE.md).
convergence: renderer
	scripts/convergence.py $(BUILD)/penumbra scenes/cornell_physical.json $(OUT)/convergence

clean:
	rm -rf $(BUILD) $(OUT) $(FUZZ_BUILD) $(ASAN_BUILD) $(TSAN_BUILD)

# ---- Sanitizers and fuzzing (docs/TESTING.md). Clang builds in their own
# folders; only these targets need SAN_PKGS.
SAN_PKGS := clang libclang-rt-14-dev
CLANG_CXX ?= clang++
FUZZ_BUILD ?= build-fuzz
ASAN_BUILD ?= build-asan
TSAN_BUILD ?= build-tsan
# Debian's oneTBB rebuilt with ThreadSanitizer (fuzz/sanitizers/build_tsan_tbb.sh).
TSAN_TBB ?= $(TSAN_BUILD)/tbb
# Seconds per fuzz target. Inputs up to FUZZ_MAX_LEN bytes (the largest shipped
# scene is 3.6 kB); one input taking FUZZ_TIMEOUT s is a hang finding.
FUZZ_SECONDS ?= 60
FUZZ_MAX_LEN ?= 8192
# A .vdb's smallest tree (one 8^3 leaf under OpenVDB's 32^3 and 16^3 nodes) is ~10 kB.
FUZZ_VDB_MAX_LEN ?= 32768
FUZZ_TIMEOUT ?= 10
FUZZ_RSS_MB ?= 2048
# Every fuzz/fuzz_*.cpp is a target, with seeds in fuzz/corpus/<target>/ and an
# optional fuzz/dict/<target>.dict. fuzz_vdb_reader's inputs reach OpenVDB in the
# reader process (core/density_codec.h), which ends a hang at its deadline of 30 s and
# more for a large file: that target's timeout lies beyond it, so a refusal after the
# deadline is no finding.
FUZZ_TARGETS ?= $(patsubst fuzz/%.cpp,%,$(wildcard fuzz/fuzz_*.cpp))
FUZZ_VDB_FLAGS = -timeout=60
# Stop at the first report, with a symbolised stack; leak checking stays on.
# new_delete_type_mismatch=0: that check sees only sized deletes, which clang 14
# does not emit (no -fsized-deallocation by default), so it can fire only inside
# g++-built libraries; it does in OpenImageIO 2.4's TextureSystem::destroy
# (allocated 184 bytes, deleted as 1), which every texture test reaches.
SAN_ENV := ASAN_OPTIONS=halt_on_error=1:abort_on_error=1:detect_leaks=1:check_initialization_order=1:strict_init_order=1:new_delete_type_mismatch=0 \
           UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
           TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1:suppressions=$(CURDIR)/fuzz/sanitizers/tsan.supp
# The tests of tests/test_pipeline_determinism.cpp, read from the file so a new
# one is picked up: "^(Determinism.RunRender...|Cli.HelpExitsWithZero|...)$$", and the
# lookup cache's lock-free lazy cells asked from every thread at once.
TSAN_TESTS := ^($(shell sed -n 's/^TEST(\([A-Za-z0-9_]*\), *\([A-Za-z0-9_]*\)).*/\1.\2/p' \
                tests/test_pipeline_determinism.cpp | paste -sd'|')|LookupCache.APointWithNoCellNearGetsItsOwnCellsEstimateOnceForEveryThread)$$
SAN_CMAKE := -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=$(CLANG_CXX)

san-deps: deps
	$(call install_missing,$(SAN_PKGS))

# Each target runs FUZZ_SECONDS on a scratch copy of its seeds, so the tree stays
# clean; new inputs, logs and crash artifacts stay under $(FUZZ_BUILD)/.
fuzz: san-deps
	cmake -S . -B $(FUZZ_BUILD) $(SAN_CMAKE) -DPENUMBRA_FUZZ=ON
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_all
	@set -e; for t in $(FUZZ_TARGETS); do \
	  work=$(FUZZ_BUILD)/run/$$t; rm -rf $$work; mkdir -p $$work/corpus $$work/artifacts; \
	  cp fuzz/corpus/$$t/* $$work/corpus/; \
	  dict=; [ -f fuzz/dict/$$t.dict ] && dict=-dict=fuzz/dict/$$t.dict; \
	  len=$(FUZZ_MAX_LEN); own_flags=; \
	  if [ $$t = fuzz_vdb_reader ]; then len=$(FUZZ_VDB_MAX_LEN); own_flags="$(FUZZ_VDB_FLAGS)"; fi; \
	  echo "== $$t: $(FUZZ_SECONDS) s, log $$work/log.txt"; \
	  if $(SAN_ENV) $(FUZZ_BUILD)/fuzz/$$t -max_total_time=$(FUZZ_SECONDS) \
	       -max_len=$$len -timeout=$(FUZZ_TIMEOUT) $$own_flags -rss_limit_mb=$(FUZZ_RSS_MB) \
	       -print_final_stats=1 -artifact_prefix=$$work/artifacts/ $$dict \
	       $$work/corpus > $$work/log.txt 2>&1; then \
	    grep -E '^#[0-9]+[[:space:]]+(INITED|DONE)|^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)' $$work/log.txt; \
	  else \
	    tail -n 60 $$work/log.txt; ls $$work/artifacts; \
	    echo "$$t: FINDING, reproducer in $$work/artifacts (see docs/TESTING.md)"; exit 1; \
	  fi; \
	done

# The whole ctest suite under ASan + UBSan (float-cast-overflow included).
test-asan: san-deps
	cmake -S . -B $(ASAN_BUILD) $(SAN_CMAKE) -DPENUMBRA_SANITIZE=address,undefined
	$(SAN_ENV) cmake --build $(ASAN_BUILD) -j $(JOBS) --target penumbra_tests
	cd $(ASAN_BUILD) && $(SAN_ENV) ctest --output-on-failure -j $(JOBS)

# ThreadSanitizer on the determinism tests (renders with 1 and 2 threads) and the
# lookup cache's lazy cells,
# linked against Debian's oneTBB rebuilt with -fsanitize=thread so the races
# inside TBB tasks are checked too; the check below refuses to run against the
# uninstrumented system libtbb.
test-tsan: san-deps
	JOBS=$(JOBS) fuzz/sanitizers/build_tsan_tbb.sh $(TSAN_TBB)
	cmake -S . -B $(TSAN_BUILD) $(SAN_CMAKE) -DPENUMBRA_SANITIZE=thread \
	      -DTBB_DIR=$(CURDIR)/$(TSAN_TBB)/lib/cmake/TBB
	$(SAN_ENV) cmake --build $(TSAN_BUILD) -j $(JOBS) --target test_pipeline_determinism test_gather_lookup_cache
	@for t in test_pipeline_determinism test_gather_lookup_cache; do \
	  ldd $(TSAN_BUILD)/tests/$$t | grep -q '$(CURDIR)/$(TSAN_TBB)/lib/libtbb.so.12' || \
	  { echo "test-tsan: $$t is not linked against the TSan libtbb in $(TSAN_TBB)"; exit 1; }; done
	cd $(TSAN_BUILD) && LD_LIBRARY_PATH=$(CURDIR)/$(TSAN_TBB)/lib $(SAN_ENV) \
	  ctest --output-on-failure -j $(JOBS) -R '$(TSAN_TESTS)'
