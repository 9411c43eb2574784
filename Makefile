# pleinair's two entry points on a fresh Debian 12 machine: `make render` and `make test`.
# Both install any missing Debian package first (apt-get, as root or through sudo).

BUILD ?= build
SAN_BUILD ?= build-sanitize
JOBS ?= $(shell nproc)
DEPS := build-essential cmake ninja-build libopenmesh-dev libglm-dev libopenimageio-dev \
        openimageio-tools libembree-dev libtbb-dev nlohmann-json3-dev libcli11-dev \
        libgtest-dev libbenchmark-dev libhwy-dev ffmpeg
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: all deps build render test test-sanitize test-farm bench format reference golden clean

all: build

deps:
	@missing=""; \
	for p in $(DEPS); do \
	    dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	    echo "Installing Debian packages:$$missing"; \
	    $(SUDO) apt-get update -qq && \
	    DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
	fi

build: deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS)

# Paints the default scene (a full landscape at 1920x1080) into out/mortefontaine.png and prints
# the frame's plan.
render: build
	$(BUILD)/pleinair render mortefontaine -o out/mortefontaine.png --explain

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Renders a small shot on a real one-node Slurm cluster that the test starts and stops (as root;
# installs slurmctld, slurmd and munge if missing): tests/farm/test_farm.sh.
test-farm: build
	PLEINAIR=$(abspath $(BUILD))/pleinair tests/farm/test_farm.sh

# The same tests built with AddressSanitizer and UndefinedBehaviorSanitizer.
test-sanitize: deps
	cmake -S . -B $(SAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	    -DPLEINAIR_SANITIZE=ON -DPLEINAIR_BENCH=OFF
	cmake --build $(SAN_BUILD) -j $(JOBS)
	cd $(SAN_BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	$(BUILD)/tests/pleinair_bench

# Regenerates the key references in README.md (trees, shaders, scenes) from the key tables in
# the code, between their BEGIN/END markers.
reference: build
	for kind in trees shaders scenes; do \
	    $(BUILD)/pleinair presets --reference $$kind > $(BUILD)/reference.md && \
	    awk -v ref=$(BUILD)/reference.md -v kind=$$kind \
	        '$$0 ~ "<!-- END " kind " reference" {skip=0} !skip {print} \
	         $$0 ~ "<!-- BEGIN " kind " reference" {while ((getline l < ref) > 0) print l; skip=1}' \
	        README.md > $(BUILD)/README.md && mv $(BUILD)/README.md README.md || exit 1; \
	done

# Repaints every golden image's reference (tests/golden/README.md): look at them before
# committing.
golden: build
	for d in tests/golden/*/; do $(BUILD)/pleinair render $$d/scene.json -o $$d/reference.png; done

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) $(SAN_BUILD) out
