# glarecam: the README's commands. Every target installs what it needs (idempotent) and builds.
BUILD_DIR      ?= build
ASAN_BUILD_DIR ?= build-asan
JOBS           ?= $(shell nproc)
DEMO_DIR       ?= demo-out
CMAKE_FLAGS    ?=

.PHONY: deps demo-deps configure build test test-asan fuzz soak demo bench install package coverage-check kill-check route-check cluster-check clean format

deps:
	bash scripts/install-deps.sh

# Only what the demo builds and runs (scripts/install-deps.sh --demo): no test, benchmark,
# packaging or sanitizer toolchain.
demo-deps:
	bash scripts/install-deps.sh --demo

CONFIGURE = cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo

# The suite and the benchmark are asked for by name: a build directory the demo configured
# without them gets them back.
configure: deps
	$(CONFIGURE) -DGLARECAM_BUILD_TESTS=ON -DGLARECAM_BUILD_BENCH=ON $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

# A test with no TIMEOUT of its own fails after this long (the slowest takes ~80 s under ASan):
# a hang is a named failure, not a CI run that never ends.
TEST_TIMEOUT_S ?= 300

# The whole suite, then again under AddressSanitizer + UBSan the executables marked SANITIZE in
# tests/CMakeLists.txt (the only tests that configure defines).
test: build test-asan
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS) --timeout $(TEST_TIMEOUT_S)

# The sanitizer build is Clang's (clang-19: libFuzzer, and std::expected with libstdc++ 12), and
# holds the fuzz targets; its ctest runs each for a short budget (tests/fuzz/CMakeLists.txt).
ASAN_CONFIGURE = CC=clang-19 CXX=clang++-19 cmake -S . -B $(ASAN_BUILD_DIR) -G Ninja \
	  -DCMAKE_BUILD_TYPE=Debug -DGLARECAM_SANITIZE=ON -DGLARECAM_FUZZ=ON \
	  -DGLARECAM_BUILD_BENCH=OFF $(CMAKE_FLAGS)

test-asan: deps
	$(ASAN_CONFIGURE)
	cmake --build $(ASAN_BUILD_DIR) -j $(JOBS) --target sanitized_tests
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp ctest --test-dir $(ASAN_BUILD_DIR) \
	  --output-on-failure -j $(JOBS) --timeout $(TEST_TIMEOUT_S)

# Every fuzz target for FUZZ_SECONDS each (docs/fuzzing.md): what they learn stays in
# $(ASAN_BUILD_DIR)/fuzz/corpus, what they find in $(ASAN_BUILD_DIR)/fuzz/findings.
FUZZ_SECONDS ?= 60
fuzz: deps
	$(ASAN_CONFIGURE)
	cmake --build $(ASAN_BUILD_DIR) -j $(JOBS) --target fuzz_targets
	python3 scripts/fuzz --seconds $(FUZZ_SECONDS) $(ASAN_BUILD_DIR)/bin

# Installs and builds only what the demo runs: the tests and the benchmark are most of the objects
# and of the packages, and the demo runs neither (`make build` builds everything). AUTO: the
# suite and the benchmark stay configured where `make deps` installed their packages.
DEMO_TARGETS = glarecam glarecamd
demo: demo-deps
	$(CONFIGURE) -DGLARECAM_BUILD_TESTS=AUTO -DGLARECAM_BUILD_BENCH=AUTO $(CMAKE_FLAGS)
	cmake --build $(BUILD_DIR) -j $(JOBS) --target $(DEMO_TARGETS)
	bash scripts/demo.sh $(BUILD_DIR)/bin $(DEMO_DIR)

# glarecamd on the simulated rig for SOAK_STACKS stacks (weeks of simulated days in a time
# lapse), failing on growing memory or descriptors, a lost stack or a missing result; then a
# season on a small disk (SEASON_DAYS simulated days on a 160 MiB tmpfs with max_use_gib 0.2
# alone: never a pause for the disk, as many stacks every day, every stack's numbers kept;
# docs/operator.md, "Soak test" and "Retention"). Not part of `make test`: about 5 + 12 minutes.
SOAK_STACKS ?= 1000
SOAK_DIR    ?= soak-out
SEASON_DAYS ?= 28
SEASON_DIR  ?= soak-season-out
soak: configure
	cmake --build $(BUILD_DIR) -j $(JOBS) --target glarecamd
	python3 scripts/soak --stacks $(SOAK_STACKS) --out $(SOAK_DIR) $(BUILD_DIR)/bin
	python3 scripts/soak-season --days $(SEASON_DAYS) --out $(SEASON_DIR) $(BUILD_DIR)/bin

# The method's two routes checked against each other (docs/brdf.md, "The route check"): each named
# surface swept by the simulated camera under the sun and by the simulated goniophotometer, Lmax
# and the limit axes compared per α in units of their combined σ; fails when any |z| is beyond
# the 3σ threshold for the whole check (Šidák: 4.0 for 40 comparisons). The tables go to
# ROUTE_CHECK_DIR/<surface>/route-check.csv. `make test` runs a small version (RouteCheck.* in
# brdf_tests: three α of the standard surface; and the CLI script's). About 75 s.
ROUTE_CHECK_DIR ?= route-check-out
route-check: configure
	cmake --build $(BUILD_DIR) -j $(JOBS) --target glarecam
	for surface in standard glare-reduced; do \
	  $(BUILD_DIR)/bin/glarecam route-check --surface $$surface --out $(ROUTE_CHECK_DIR)/$$surface || exit 1; \
	done

# Issue 9's 50 SIGKILLs while glarecamd writes (25 while a stack, 25 while a result is staged):
# no partial stack visible, the next start cleans up; and the long camera-loss checks (the fake
# GigE camera killed under glarecamd, a 6 s bracket cut and SIGTERM mid-bracket:
# GLARECAM_LONG_CHECKS=1). `make test` kills 8 of each and skips the long ones, whose small
# versions are unit tests. About 5 minutes.
kill-check: build
	GLARECAM_LONG_CHECKS=1 GLARECAM_KILLS_PER_KIND=25 ctest --test-dir $(BUILD_DIR) \
	  --output-on-failure --timeout $(TEST_TIMEOUT_S) \
	  -R 'GlarecamdKills\.|GlarecamdLongBracket\.|GlarecamdProcess\.FakeGigECameraKilledAndRestarted'

# Do the reported uncertainties hold? 50 noise seeds at three α and two lobe sizes, each sigma
# against the seeds' scatter (scripts/uncertainty-coverage, docs/process.md). About 10 minutes.
COVERAGE_SEEDS ?= 50
coverage-check: configure
	cmake --build $(BUILD_DIR) -j $(JOBS) --target glarecam
	python3 scripts/uncertainty-coverage --seeds $(COVERAGE_SEEDS) --jobs $(JOBS) $(BUILD_DIR)/bin

# District screening on a real Slurm (docs/cluster.md): installs slurm-wlm and munge where missing
# (scripts/install-deps.sh --cluster), brings up a one-node Slurm on this machine as root (state in
# a temp dir, torn down at the end), runs deploy/slurm's job array over CLUSTER_SHARDS shards of a
# small city (scripts/make-city) and the merge after it, and compares hazard.geojson,
# receptors.csv and screen.json with one `glarecam hazard --screen` run byte for byte. Exit 77
# (a skip, with the reason) where Slurm cannot run here. Not part of `make test`: about a minute.
CLUSTER_SHARDS ?= 4
cluster-check: configure
	cmake --build $(BUILD_DIR) -j $(JOBS) --target glarecam
	bash scripts/cluster-check --shards $(CLUSTER_SHARDS) $(BUILD_DIR)/bin

bench: build
	$(BUILD_DIR)/bin/glarecam-bench --benchmark_counters_tabular=true

# Binaries, systemd units, the service user, udev rules, the example config and the docs
# (docs/operator.md, "Installing on a rig"). PREFIX: where (default /usr/local; the units name
# the binaries there, so it is set at configure time); DESTDIR works.
PREFIX ?= /usr/local
install: build
	cmake -S . -B $(BUILD_DIR) -DCMAKE_INSTALL_PREFIX=$(PREFIX)
	cmake --build $(BUILD_DIR) -j $(JOBS)
	cmake --install $(BUILD_DIR)

# A Debian package of this build (docs/operator.md, "The Debian package"):
# $(BUILD_DIR)/glarecam_VERSION_ARCH.deb, which lintian must pass without an error or a warning.
package: build
	cmake --build $(BUILD_DIR) --target package
	lintian --fail-on error,warning $(BUILD_DIR)/glarecam_*_*.deb

format:
	git ls-files '*.cpp' '*.h' | xargs clang-format -i

clean:
	rm -rf $(BUILD_DIR) $(ASAN_BUILD_DIR) $(DEMO_DIR) $(SOAK_DIR) $(ROUTE_CHECK_DIR)
