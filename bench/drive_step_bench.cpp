// Cost of the CiA 402 drive per control step: one DriveEngine with its product's default
// plant, enabled in csp and following a moving set-point, so every part runs (PDS, mode, limits,
// supervision, I/O, touch probe, servo or stepper loop, one plant step). One iteration = one
// control step (125 us of drive time). Results and method: docs/performance.md.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>

#include "vdrive/drive/product_plant.hpp"
#include "plant/plant.hpp"
#include "vdrive/drive/drive_engine.hpp"
#include "vdrive/drive/object_ref.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace {

using vdrive::Nanos;
namespace drive = vdrive::drive;

void BM_DriveStepCsp(benchmark::State& state, const std::string& id) {
  const vdrive::profile::ProductProfile profile = vdrive::profile::load_profile(id);
  const vdrive::plant::PlantDescription description = vdrive::drive::default_plant(profile);
  auto dictionary = vdrive::od::shared_dictionary(profile);
  vdrive::od::ObjectStore store(*dictionary);
  vdrive::plant::Plant plant(description);
  drive::DriveEngine engine(profile, store, plant, 0, description.axes.at(0), [](const auto&) {});
  drive::BusState bus;
  bus.esm_init = false;
  bus.remote = true;
  using vdrive::ecat::AlState;
  engine.power_on(0);
  engine.esm_changed(AlState::Init, AlState::PreOp, 0);
  engine.esm_changed(AlState::PreOp, AlState::SafeOp, 0);
  engine.esm_changed(AlState::SafeOp, AlState::Op, 0);
  drive::ObjectRef<std::uint16_t> controlword(store, 0x6040);
  drive::ObjectRef<std::int8_t> mode(store, 0x6060);
  drive::ObjectRef<std::int32_t> target(store, 0x607A);
  mode.set(8);
  const Nanos period = engine.control_period();
  Nanos now = 0;
  for (const std::uint16_t cw : {0x0006, 0x0007, 0x000F}) {
    controlword.set(cw);
    for (int i = 0; i < 20; ++i) {
      engine.outputs_taken(now);
      now += 1'000'000;
      engine.advance_to(now, bus);
    }
  }
  if (engine.state() != drive::PdsState::OperationEnabled) state.SkipWithError("drive did not enable");
  const double per_rev = 2.0 * M_PI / engine.units().motor_rad_per_user();
  const std::int32_t start = static_cast<std::int32_t>(engine.sample().position);
  const Nanos t0 = now;
  std::int64_t steps = 0;
  for (auto _ : state) {
    if (steps % 8 == 0) {  // a bus cycle of 1 ms: a new csp set-point (0.5 Hz sine of one turn, from rest)
      const double t = static_cast<double>(now - t0) * 1e-9;
      target.set(start + static_cast<std::int32_t>(per_rev * (1.0 - std::cos(M_PI * t))));
      engine.outputs_taken(now);
    }
    now += period;
    engine.advance_to(now, bus);
    ++steps;
  }
  if (engine.state() != drive::PdsState::OperationEnabled) state.SkipWithError("drive left Operation enabled");
  state.counters["steps"] = static_cast<double>(steps);
}

BENCHMARK_CAPTURE(BM_DriveStepCsp, a6b, std::string("a6b"));
BENCHMARK_CAPTURE(BM_DriveStepCsp, ds5c1, std::string("ds5c1"));
BENCHMARK_CAPTURE(BM_DriveStepCsp, ds1000a, std::string("ds1000a"));

}  // namespace
