# The two commands of the README's quick start. Each installs what is missing (Debian packages),
# configures, builds, and then renders the demo or runs the test suite.
BUILD ?= build
JOBS ?= $(shell nproc)
DEMO_SCENE ?= scenes/demo.json

.PHONY: all deps configure build demo test clean

all: build

deps:
	@./.ci/install-deps

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

configure: $(BUILD)/CMakeCache.txt

build: deps configure
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	@mkdir -p out
	VK_ICD_FILENAMES=$${VK_ICD_FILENAMES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json} \
	  $(BUILD)/vitrum render $(DEMO_SCENE) -o out/demo.png --backend vulkan

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

clean:
	rm -rf $(BUILD) out
