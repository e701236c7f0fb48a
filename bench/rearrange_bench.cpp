// Rearrangement speed (issue 7 acceptance: a 10-room apartment in under 2 s on 2 cores).
//   BM_Rearrange10Rooms  rearrange() of the generated apartment seed 5 with 10 rooms (built
//                        once, outside the timing), rearrangement seed = iteration % 8
// The physics is single-threaded (deterministic Bullet world), so the core count only matters
// for what else runs on the machine.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "procedural/apartment.h"
#include "variation/rearrange.h"

namespace inet {
namespace {

void BM_Rearrange10Rooms(benchmark::State& state) {
  const auto dir = std::filesystem::temp_directory_path() / "inet_rearrange_bench";
  ApartmentOptions a;
  a.seed = 5;
  a.rooms = 10;
  a.texture_size = 64;
  const Apartment apt = makeApartment(a, dir, dir / "textures");
  uint64_t seed = 0;
  double steps = 0, movable = 0;
  for (auto _ : state) {
    RearrangeOptions opt;
    opt.seed = seed++ % 8;
    RearrangeLog log;
    benchmark::DoNotOptimize(rearrange(apt.scene, opt, &log));
    steps += log.steps;
    movable += log.movable;
  }
  state.counters["objects"] = static_cast<double>(apt.scene.objects.size());
  state.counters["movable"] = movable / state.iterations();
  state.counters["steps"] = steps / state.iterations();
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_Rearrange10Rooms)->Unit(benchmark::kMillisecond)->Iterations(16);

}  // namespace
}  // namespace inet

BENCHMARK_MAIN();
