# The two set-up commands of the README. Each installs what is missing, builds, then runs.
BUILD ?= build
PRESET ?= release
JOBS ?= $(shell nproc)
# A compile cache when there is one: scripts/check-consumer.sh then reuses this build's compiles.
LAUNCHER := $(if $(shell command -v ccache),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR := $(CURDIR)
FORMATTED = find src app include tests examples tools shaders fuzz -name '*.cpp' -o -name '*.h'

.PHONY: deps build demo test sanitize clean format format-check consumer fuzz soak

deps:
	bash scripts/install-deps.sh

build: deps
	cmake --preset $(PRESET) $(LAUNCHER) >/dev/null
	cmake --build --preset $(PRESET) -j $(JOBS)

demo: build
	mkdir -p out
	./$(BUILD)/bounce render --scene sunroom --sky daylight --gi evolve --preset desktop --res 480x270 --frames 64 \
		--timings out/demo-timings.json --out out/demo.png
	@echo "demo: wrote out/demo.png and the per-pass GPU times out/demo-timings.json"

# A test that crashed (a signal, not a failed check) is rerun once: scripts/run-tests.sh says why.
test: build
	PRESET=$(PRESET) JOBS=$(JOBS) bash scripts/run-tests.sh

sanitize: deps
	cmake --preset asan >/dev/null
	cmake --build --preset asan -j $(JOBS)
	ctest --preset asan -j $(JOBS)

# Bounce used from another CMake project, through find_package and through add_subdirectory.
consumer: build
	bash scripts/check-consumer.sh

# libFuzzer on the glTF loader and the image readers (fuzz/; FUZZ_RUNS per target, default 1 M).
fuzz:
	bash scripts/fuzz.sh

# Long animated runs checked for NaN pixels and memory growth (scripts/soak.sh; SOAK_FRAMES ...).
soak: build
	bash scripts/soak.sh

format:
	$(FORMATTED) | xargs clang-format -i

# Fails, listing the places, where a file differs from .clang-format's style (CI runs it).
format-check: deps
	$(FORMATTED) | xargs clang-format --dry-run --Werror

clean:
	rm -rf build build-asan build-debug build-consumer build-fuzz out
