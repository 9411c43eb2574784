# pleinair's two entry points on a fresh Debian 12 machine: `make render` and `make test`.
# Both install any missing Debian package first (apt-get, as root or through sudo).

BUILD ?= build
SAN_BUILD ?= build-sanitize
JOBS ?= $(shell nproc)
DEPS := build-essential cmake ninja-build libopenmesh-dev libglm-dev libopenimageio-dev \
        openimageio-tools libembree-dev libtbb-dev nlohmann-json3-dev libcli11-dev \
        libgtest-dev libbenchmark-dev libhwy-dev
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: all deps build render test test-sanitize bench format reference clean

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

# Until the painter lands: grow the default family (six oaks) into out/.
render: build
	$(BUILD)/pleinair family --preset oak --count 6 --seed 1 -o out/oak
	$(BUILD)/pleinair tree --preset oak --seed 1 --stats

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The same tests built with AddressSanitizer and UndefinedBehaviorSanitizer.
test-sanitize: deps
	cmake -S . -B $(SAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	    -DPLEINAIR_SANITIZE=ON -DPLEINAIR_BENCH=OFF
	cmake --build $(SAN_BUILD) -j $(JOBS)
	cd $(SAN_BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	$(BUILD)/tests/pleinair_bench

# Regenerates the preset key reference in README.md from the key table in the code.
reference: build
	$(BUILD)/pleinair presets --reference > $(BUILD)/reference.md
	awk -v ref=$(BUILD)/reference.md '/<!-- END tree preset reference/ {skip=0} \
	    !skip {print} /<!-- BEGIN tree preset reference/ {while ((getline l < ref) > 0) print l; skip=1}' \
	    README.md > $(BUILD)/README.md && mv $(BUILD)/README.md README.md

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) $(SAN_BUILD) out
