# Quick start: `make render` and `make test` work on a fresh Debian 12 machine.
# Both install only the Debian packages that are missing, then build Release.
BUILD ?= build
JOBS ?= 2
SHOWCASE ?= scenes/showcase.json
OUT ?= out
PKGS := cmake ninja-build g++ pkg-config libtbb-dev libembree-dev libglm-dev \
        libopenimageio-dev openimageio-tools libnanoflann-dev libbenchmark-dev \
        libgtest-dev nlohmann-json3-dev libcli11-dev libtinyobjloader-dev libfmt-dev \
        fonts-dejavu-core python3 python3-matplotlib
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: all deps configure build renderer render test bench gallery convergence clean
all: build

deps:
	@missing=$$(for p in $(PKGS); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'install ok installed' || echo $$p; \
	done); \
	if [ -n "$$missing" ]; then \
	  echo "Installing missing packages:" $$missing; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; \
	fi

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

bench: build
	@for b in $(BUILD)/bench/bench_*; do $$b; done

gallery: renderer
	scripts/gallery.sh $(BUILD)/penumbra $(OUT)/gallery

# Error against time of the physical model on the convergence scene (docs/PERFORMANCE.md).
convergence: renderer
	scripts/convergence.py $(BUILD)/penumbra scenes/cornell_physical.json $(OUT)/convergence

clean:
	rm -rf $(BUILD) $(OUT)
