# pleinair's two entry points on a fresh Debian 12 machine: `make render` and `make test`.
# Both install any missing Debian package first (apt-get, as root or through sudo).

SHELL := /bin/bash
BUILD ?= build
SAN_BUILD ?= build-sanitize
JOBS ?= $(shell nproc)
# Extra ctest arguments for `make test` and `make test-sanitize` (CI: --output-junit FILE).
CTEST_ARGS ?=
DEPS := build-essential cmake ninja-build libopenmesh-dev libglm-dev libopenimageio-dev \
        openimageio-tools libembree-dev libtbb-dev nlohmann-json3-dev libcli11-dev \
        libgtest-dev libbenchmark-dev libhwy-dev libcairo2-dev pkg-config ffmpeg \
        libcpp-httplib-dev libtinygltf-dev
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

# Seconds each fuzz target runs in `make fuzz` (CI: 20 s each of the ten, two at once).
FUZZ_SECONDS ?= 60
# libFuzzer's seed (0: a new one each run); CI fixes it, so its run can be repeated here.
FUZZ_SEED ?= 0
FUZZ_TARGETS := tree_preset shader_preset palette scene set_value studio_request particle_file graftal \
                imposter gltf

.PHONY: all deps configure build build-sanitize render test test-sanitize test-farm test-studio test-clients deps-studio deps-clients fuzz bench format reference golden gallery clean

all: build

# Installs those of the Debian packages named in $(1) that are missing.
define install_missing
@missing=""; \
for p in $(1); do \
    dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
done; \
if [ -n "$$missing" ]; then \
    echo "Installing Debian packages:$$missing"; \
    $(SUDO) apt-get update -qq && \
    DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
fi
endef

deps:
	$(call install_missing,$(DEPS))

# Seeds build folder $(1)'s ctest cost data with tests/ctest_costs/$(2).txt when it has none, so
# that a fresh build's `ctest -j` starts its longest tests first instead of last (a clean clone
# otherwise runs them in file order, and the last long one runs alone). Refreshed from a run's
# JUnit file: tools/ci/slowest_tests.py --cost-data tests/ctest_costs/$(2).txt FILE.xml.
define seed_costs
@mkdir -p $(1)/Testing/Temporary && { [ -s $(1)/Testing/Temporary/CTestCostData.txt ] || \
    cp tests/ctest_costs/$(2).txt $(1)/Testing/Temporary/CTestCostData.txt; }
endef

configure: deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# Paints the default scene (a full landscape at 1920x1080) into out/mortefontaine.png and prints
# the frame's plan. Builds the program alone, not the tests.
render: configure
	cmake --build $(BUILD) -j $(JOBS) --target pleinair
	$(BUILD)/pleinair render mortefontaine -o out/mortefontaine.png --explain

test: build
	$(call seed_costs,$(BUILD),release)
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) $(CTEST_ARGS)

# Renders a small shot on a real one-node Slurm cluster that the test starts and stops (as root;
# installs slurmctld, slurmd and munge if missing): tests/farm/test_farm.sh.
test-farm: build
	PLEINAIR=$(abspath $(BUILD))/pleinair tests/farm/test_farm.sh

# The studio in a headless Chromium driven by Selenium (installs chromium, its driver and
# python3-selenium if missing): tests/studio/test_studio.py. Screenshots stay in
# $(BUILD)/studio-artifacts.
STUDIO_DEPS := chromium chromium-driver python3-selenium
deps-studio:
	$(call install_missing,$(STUDIO_DEPS))
test-studio: build deps-studio
	/usr/bin/python3 tests/studio/test_studio.py --pleinair $(BUILD)/pleinair \
	    --artifacts $(BUILD)/studio-artifacts

# pleinair's glTF files against real clients (installs Blender, numpy for its glTF importer, and
# Node.js with npm if missing; the Khronos validator comes from npm into $(BUILD)/clients):
# tests/clients/run.sh.
CLIENT_DEPS := blender python3-numpy
deps-clients:
	$(call install_missing,$(CLIENT_DEPS))
	@command -v npm >/dev/null || { $(SUDO) apt-get update -qq && \
	    DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends nodejs npm; }
test-clients: build deps-clients
	tests/clients/run.sh $(abspath $(BUILD))/pleinair $(abspath $(BUILD))/clients

# The same tests built with AddressSanitizer and UndefinedBehaviorSanitizer. Some do less there
# (test::kAddressSanitizer, each says why): the golden images are compared in the plain build
# only (the painters they reach run here through the every-shipped-scene test), and every
# shipped shot runs through render and animate but compares only its middle frame, leaving the
# preview, the benches and the stills to the plain build.
# One build, by clang, serves these tests and the fuzzers (`make fuzz`): the sources the parsers
# reach are instrumented for libFuzzer's coverage too (CMakeLists.txt, PLEINAIR_FUZZ); clang
# compiles it in a third of GCC's time under the sanitizers (BENCHMARKS.md, "CI's time").
SAN_DEPS := clang libfuzzer-14-dev
build-sanitize: deps
	$(call install_missing,$(SAN_DEPS))
	CXX=clang++ cmake -S . -B $(SAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	    -DPLEINAIR_SANITIZE=ON -DPLEINAIR_FUZZ=ON
	cmake --build $(SAN_BUILD) -j $(JOBS)

test-sanitize: build-sanitize
	$(call seed_costs,$(SAN_BUILD),sanitize)
	cd $(SAN_BUILD) && ctest --output-on-failure -j $(JOBS) $(CTEST_ARGS)

# Every parser fuzzed with libFuzzer under ASan and UBSan (clang), FUZZ_SECONDS each, JOBS at
# once (tools/ci/fuzz.sh), from the committed seed corpus (new inputs go to a scratch folder, not
# the repository). A finding fails the run with the input saved as $(SAN_BUILD)/finding-*;
# minimise it (-minimize_crash=1) and commit it under tests/fuzz/regressions/TARGET/, where every
# test run replays it.
fuzz: build-sanitize
	FUZZ_SEED=$(FUZZ_SEED) tools/ci/fuzz.sh $(abspath $(SAN_BUILD)) $(FUZZ_SECONDS) $(JOBS) $(FUZZ_TARGETS)

# The Google Benchmark programs in $(BUILD)/tests (pleinair_bench_*) are built on request.
bench: configure
	cmake -S . -B $(BUILD) -DPLEINAIR_BENCH=ON
	cmake --build $(BUILD) -j $(JOBS)
	$(BUILD)/tests/pleinair_bench

# Regenerates the key references in README.md (trees, shaders, scenes, graftals, imposters, the
# draft's settings) from the key tables in the code, between their BEGIN/END markers.
reference: build
	for kind in trees shaders scenes graftals imposters draft; do \
	    $(BUILD)/pleinair presets --reference $$kind > $(BUILD)/reference.md && \
	    awk -v ref=$(BUILD)/reference.md -v kind=$$kind \
	        '$$0 ~ "<!-- END " kind " reference" {skip=0} !skip {print} \
	         $$0 ~ "<!-- BEGIN " kind " reference" {while ((getline l < ref) > 0) print l; skip=1}' \
	        README.md > $(BUILD)/README.md && mv $(BUILD)/README.md README.md || exit 1; \
	done

# Paints docs/gallery.md's images again (every shipped scene and tree family, and the Corot
# look beside the thesis's) and rewrites the page; look at them before committing.
gallery: build
	bash docs/gallery.sh $(BUILD)/pleinair

# Repaints every golden image's reference (tests/golden/README.md): look at them before
# committing.
# A case with an `animate` file is a frame of a shipped shot, painted by animate with the
# arguments the file holds (shot-NAME, or shot-NAME@WHEN for another frame of it).
golden: build
	for d in tests/golden/*/; do \
	    if [ -f $$d/animate ]; then \
	        tmp=$$(mktemp -d) && n=$$(basename $$d) && n=$${n#shot-} && \
	        $(BUILD)/pleinair animate $${n%@*} $$(cat $$d/animate) -o $$tmp/f_####.png --progress log >/dev/null && \
	        mv $$tmp/f_*.png $$d/reference.png && rmdir $$tmp || exit 1; \
	    else $(BUILD)/pleinair render $$d/scene.json -o $$d/reference.png || exit 1; fi; \
	done

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) $(SAN_BUILD) out
