#include "oracle/OracleCommand.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "config/NumberText.hpp"
#include "fldsim/error.hpp"
#include "fldsim/force.hpp"
#include "fldsim/shape.hpp"
#include "oracle/EquilibriumOracle.hpp"
#include "run/Experiment.hpp"

namespace fldsim {

const char* const kOracleHelp =
    "usage: fldsim oracle FILE.yaml [options]\n"
    "\n"
    "The exact equilibrium of the experiment's force potential (every force must declare a pair\n"
    "energy): Metropolis Monte Carlo of system.shape, system.count and the volume fraction, from a\n"
    "hard-body start (seed system.init.seed), in the cubic periodic box. Hydrodynamics, flow and\n"
    "run keys play no part (the force prefactors use the experiment's Pe as a run would). Writes\n"
    "g(r) of body centres and of nodes with block standard errors to a CSV file and prints\n"
    "Z = P/(n kT) = 1 + tr(W)/(3 N kT), W the virial of body-centre separations and pair forces,\n"
    "and the node-node contact value g(2a+). Method: docs/equilibrium-oracle.md.\n"
    "\n"
    "  -o, --output OUT.csv    g(r) table (default: the experiment's output with .oracle.csv)\n"
    "  --overwrite             replace an existing table (refused otherwise)\n"
    "  --set KEY=VALUE         override an experiment key, as for `fldsim run`\n"
    "  --sweeps N              sampling sweeps (5000); one sweep = one trial move per body\n"
    "  --equilibrate N         Metropolis sweeps before sampling (500)\n"
    "  --every N               sweeps between samples (5)\n"
    "  --blocks B              blocks for the standard errors (20)\n"
    "  --bin W                 g(r) bin width in a (0.02)\n"
    "  --r-max R               g(r) range in a (min(5, L/2))\n"
    "  --seed S                seed of the start and the chain (system.init.seed)\n"
    "  --hard-core             no two bodies' nodes overlap (U = infinity there): the reference for\n"
    "                          lubricated hydrodynamics (fld, lubrication), whose steps do not reach\n"
    "                          the overlaps of the repulsion (docs/equilibrium-oracle.md, \"FLD near\n"
    "                          contact\"); Z then leaves out the hard core's contact term\n";

namespace {

struct CommandLine {
  std::string file, output;
  bool overwrite = false;
  std::vector<std::string> overrides;
  oracle::OracleOptions opt;
  bool seed_given = false, r_max_given = false;
};

long parse_integer(const std::string& option, const std::string& text, long min) {
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < min)
    throw ConfigError("fldsim oracle: " + option + ": expected an integer >= " + std::to_string(min) +
                      ", got '" + text + "'");
  return v;
}

double parse_positive(const std::string& option, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(v > 0.0) || !std::isfinite(v))
    throw ConfigError("fldsim oracle: " + option + ": expected a number > 0, got '" + text + "'");
  return v;
}

bool parse(const std::vector<std::string>& args, CommandLine& c, std::ostream& out) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw ConfigError("fldsim oracle: " + a + ": expected a value");
      return args[++i];
    };
    if (a == "-h" || a == "--help") {
      out << kOracleHelp;
      return false;
    } else if (a == "-o" || a == "--output") {
      c.output = value();
    } else if (a == "--overwrite") {
      c.overwrite = true;
    } else if (a == "--set") {
      c.overrides.push_back(value());
    } else if (a == "--sweeps") {
      c.opt.sweeps = parse_integer(a, value(), 1);
    } else if (a == "--equilibrate") {
      c.opt.equilibration_sweeps = parse_integer(a, value(), 0);
    } else if (a == "--every") {
      c.opt.sample_every = parse_integer(a, value(), 1);
    } else if (a == "--blocks") {
      c.opt.blocks = int(parse_integer(a, value(), 2));
    } else if (a == "--bin") {
      c.opt.bin_width = parse_positive(a, value());
    } else if (a == "--r-max") {
      c.opt.r_max = parse_positive(a, value());
      c.r_max_given = true;
    } else if (a == "--hard-core") {
      c.opt.hard_core = true;
    } else if (a == "--seed") {
      c.opt.seed = std::uint64_t(parse_integer(a, value(), 0));
      c.seed_given = true;
    } else if (!a.empty() && a[0] == '-') {
      throw ConfigError("fldsim oracle: unknown option " + a + " (see fldsim oracle --help)");
    } else if (c.file.empty()) {
      c.file = a;
    } else {
      throw ConfigError("fldsim oracle: more than one experiment file given");
    }
  }
  if (c.file.empty()) throw ConfigError("fldsim oracle: no experiment file given (see fldsim oracle --help)");
  if (c.opt.sweeps < std::int64_t(c.opt.blocks) * c.opt.sample_every)
    throw ConfigError("fldsim oracle: --sweeps " + std::to_string(c.opt.sweeps) +
                      " is fewer than --blocks x --every = " +
                      std::to_string(std::int64_t(c.opt.blocks) * c.opt.sample_every));
  return true;
}

std::string default_output(const Experiment& ex) {
  if (ex.output.empty())
    throw ConfigError(ex.file + ": output: no file to name the table after; give -o OUT.csv");
  std::filesystem::path p(ex.output);
  p.replace_extension(".oracle.csv");
  return p.string();
}

}  // namespace

int oracle_command(const std::vector<std::string>& args, std::ostream& out, std::ostream& log) {
  CommandLine c;
  if (!parse(args, c, out)) return 0;
  std::unique_ptr<PluginRegistry> registry;
  const Experiment ex = read_experiment(c.file, c.overrides, registry);
  if (!ex.brownian)
    throw ConfigError(ex.file +
                      ": flow.brownian: the oracle samples exp(-U/kT) and needs a Brownian (kT > 0) system");
  const std::string output = c.output.empty() ? default_output(ex) : c.output;
  if (!c.overwrite && std::filesystem::exists(output))
    throw ConfigError("fldsim oracle: " + output + " exists (use --overwrite to replace it)");

  auto shape = registry->create<Shape>("shape", ex.shape.name, ex.shape.params);
  std::vector<std::shared_ptr<ForceLaw>> forces;
  for (const auto& f : ex.forces) forces.push_back(registry->create<ForceLaw>("force", f.name, f.params));
  for (std::size_t k = 0; k < forces.size(); ++k)
    if (!pair_energy_of(*forces[k]))
      throw ConfigError(ex.file + ": forces[" + std::to_string(k) + "]: force '" + ex.forces[k].name +
                        "' declares no pair energy, so the oracle cannot sample it");

  Physics ph;  // as a run sets it: a = 1, 6 pi mu a = 1, kT = 1
  ph.kT = 1.0;
  ph.shear_rate = ex.peclet;
  double edge = ex.box_edge;
  ph.volume_fraction = ex.volume_fraction;
  if (edge > 0.0)
    ph.volume_fraction = double(ex.count) * shape->volume() / (edge * edge * edge);
  else
    edge = std::cbrt(double(ex.count) * shape->volume() / ex.volume_fraction);
  System sys(shape, std::size_t(ex.count), edge, ph);

  oracle::OracleOptions opt = c.opt;
  if (!c.seed_given) opt.seed = std::uint64_t(ex.init_seed);
  if (!c.r_max_given) opt.r_max = std::min(5.0, std::floor(0.5 * edge / opt.bin_width) * opt.bin_width);
  if (2.0 * opt.r_max > edge)
    throw ConfigError("fldsim oracle: --r-max " + format_number(opt.r_max) + " exceeds half the box edge " +
                      format_number(0.5 * edge));
  log << "fldsim oracle: " << ex.file << ": " << ex.count << " x " << ex.shape.name
      << ", phi = " << ph.volume_fraction << ", box edge " << edge << " a, " << forces.size()
      << " force(s)\n";
  if (ex.peclet != 0.0)
    log << "note: flow.peclet = " << ex.peclet
        << " enters only through the force prefactors; the oracle is the "
        << "equilibrium of that potential\n";

  const oracle::OracleResult r =
      oracle::run_oracle(sys, forces, opt, [&](const std::string& m) { log << m << "\n"; });

  // Table first to OUT.part, then renamed: an interrupted run leaves no half table under the name.
  const std::string part = output + ".part";
  {
    std::ofstream f(part);
    if (!f) throw Error("cannot write " + part);
    f << "# fldsim oracle " << ex.file << ": " << ex.count << " x " << ex.shape.name
      << ", phi = " << ph.volume_fraction << "; " << r.samples << " samples in " << opt.blocks
      << " blocks; g = mean of block g, se = block SE\n";
    f << "r_lo,r_hi,g_body,se_body,g_node,se_node\n";
    for (int k = 0; k < r.bodies.bins(); ++k) {
      const auto gb = r.bodies.g(k), gn = r.nodes.g(k);
      f << format_number(r.bodies.lower_edge(k)) << ","
        << format_number(r.bodies.lower_edge(k) + opt.bin_width) << "," << gb.mean << "," << gb.se << ","
        << gn.mean << "," << gn.se << "\n";
    }
    if (!f.flush()) throw Error("cannot write " + part + " (disk full?)");
  }
  std::filesystem::rename(part, output);

  char line[512];
  std::snprintf(
      line, sizeof line,
      "Z = P/(n kT)          %.4f +- %.4f  (molecular virial: body-centre separations x pair forces)\n"
      "Z (node-node virial)  %.4f +- %.4f  (leaves out the intra-body constraint virial)\n",
      r.Z.mean, r.Z.se, r.Z_node.mean, r.Z_node.se);
  out << line;
  if (opt.hard_core) {
    out << "(hard core: Z is the virial of the force laws only, without the contact term)\n";
    std::snprintf(
        line, sizeof line,
        "Z contact term        %.4f +- %.4f  (hard core, molecular form, x exp(-U(0)/kT) = %.4f)\n"
        "Z hard core           %.4f +- %.4f  (Z + contact term: the restricted system's pressure)\n",
        r.Z_contact.mean, r.Z_contact.se, r.boltzmann_at_contact, r.Z_hard_core.mean, r.Z_hard_core.se);
    out << line;
  }
  if (r.contact.blocks > 0) {
    std::snprintf(
        line, sizeof line, "g(%.3g a+) nodes      %.4f +- %.4f  (quadratic fit over [%.3g, %.3g) a)\n",
        r.contact_distance, r.contact.mean, r.contact.se, r.contact_distance, r.contact_distance + 0.1);
    out << line;
  }
  std::snprintf(
      line, sizeof line,
      "U/(N kT)              %.5f\n"
      "%lld samples, %d blocks (SE with half as many blocks / SE = %.2f; about 1 when the blocks are "
      "long enough), acceptance %.2f translation / %.2f rotation, %.1f s\n",
      r.energy_per_body, (long long)r.samples, opt.blocks, r.Z_block_ratio, r.acceptance_translation,
      r.acceptance_rotation, r.seconds);
  out << line << "g(r): " << output << "\n";
  return 0;
}

}  // namespace fldsim
