# The two commands of the README's quick start. Each installs what is missing (Debian packages),
# configures, builds, and then renders the demo or runs the test suite.
BUILD ?= build
JOBS ?= $(shell nproc)
DEMO_SCENE ?= scenes/demo.json
BENCH_RUNS ?= 5

.PHONY: all deps drivers configure build demo test clean fuzz fuzz-deps sanitize bench-specialization bench-performance bench-ray-query bench-instancing bench-big-models study study-wavelengths

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

# The GPU tests run on two lavapipes: the system's (Debian 12: Mesa 22.3) and Debian's newer one
# from bookworm-backports (Mesa 25.0), unpacked into the build tree, never installed
# (docs/testing.md, "Two drivers"). Fails, saying why, when the second cannot be fetched.
BACKPORTS_LAVAPIPE = $(BUILD)/drivers/mesa-backports
SYSTEM_LAVAPIPE_ICD = /usr/share/vulkan/icd.d/lvp_icd.x86_64.json

drivers: deps
	@./.ci/fetch-backports-lavapipe $(BACKPORTS_LAVAPIPE)

test: drivers build
	@echo "vitrum: the GPU tests run on these two drivers:"
	@VK_ICD_FILENAMES=$(SYSTEM_LAVAPIPE_ICD) $(BUILD)/vitrum devices | sed -n 's/^ *driver: /  system lavapipe:    /p'
	@VK_ICD_FILENAMES=$(CURDIR)/$(BACKPORTS_LAVAPIPE)/lvp_icd.json $(BUILD)/vitrum devices | \
	  sed -n 's/^ *driver: /  backports lavapipe: /p'
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# Benchmarks: each regenerates its report in docs/ (several minutes on 2 cores).
bench-specialization: build
	VK_ICD_FILENAMES=$${VK_ICD_FILENAMES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json} \
	  $(BUILD)/bench/vitrum_bench_specialization docs/specialization.md $(BENCH_RUNS)

# Needs Embree 3 (bench/install-deps); cmake runs again so that it finds it.
bench-performance: drivers build
	@./bench/install-deps
	cmake -S . -B $(BUILD) > /dev/null
	cmake --build $(BUILD) -j $(JOBS) --target vitrum_bench_bvh vitrum_bench_primary_rays vitrum_bench_whitted \
	  vitrum_bench_embree_render vitrum_bench_ray_query vitrum_bench_big_sphere
	$(BUILD)/bench/vitrum_bench_bvh $(BENCH_RUNS) > docs/performance.md.partial
	VK_ICD_FILENAMES=$${VK_ICD_FILENAMES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json} \
	  $(BUILD)/bench/vitrum_bench_primary_rays $(BENCH_RUNS) >> docs/performance.md.partial
	VK_ICD_FILENAMES=$${VK_ICD_FILENAMES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json} \
	  $(BUILD)/bench/vitrum_bench_whitted $(BENCH_RUNS) >> docs/performance.md.partial
	echo >> docs/performance.md.partial
	./bench/renderer-vs-embree $(BENCH_RUNS) >> docs/performance.md.partial
	./bench/compare-drivers $(BENCH_RUNS) >> docs/performance.md.partial
	echo >> docs/performance.md.partial
	./bench/instancing --runs $(INSTANCING_RUNS) >> docs/performance.md.partial
	echo >> docs/performance.md.partial
	./bench/ray-query $(BENCH_RUNS) >> docs/performance.md.partial
	mv docs/performance.md.partial docs/performance.md

# The instancing section of docs/performance.md alone (about 6 minutes on 2 cores; the sphere's
# OBJ is kept in /tmp/vitrum-instancing); bench-performance regenerates it with the rest.
INSTANCING_RUNS ?= 3
bench-instancing: build
	./bench/instancing --runs $(INSTANCING_RUNS) > docs/performance.md.section
	./bench/replace-section docs/performance.md "## Instancing" "## vitrum's traversal against" docs/performance.md.section
	rm docs/performance.md.section

# The last section of docs/performance.md alone, vitrum's traversal against Mesa 25's ray queries
# (about 2 minutes on 2 cores); bench-performance regenerates it with the rest.
bench-ray-query: drivers build
	./bench/ray-query $(BENCH_RUNS) > docs/performance.md.section
	sed '/^## vitrum.s traversal against the driver.s ray queries/,$$d' docs/performance.md > docs/performance.md.partial
	cat docs/performance.md.section >> docs/performance.md.partial
	rm docs/performance.md.section
	mv docs/performance.md.partial docs/performance.md

# Big models against an Embree 3 CPU renderer: docs/big-models.md (about 10 minutes on 2 cores;
# the generated OBJs, 1.3 GB, are kept in /tmp/vitrum-big-models for the next run).
BIG_MODEL_RUNS ?= 3
bench-big-models: build
	@./bench/install-deps
	cmake -S . -B $(BUILD) > /dev/null
	cmake --build $(BUILD) -j $(JOBS) --target vitrum_bench_embree_render vitrum_bench_big_sphere
	./bench/big-models --runs $(BIG_MODEL_RUNS) > docs/big-models.md.partial
	mv docs/big-models.md.partial docs/big-models.md

# The accuracy study: docs/accuracy-vs-time.md and docs/study/ (8.5-25 minutes on 2 cores).
STUDY_RUNS ?= 3
study: build
	VK_ICD_FILENAMES=$${VK_ICD_FILENAMES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json} \
	  $(BUILD)/bench/vitrum_study docs --runs $(STUDY_RUNS)

# The study's dispersion setting: wavelength samples against time (docs/wavelengths-vs-time.md).
study-wavelengths: build
	VK_ICD_FILENAMES=$${VK_ICD_FILENAMES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json} \
	  $(BUILD)/bench/vitrum_wavelength_study docs --runs 5 --size 320x240

# Not part of the quick start (docs/testing.md): libFuzzer on the scene and image loaders for
# FUZZ_SECONDS per target, in its own clang build; and the whole suite under ASan + UBSan.
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
ASAN_BUILD ?= build-asan

fuzz-deps: deps
	@./tests/fuzz/install-deps

fuzz: fuzz-deps
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DVITRUM_FUZZ=ON
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_obj_mtl fuzz_scene_json fuzz_gltf fuzz_image
	./tests/fuzz/run-fuzz $(FUZZ_BUILD) $(FUZZ_SECONDS)

# The Vulkan loader unloads lavapipe and the validation layer at vkDestroyInstance, before
# LeakSanitizer can name the module of the driver's own leaks; preloading them keeps them mapped so
# that tests/sanitizers/lsan.supp can suppress those by name (the ASan runtime must come first).
# So it runs the device tests on the system's lavapipe only: the preloaded driver would stand in
# for the backports one, whose library has the same name (the host code is the same either way).
SANITIZE_PRELOAD = $(shell g++ -print-file-name=libasan.so) $(wildcard \
  /usr/lib/x86_64-linux-gnu/libvulkan_lvp.so /usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so)


sanitize: deps
	cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVITRUM_SANITIZE=ON
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	LD_PRELOAD="$(SANITIZE_PRELOAD)" ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitizers/lsan.supp:print_suppressions=0 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS) --timeout 1800 \
	  --label-exclude backports-lavapipe --exclude-regex '^TwoDrivers\.'

clean:
	rm -rf $(BUILD) $(FUZZ_BUILD) $(ASAN_BUILD) out
