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

FUZZ_BUILD ?= build-fuzz
# Seconds each fuzz target runs in `make fuzz` (CI: 20 s each of the ten, to keep its run under an
# hour).
FUZZ_SECONDS ?= 60
FUZZ_TARGETS := tree_preset shader_preset palette scene set_value studio_request particle_file graftal \
                imposter gltf

.PHONY: all deps configure build build-sanitize build-fuzz render test test-sanitize test-farm test-studio test-clients fuzz bench format reference golden gallery clean

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
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) $(CTEST_ARGS)

# Renders a small shot on a real one-node Slurm cluster that the test starts and stops (as root;
# installs slurmctld, slurmd and munge if missing): tests/farm/test_farm.sh.
test-farm: build
	PLEINAIR=$(abspath $(BUILD))/pleinair tests/farm/test_farm.sh

# The studio in a headless Chromium driven by Selenium (installs chromium, its driver and
# python3-selenium if missing): tests/studio/test_studio.py. Screenshots stay in
# $(BUILD)/studio-artifacts.
STUDIO_DEPS := chromium chromium-driver python3-selenium
test-studio: build
	$(call install_missing,$(STUDIO_DEPS))
	/usr/bin/python3 tests/studio/test_studio.py --pleinair $(BUILD)/pleinair \
	    --artifacts $(BUILD)/studio-artifacts

# pleinair's glTF files against real clients (installs Blender, numpy for its glTF importer, and
# Node.js with npm if missing; the Khronos validator comes from npm into $(BUILD)/clients):
# tests/clients/run.sh.
CLIENT_DEPS := blender python3-numpy
test-clients: build
	$(call install_missing,$(CLIENT_DEPS))
	@command -v npm >/dev/null || { $(SUDO) apt-get update -qq && \
	    DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends nodejs npm; }
	tests/clients/run.sh $(abspath $(BUILD))/pleinair $(abspath $(BUILD))/clients

# The same tests built with AddressSanitizer and UndefinedBehaviorSanitizer, but for the golden
# images (2 minutes of test time under the sanitizers; the painters they reach run here through
# the every-shipped-scene test), which `make test` runs. Every shipped shot still runs here,
# through render and animate (ShippedScene.PaintsOneFrameWhicheverCommandPaintsIt, which
# compares only the middle frame when sanitized and leaves the preview, the benches and the
# stills to the plain build).
SAN_SKIP := GoldenImages\.MatchTheirReferences
build-sanitize: deps
	cmake -S . -B $(SAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	    -DPLEINAIR_SANITIZE=ON -DPLEINAIR_BENCH=OFF
	cmake --build $(SAN_BUILD) -j $(JOBS)

test-sanitize: build-sanitize
	cd $(SAN_BUILD) && ctest --output-on-failure -j $(JOBS) -E '$(SAN_SKIP)' $(CTEST_ARGS)

# Every parser fuzzed with libFuzzer under ASan and UBSan (clang), FUZZ_SECONDS each, from the
# committed seed corpus (new inputs go to a scratch folder, not the repository). A finding stops
# with the input saved as $(FUZZ_BUILD)/finding-*; minimise it (-minimize_crash=1) and commit
# it under tests/fuzz/regressions/TARGET/, where every test run replays it.
build-fuzz: deps
	@dpkg-query -W -f='$${Status}\n' clang libfuzzer-14-dev 2>/dev/null | grep -c "install ok installed" | grep -q 2 || \
	    { $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends clang libfuzzer-14-dev; }
	CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPLEINAIR_FUZZ=ON
	cmake --build $(FUZZ_BUILD) -j $(JOBS)

fuzz: build-fuzz
	@for t in $(FUZZ_TARGETS); do \
	    mkdir -p $(FUZZ_BUILD)/corpus/$$t && \
	    echo "fuzz $$t: $(FUZZ_SECONDS) s" && \
	    PLEINAIR_PRESETS=$(abspath presets) $(FUZZ_BUILD)/tests/fuzz/fuzz_$$t -max_total_time=$(FUZZ_SECONDS) \
	        -max_len=65536 -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
	        -artifact_prefix=$(FUZZ_BUILD)/finding-$$t- \
	        $(FUZZ_BUILD)/corpus/$$t tests/fuzz/corpus/$$t \
	        $$( [ -d tests/fuzz/regressions/$$t ] && echo tests/fuzz/regressions/$$t ) \
	        2>&1 | grep -E "^(stat::|==|fuzz finding|SUMMARY|Done|#[0-9]+ *DONE)" ; \
	    test $${PIPESTATUS[0]} -eq 0 || exit 1; \
	done

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
