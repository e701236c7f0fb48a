# The two commands of the README:
#   make demo   install what is missing, build the program (Release), generate a short sequence
#               through the built-in apartment into out/demo, one line per step (scripts/demo.sh)
#   make test   install what is missing, build, run every test (ctest)
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

FUZZ_SECONDS ?= 20

.PHONY: demo test build setup configure bench fuzz clean

setup:
	@bash scripts/setup.sh

configure: setup
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

demo:
	@BUILD=$(BUILD) JOBS=$(JOBS) bash scripts/demo.sh

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	@$(BUILD)/apps/interiornet bench --json

# libFuzzer on the parsers of our own formats (clang, ASan + UBSan), FUZZ_SECONDS each. The
# trajectory corpus also gets the official ground-truth files of ../shared (inputs are cut at
# 32 KB, so the excerpt around fr2/desk's repeated stamp at line 10863 is added on its own).
fuzz:
	@bash scripts/setup.sh fuzz
	@cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
	  -DINET_FUZZ=ON -DINET_BUILD_TESTS=OFF >/dev/null
	@cmake --build build-fuzz -j $(JOBS) --target fuzz_layout fuzz_trajectory fuzz_camera_json fuzz_sensors fuzz_mitsuba fuzz_light_xml fuzz_denoiser_weights fuzz_catalog fuzz_sh3d
	@for t in layout trajectory camera_json sensors mitsuba light_xml denoiser_weights catalog sh3d; do \
	  mkdir -p build-fuzz/corpus/$$t && cp -n fuzz/corpus/$$t/* build-fuzz/corpus/$$t/ ; \
	  if [ $$t = trajectory ] && [ -d ../shared/data/trajectories ]; then \
	    cp -n ../shared/data/trajectories/*.txt ../shared/data/trajectories/*.csv build-fuzz/corpus/$$t/ ; \
	    sed -n '10850,10875p' ../shared/data/trajectories/tum_rgbd_fr2_desk_groundtruth.txt \
	      > build-fuzz/corpus/$$t/fr2_desk_repeated_stamp.txt ; \
	  fi; \
	  echo "fuzz_$$t: $(FUZZ_SECONDS) s"; \
	  build-fuzz/fuzz/fuzz_$$t -max_total_time=$(FUZZ_SECONDS) -max_len=32768 -print_final_stats=0 build-fuzz/corpus/$$t \
	    2>build-fuzz/fuzz_$$t.log || { tail -40 build-fuzz/fuzz_$$t.log; exit 1; }; \
	  grep -E "^#[0-9]+.*DONE" build-fuzz/fuzz_$$t.log | tail -1; \
	done

clean:
	@rm -rf $(BUILD)
