#include "BrownianEquilibrium.hpp"

#include <chrono>
#include <cmath>
#include <sstream>
#include <tuple>

#include "dynamics/BrownianStressProbe.hpp"
#include "dynamics/Scene.hpp"
#include "geometry/HardBodyMonteCarlo.hpp"
#include "observers/FakeSink.hpp"
#include "oracle/HardCoreContact.hpp"
#include "oracle/PairVirial.hpp"
#include "run/StepLoop.hpp"

namespace fldsim::testing {

std::string EquilibriumScene::describe() const {
  std::ostringstream o;
  o << count << " x " << shape << shape_params << ", phi " << phi << ", hydro " << hydro << hydro_params
    << ", repulsion " << force_params;
  return o.str();
}

namespace {

Physics brownian_physics(double phi) {
  Physics ph;
  ph.kT = 1.0;
  ph.shear_rate = 0.0;
  ph.volume_fraction = phi;
  return ph;
}

double box_edge(const Shape& shape, std::size_t n, double phi) {
  return std::cbrt(double(n) * shape.volume() / phi);
}

}  // namespace

EquilibriumScene free_draining_spheres() {
  EquilibriumScene s;
  s.hydro = "free_draining";
  s.count = 125;
  s.phi = 0.3;
  return s;
}

oracle::OracleOptions comparison_oracle_options(bool hard_core) {
  oracle::OracleOptions o;
  o.bin_width = 0.01;
  o.sweeps = 20000;
  o.blocks = 40;
  o.node_distribution = false;
  o.hard_core = hard_core;
  return o;
}

oracle::OracleResult run_scene_oracle(const EquilibriumScene& scene, const oracle::OracleOptions& opt) {
  auto shape = make<Shape>("shape", scene.shape, scene.shape_params);
  System s(shape, scene.count, box_edge(*shape, scene.count, scene.phi), brownian_physics(scene.phi));
  return oracle::run_oracle(s, {make<ForceLaw>("force", "repulsion", scene.force_params)}, opt);
}

oracle::MeanError contact_term_reference(const oracle::OracleResult& mc) {
  const double b = mc.boltzmann_at_contact;
  return {mc.Z_contact.mean / b, mc.Z_contact.se / b, mc.Z_contact.blocks};
}

BrownianEquilibrium run_brownian(const EquilibriumScene& scene, const BrownianOptions& opt) {
  const auto wall0 = std::chrono::steady_clock::now();
  auto shape = make<Shape>("shape", scene.shape, scene.shape_params);
  Scene sc(shape, scene.count, box_edge(*shape, scene.count, scene.phi), brownian_physics(scene.phi));
  System& s = *sc.system;
  geometry::MonteCarloOptions start;
  start.seed = opt.seed;
  if (!opt.start_forgets_compression) {
    start.relaxation_msd = 0.0;
    start.relaxation_p2 = 2.0;
  }
  geometry::initialise_monte_carlo(s, start);
  auto repulsion = make<ForceLaw>("force", "repulsion", scene.force_params);
  sc.finish(make<HydroModel>("hydro", scene.hydro, scene.hydro_params), {repulsion},
            HydroRequest{true, false, opt.stress_every > 0});
  std::unique_ptr<TimeIntegrator> integrator_owner;
  if (opt.leimkuhler_matthews)
    integrator_owner = std::make_unique<LeimkuhlerMatthews>(opt.seed, s.size());
  else if (opt.rk3)
    integrator_owner = std::make_unique<RungeKutta3>(opt.seed, s.size(), opt.rejected);
  else
    integrator_owner = std::make_unique<EulerMaruyama>(opt.seed, true, opt.drift, s.size(), opt.rejected);
  TimeIntegrator& integrator = *integrator_owner;

  const std::int64_t warm = std::llround(opt.equilibrate / opt.dt);
  const std::int64_t per_block = std::llround(opt.duration / opt.dt) / opt.sample_every / opt.blocks;
  RunInfo info;
  info.dt = opt.dt;
  info.total_steps = warm + per_block * opt.sample_every * opt.blocks;
  std::vector<std::shared_ptr<Observer>> observers;
  if (opt.stress_every > 0) {
    auto stress = make<Observer>("observer", "stress");
    stress->set_schedule(opt.stress_every, warm * opt.dt);
    observers.push_back(stress);
  }
  fldsim::test::FakeSink sink;
  for (auto& o : observers) o->begin(s, info, sink);
  StepControlSettings control;
  control.frame = opt.dt;
  control.adaptive = opt.adaptive;
  control.tolerance = opt.tolerance;
  control.reject_at = opt.reject_at;
  control.order = integrator.error_order();
  control.displacement = opt.displacement;
  control.gap_step = opt.gap_step;
  control.gap_range = opt.gap_range;
  control.error_control = opt.error_control;
  StepGuard guard;
  guard.max_overlap = opt.max_overlap;
  StepLoop loop(s, integrator, *sc.evaluator, sc.list, observers, info, true,
                !opt.rk3 && !opt.leimkuhler_matthews && opt.drift == DriftScheme::Midpoint, control, guard);
  std::unique_ptr<BrownianStressProbe> probe;
  if (opt.stress_every > 0 && opt.probe_brownian_stress) {
    // As Simulation makes it: the model's own copy with the probe's solve tolerance.
    YAML::Node probe_params = YAML::Load(scene.hydro_params);
    if (registry().find("hydro", scene.hydro).schema.find("tolerance"))
      probe_params["tolerance"] = BrownianStressProbe::kDefaultTolerance;
    probe = std::make_unique<BrownianStressProbe>(
        make<HydroModel>("hydro", scene.hydro, YAML::Dump(probe_params)), s, sc.hydro->pair_range(s), 0.3,
        BrownianStressProbe::kDefaultDelta, opt.seed);
    loop.use_brownian_stress_probe(probe.get());
  }

  BrownianEquilibrium out;
  out.g = oracle::RadialHistogram(oracle::PairPoints::BodyCentres, opt.bin_width, opt.r_max);
  out.min_gap = INFINITY;
  oracle::PairVirial virial(s, {repulsion.get()});
  std::unique_ptr<oracle::HardCoreContact> contact;
  if (opt.contact_term) contact = std::make_unique<oracle::HardCoreContact>(s);
  for (std::int64_t k = 0; k < warm; ++k) loop.step(sink);
  for (int b = 0; b < opt.blocks; ++b) {
    double z = 0.0;
    for (std::int64_t j = 0; j < per_block; ++j) {
      for (std::int64_t w = 0; w < opt.sample_every; ++w) loop.step(sink);
      out.g.add_sample(s);
      z += 1.0 + virial.measure(s).body.trace() / (3.0 * double(s.size()) * s.physics().kT);
      out.min_gap = std::min(out.min_gap, sc.list.min_gap(s));
      if (contact) contact->add_sample(s);
    }
    out.g.end_block();
    if (contact) contact->end_block();
    out.Z_blocks.push_back(z / double(per_block));
  }
  out.Z = oracle::block_mean(out.Z_blocks);
  if (contact) {
    out.Z_contact_blocks = contact->block_values();
    out.Z_contact = oracle::block_mean(out.Z_contact_blocks);
  }
  out.steps = s.step();
  out.accepted = loop.statistics().accepted_steps();
  out.rejected = loop.statistics().rejected_attempts();
  out.node_step_sum = std::pow(loop.statistics().rms_node_step(), 2) * double(out.accepted);
  std::tie(out.gap_step_sum, out.near_pairs) = loop.statistics().gap_step_state();
  for (auto& o : observers) o->finish(info, sink);
  if (opt.stress_every > 0) {
    const auto& z = sink.scalar("results/stress/Z");
    out.Z_observer = z.value;
    out.Z_observer_se = z.stderr_value;
    if (sink.scalars.count("results/stress/Z_particle")) {
      const auto& zp = sink.scalar("results/stress/Z_particle");
      out.Z_particle = zp.value;
      out.Z_particle_se = zp.stderr_value;
      out.has_Z_particle = true;
    }
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return out;
}

BrownianEquilibrium run_brownian_replicas(const EquilibriumScene& scene, BrownianOptions opt, int runs) {
  BrownianEquilibrium out;
  out.g = oracle::RadialHistogram(oracle::PairPoints::BodyCentres, opt.bin_width, opt.r_max);
  out.min_gap = INFINITY;
  opt.blocks = 1;
  const std::uint64_t first = opt.seed;
  for (int k = 0; k < runs; ++k) {
    opt.seed = first + std::uint64_t(k);
    const BrownianEquilibrium r = run_brownian(scene, opt);
    out.g.append_blocks(r.g);
    out.Z_blocks.push_back(r.Z.mean);
    if (opt.stress_every > 0) out.Z_observer_blocks.push_back(r.Z_observer);
    if (r.has_Z_particle) out.Z_particle_blocks.push_back(r.Z_particle);
    if (opt.contact_term) out.Z_contact_blocks.push_back(r.Z_contact.mean);
    out.steps += r.steps;
    out.accepted += r.accepted;
    out.rejected += r.rejected;
    out.node_step_sum += r.node_step_sum;
    out.gap_step_sum += r.gap_step_sum;
    out.near_pairs += r.near_pairs;
    out.min_gap = std::min(out.min_gap, r.min_gap);
    out.seconds += r.seconds;
  }
  out.Z = oracle::block_mean(out.Z_blocks);
  if (opt.contact_term) out.Z_contact = oracle::block_mean(out.Z_contact_blocks);
  if (opt.stress_every > 0) {
    const oracle::MeanError z = oracle::block_mean(out.Z_observer_blocks);
    out.Z_observer = z.mean;
    out.Z_observer_se = z.se;
  }
  if (runs > 0 && out.Z_particle_blocks.size() == std::size_t(runs)) {
    const oracle::MeanError zp = oracle::block_mean(out.Z_particle_blocks);
    out.Z_particle = zp.mean;
    out.Z_particle_se = zp.se;
    out.has_Z_particle = true;
  }
  return out;
}

}  // namespace fldsim::testing
