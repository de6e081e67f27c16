// Cost of one plant step (one drive cycle: step_s with its ODE substeps), per axis.
// Method and results: docs/performance.md. Run: bench_plant --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <string>

#include "plant/plant.hpp"
#include "plant/plant_yaml.hpp"

namespace {

using namespace vdrive::plant;

// N independent rigid direct-drive axes in one world (a 200 W servo on an equal load inertia),
// 250 us steps with 2 substeps: the default plant's shape, repeated.
PlantDescription rigid_axes(int n, bool two_mass) {
  PlantDescription d;
  d.step_s = 250e-6;
  d.substeps = 2;
  for (int i = 0; i < n; ++i) {
    AxisSpec a;
    a.name = "axis" + std::to_string(i);
    a.load_inertia_kgm2 = a.motor.rotor_inertia_kgm2;
    a.friction = {.coulomb = 0.01, .breakaway = 0.015, .stribeck_velocity = 0.01, .viscous = 1e-5};
    if (two_mass) {
      a.load_inertia_kgm2 = 5 * a.motor.rotor_inertia_kgm2;
      a.transmission.stiffness = 20.0;  // ~250 Hz resonance
      a.transmission.damping = 1e-3;
    }
    d.axes.push_back(a);
  }
  return d;
}

void run(benchmark::State& state, Plant& p) {
  const std::size_t axes = p.axis_count();
  AxisCommand c;
  int i = 0;
  for (auto _ : state) {
    c.torque_nm = (i++ & 1024) ? 0.2 : -0.2;  // keep the axes moving back and forth
    for (std::size_t a = 0; a < axes; ++a) p.command(a, c);
    p.step();
    benchmark::DoNotOptimize(p.feedback(0).encoder.counts);
  }
  state.counters["axes"] = static_cast<double>(axes);
  state.counters["per_axis"] = benchmark::Counter(static_cast<double>(axes),
                                                  benchmark::Counter::kIsIterationInvariantRate |
                                                      benchmark::Counter::kInvert);
}

void BM_RigidAxes(benchmark::State& state) {
  Plant p(rigid_axes(static_cast<int>(state.range(0)), false));
  run(state, p);
}
BENCHMARK(BM_RigidAxes)->Arg(1)->Arg(2)->Arg(4)->Arg(8)->Arg(16);

// The same axes stepped by ODE instead of the closed form (plant/lone_hinge_step.hpp).
void BM_RigidAxesOde(benchmark::State& state) {
  PlantDescription d = rigid_axes(static_cast<int>(state.range(0)), false);
  d.closed_form_hinges = false;
  Plant p(d);
  run(state, p);
}
BENCHMARK(BM_RigidAxesOde)->Arg(1)->Arg(16);

void BM_TwoMassAxes(benchmark::State& state) {
  Plant p(rigid_axes(static_cast<int>(state.range(0)), true));
  run(state, p);
}
BENCHMARK(BM_TwoMassAxes)->Arg(1)->Arg(4)->Arg(16);

void BM_TwoLinkArm(benchmark::State& state) {
  Plant p(load_plant_file(std::string(VDRIVE_SOURCE_DIR) + "/scenarios/plants/two_link_arm.yaml"));
  run(state, p);
}
BENCHMARK(BM_TwoLinkArm);

}  // namespace
