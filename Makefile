# The two set-up commands of the README. Each installs what is missing, builds, then runs.
BUILD ?= build
PRESET ?= release
JOBS ?= $(shell nproc)

.PHONY: deps build demo test sanitize clean format

deps:
	bash scripts/install-deps.sh

build: deps
	cmake --preset $(PRESET) >/dev/null
	cmake --build --preset $(PRESET) -j $(JOBS)

demo: build
	mkdir -p out
	./$(BUILD)/bounce render --scene sunroom --sky daylight --gi evolve --preset desktop --res 480x270 --frames 64 \
		--timings out/demo-timings.json --out out/demo.png
	@echo "demo: wrote out/demo.png and the per-pass GPU times out/demo-timings.json"

test: build
	ctest --preset $(PRESET) -j $(JOBS)

sanitize: deps
	cmake --preset asan >/dev/null
	cmake --build --preset asan -j $(JOBS)
	ctest --preset asan -j $(JOBS)

format:
	find src app include tests examples shaders -name '*.cpp' -o -name '*.h' | xargs clang-format -i

clean:
	rm -rf build build-asan out
