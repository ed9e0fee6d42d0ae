# irloc: the front door. CMake + Ninja do the real build underneath.
#   make            release build: build/bin/irlocd, build/bin/irloc-sim
#   make test       every suite once: the algo/ suites (but the rendered drives, label scene), the
#                   file readers' and protocols' suites and the fuzz corpora under ASan+UBSan
#                   (build/asan), then the release build and every other suite
#   make demo       build, then run the default demo and print its result
#   make bench      builds the benchmarks (not part of make or make test) and runs them, JSON under build/bench/
#   make fuzz       libFuzzer targets (clang, ASan+UBSan), FUZZ_SECONDS each (default 120)
#   make cross      aarch64 build (build/aarch64) with Debian's cross compiler
#   make test-cross the algo tests of the aarch64 build under qemu-aarch64 -cpu cortex-a72
#   make deb        the irlocd Debian package for this machine (and the arm64 one after make cross)
#   make check-backends  compile the libcamera and libgpiod backends against bookworm-backports'
#                   (libcamera 0.3, libgpiod 2.1) and Debian 13's (0.4, 2.2) dev packages, and the
#                   live view against Debian 13's cpp-httplib (0.18), unpacked into build/backends
#   make survey-scenarios  host_sim/scenarios/survey_*.yaml through irlocd --survey (minutes)
#   make survey-goal  issue 28's map-building goals on rendered drives (SURVEY_SCENES per class,
#                   SURVEY_SEED), minutes; not part of make test
#   make eval-rolling  the rolling-shutter evaluation: EVAL_SCENES drives of EVAL_FRAMES frames from
#                   EVAL_SEED per family (dot, square, led), rolling against global shutter
#                   (tools/rolling_eval.sh)
#   make test-vm    irlocd --camera libcamera on libcamera 0.4's virtual camera in a Debian 13 VM
#                   (qemu: KVM, else TCG): poses scored, 10,000 frames, a reopen; then on an
#                   emulated UVC webcam: its exposure and gain set as asked; cached in build/vm
#                   (tools/test_vm.sh; time budget: docs/hardware.md)
#   make soak       1e6 frames through irlocd on the simulated camera: memory, descriptors and
#                   allocations flat (SOAK_FRAMES=N for another length)
#   make clean
# WERROR=0 turns warnings back into warnings (default: they are errors).

WERROR ?= 1
# ctest runs this many tests at once (the machine's cores by default).
TEST_JOBS ?= $(shell nproc)
BUILD := build
CMAKE_FLAGS := -G Ninja -DIRLOC_WERROR=$(if $(filter 1,$(WERROR)),ON,OFF)

.PHONY: all deps deps-cross configure test demo bench eval-rolling fuzz cross test-cross soak clean check-backends

all: configure
	cmake --build $(BUILD) --target irlocd irloc-sim

deps:
	@tools/deps.sh native

deps-cross:
	@tools/deps.sh cross

configure: deps
	@cmake -S . -B $(BUILD) $(CMAKE_FLAGS) -DCMAKE_BUILD_TYPE=Release >/dev/null

test: deps
	@cmake -S . -B $(BUILD)/asan $(CMAKE_FLAGS) -DCMAKE_BUILD_TYPE=Debug -DIRLOC_SANITIZE=ON >/dev/null
	cmake --build $(BUILD)/asan --target test_programs
	cd $(BUILD)/asan && ctest --output-on-failure --parallel $(TEST_JOBS)
	@cmake -S . -B $(BUILD) $(CMAKE_FLAGS) -DCMAKE_BUILD_TYPE=Release >/dev/null
	cmake --build $(BUILD)
	cd $(BUILD) && ctest --output-on-failure --parallel $(TEST_JOBS)

demo: all
	tools/demo.sh $(BUILD)

bench: configure
	cmake --build $(BUILD) --target bench

.PHONY: survey-scenarios
survey-scenarios: configure
	cmake --build $(BUILD) --target irlocd_survey_scenarios_test irlocd
	cd $(BUILD) && nice -n 10 bin/irlocd_survey_scenarios_test

SURVEY_SCENES ?= 2
SURVEY_SEED ?= 28
.PHONY: survey-goal
survey-goal: configure
	cmake --build $(BUILD) --target survey_goal irlocd
	cd $(BUILD) && nice -n 10 bin/survey_goal --scenes=$(SURVEY_SCENES) --seed=$(SURVEY_SEED) --out=survey_goal

EVAL_SCENES ?= 6
EVAL_SEED ?= 29
EVAL_FRAMES ?= 200
eval-rolling: configure
	cmake --build $(BUILD) --target irlocd irloc-sim
	status=0; for family in dot square led; do \
	  tools/rolling_eval.sh $(BUILD) $(EVAL_SCENES) $(EVAL_SEED) $(EVAL_FRAMES) $$family || status=1; done; exit $$status

SOAK_FRAMES ?= 1000000
soak: configure
	cmake --build $(BUILD) --target irlocd-soak irloc-sim
	nice -n 10 tools/soak.sh $(BUILD) $(SOAK_FRAMES)

fuzz: deps
	@tools/deps.sh fuzz
	tools/fuzz.sh $(BUILD)

cross: deps-cross
	@cmake -S . -B $(BUILD)/aarch64 $(CMAKE_FLAGS) -DCMAKE_BUILD_TYPE=Release \
	  -DCMAKE_TOOLCHAIN_FILE=$(CURDIR)/boards/toolchains/aarch64-linux-gnu.cmake >/dev/null
	cmake --build $(BUILD)/aarch64

test-cross: cross
	cd $(BUILD)/aarch64 && ctest --output-on-failure -L algo

check-backends: deps
	tools/check_backends.sh $(BUILD)

.PHONY: test-vm
test-vm:
	@tools/deps.sh vm
	tools/test_vm.sh $(BUILD)

clean:
	rm -rf $(BUILD)

# make deb: the irlocd Debian package for this machine's architecture (build/irlocd_VERSION_ARCH.deb:
# amd64 on a PC, arm64 when run on a Raspberry Pi, whose own libcamera the Depends then names);
# on a PC after `make cross`, the arm64 one too (build/aarch64/irlocd_VERSION_arm64.deb). See docs/hardware.md.
.PHONY: deb
deb: all
	tools/make_deb.sh $(BUILD) $$(dpkg --print-architecture)
	@if [ "$$(dpkg --print-architecture)" != arm64 ] && [ -x $(BUILD)/aarch64/bin/irlocd ]; then \
	  tools/make_deb.sh $(BUILD)/aarch64 arm64; \
	elif [ "$$(dpkg --print-architecture)" != arm64 ]; then echo "deb: no arm64 package: run make cross first"; fi
