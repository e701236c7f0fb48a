# The two commands of the README:
#   make demo   install what is missing, build (Release), generate the built-in sequence into out/demo
#   make test   install what is missing, build, run every test (ctest)
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: demo test build setup configure bench clean

setup:
	@bash scripts/setup.sh

configure: setup
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

demo: build
	@$(BUILD)/apps/interiornet generate --out out/demo
	@echo "frames are in $$(ls -d out/demo/*/*/ | head -1)"

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	@$(BUILD)/apps/interiornet bench --json

clean:
	@rm -rf $(BUILD)
