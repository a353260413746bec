#include "oracle/EquilibriumOracle.hpp"

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <sstream>

#include "fldsim/error.hpp"
#include "geometry/HardBodyMonteCarlo.hpp"
#include "oracle/HardCoreContact.hpp"
#include "oracle/PairVirial.hpp"

namespace fldsim::oracle {

std::vector<double> contact_extrapolation(const RadialHistogram& h, double r0, double span) {
  std::vector<int> bins;
  for (int k = 0; k < h.bins(); ++k)
    if (h.lower_edge(k) >= r0 - 1e-9 && h.lower_edge(k) < r0 + span - 1e-9) bins.push_back(k);
  std::vector<double> out;
  if (bins.size() < 3) return out;
  Eigen::MatrixXd A(bins.size(), 3);
  for (std::size_t j = 0; j < bins.size(); ++j) {
    const double x = h.lower_edge(bins[j]) + 0.5 * h.bin_width() - r0;
    A.row(Eigen::Index(j)) << 1.0, x, x * x;
  }
  const auto qr = A.colPivHouseholderQr();
  for (int b = 0; b < h.closed_blocks(); ++b) {
    Eigen::VectorXd y(bins.size());
    for (std::size_t j = 0; j < bins.size(); ++j)
      y[Eigen::Index(j)] = h.block_values(bins[j])[std::size_t(b)];
    out.push_back(qr.solve(y)[0]);
  }
  return out;
}

OracleResult run_oracle(System& s, const std::vector<std::shared_ptr<ForceLaw>>& laws,
                        const OracleOptions& opt, const std::function<void(const std::string&)>& log) {
  const auto wall0 = std::chrono::steady_clock::now();
  auto say = [&](const std::string& m) {
    if (log) log(m);
  };
  if (opt.blocks < 2 || opt.sweeps < opt.blocks * opt.sample_every || opt.sample_every < 1)
    throw Error("Monte Carlo oracle: need blocks >= 2 and sweeps >= blocks * sample_every");
  std::vector<const PairEnergy*> energies;
  std::vector<const ForceLaw*> forces;
  double range = 0.0;
  for (const auto& law : laws) {
    const PairEnergy* e = pair_energy_of(*law);
    if (!e)
      throw Error("Monte Carlo oracle: force '" + law->plugin_name() +
                  "' declares no pair energy (fldsim::PairEnergy), so it has no equilibrium to sample");
    energies.push_back(e);
    forces.push_back(law.get());
    range = std::max(range, law->range(s));
  }

  geometry::MonteCarloOptions start;
  start.seed = opt.seed;
  start.sweeps = opt.start_sweeps;
  const auto report = geometry::initialise_monte_carlo(s, start);
  {
    std::ostringstream o;
    o << "oracle: hard-body start, " << report.sweeps << " sweeps, phi = " << report.final_volume_fraction;
    say(o.str());
  }

  // Its own stream (stage 2 of the Monte Carlo purpose), so the same seed is fine.
  if (opt.hard_core)
    for (const auto& n : s.shape().nodes()) range = std::max(range, 2.0 * n.radius);
  MetropolisSampler mc(s, energies, std::max(range, 1e-9), opt.seed, opt.acceptance);
  mc.set_hard_core(opt.hard_core);
  mc.set_steps(report.max_displacement, 0.3);
  for (std::int64_t k = 0; k < opt.equilibration_sweeps; ++k) {
    mc.sweep();
    if (2 * k < opt.equilibration_sweeps) mc.adapt_steps(opt.target_acceptance);
  }
  {
    std::ostringstream o;
    o << "oracle: " << opt.equilibration_sweeps << " Metropolis sweeps to equilibrate (steps "
      << mc.translation_step() << " a, " << mc.rotation_step()
      << " rad), U/(N kT) = " << mc.total_energy() / double(s.size());
    say(o.str());
  }
  mc.reset_counters();

  OracleResult r;
  r.bodies = RadialHistogram(PairPoints::BodyCentres, opt.bin_width, opt.r_max);
  r.nodes = RadialHistogram(PairPoints::Nodes, opt.bin_width, opt.r_max);
  PairVirial virial(s, forces);
  std::unique_ptr<HardCoreContact> contact;
  if (opt.hard_core) contact = std::make_unique<HardCoreContact>(s);
  const double N = double(s.size()), kT = s.physics().kT;
  const std::int64_t samples_per_block = opt.sweeps / opt.sample_every / opt.blocks;
  // One node per body: the node g is the body g (copied at the end).
  const bool node_histogram = opt.node_distribution && s.nodes_per_body() > 1;
  double energy_sum = 0.0;
  for (int b = 0; b < opt.blocks; ++b) {
    double zb = 0.0, zn = 0.0;
    for (std::int64_t k = 0; k < samples_per_block; ++k) {
      for (std::int64_t w = 0; w < opt.sample_every; ++w) mc.sweep();
      r.bodies.add_sample(s);
      if (node_histogram) r.nodes.add_sample(s);
      if (contact) contact->add_sample(s);
      const Virials v = virial.measure(s);
      zb += 1.0 + v.body.trace() / (3.0 * N * kT);
      zn += 1.0 + v.node.trace() / (3.0 * N * kT);
      energy_sum += mc.total_energy();
      ++r.samples;
    }
    r.bodies.end_block();
    if (node_histogram) r.nodes.end_block();
    if (contact) contact->end_block();
    r.Z_blocks.push_back(zb / double(samples_per_block));
    r.Z_node_blocks.push_back(zn / double(samples_per_block));
  }
  if (opt.node_distribution && !node_histogram) r.nodes = r.bodies;
  r.Z = block_mean(r.Z_blocks);
  r.Z_node = block_mean(r.Z_node_blocks);
  r.Z_block_ratio = block_error_ratio(r.Z_blocks);
  if (contact) {
    // exp(-U(0)/kT): the fit above lies outside the laws' range (the repulsion's 1e-3 a), where
    // the restricted density is the contact density divided by it.
    const double d = 2.0 * s.shape().nodes().front().radius;
    const NodePair at_contact{0, 1, 0, 0, Vec3(d, 0.0, 0.0), d};
    double u0 = 0.0;
    for (const PairEnergy* e : energies) u0 += e->pair_energy(s, at_contact);
    r.boltzmann_at_contact = std::exp(-u0 / kT);
    std::vector<double> z_hc;
    for (std::size_t b = 0; b < contact->block_values().size(); ++b) {
      r.Z_contact_blocks.push_back(contact->block_values()[b] * r.boltzmann_at_contact);
      z_hc.push_back(r.Z_blocks[b] + r.Z_contact_blocks.back());
    }
    r.Z_contact = block_mean(r.Z_contact_blocks);
    r.Z_hard_core = block_mean(z_hc);
  }
  r.energy_per_body = energy_sum / double(r.samples) / N;
  r.sweeps = mc.sweeps_done();
  r.acceptance_translation = mc.acceptance_translation();
  r.acceptance_rotation = mc.acceptance_rotation();
  r.translation_step = mc.translation_step();
  r.rotation_step = mc.rotation_step();

  // Contact value: only for nodes of one radius (one contact distance).
  const auto& nodes = s.shape().nodes();
  bool one_radius = true;
  for (const auto& n : nodes) one_radius = one_radius && n.radius == nodes.front().radius;
  if (opt.node_distribution && one_radius) {
    r.contact_distance = 2.0 * nodes.front().radius;
    const auto values = contact_extrapolation(r.nodes, r.contact_distance, 0.1);
    if (!values.empty()) r.contact = block_mean(values);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return r;
}

}  // namespace fldsim::oracle
