#include "PairDistributionObserver.hpp"

#include <string>
#include <vector>

#include "fldsim-sdk/statistics/ObserverOutput.hpp"
#include "fldsim/number_text.hpp"

namespace fldsim::observers {

void PairDistributionObserver::begin(const System& system, const RunInfo&, ResultSink&) {
  pd_.check_box(system.box());
}

void PairDistributionObserver::sample(const StepView& view, ResultSink& out) {
  pd_.add_sample(view.system.positions(), view.system.box());
  // Time series of the contact-region value would need a choice of region; the maps are
  // steady-state averages, so only the sample count is recorded as it grows.
  const double n = static_cast<double>(pd_.samples());
  out.append_sample("timeseries/pair_distribution/samples", view.system.step(), view.system.time(), {}, &n,
                    "1");
}

void PairDistributionObserver::finish(const RunInfo&, ResultSink& out) {
  const std::string r = "results/pair_distribution/";
  if (pd_.samples() == 0) {
    out.write_attribute("results/pair_distribution", "skipped", "no samples after start");
    return;
  }
  write_vector(out, r + "r", pd_.r_centres(), "a", "shell centres of g(r)");
  write_vector(out, r + "g_r", pd_.g_r(), "1", "radial distribution of body centres, uncorrelated = 1");
  write_vector(out, r + "g_r_stderr", pd_.g_r_stderr(), "1",
               "Poisson SE of g(r) (assumes independent samples; a lower bound otherwise)");
  const int nb = pd_.map_bins();
  std::vector<double> edges(nb + 1);
  for (int b = 0; b <= nb; ++b) edges[b] = -pd_.config().range + b * pd_.map_cell();
  write_vector(out, r + "map_edges", edges, "a", "cell edges of the g maps along both axes");
  for (Projection p : pd_.config().projections) {
    const std::string name = projection_name(p);
    const std::vector<std::size_t> shape{static_cast<std::size_t>(nb), static_cast<std::size_t>(nb)};
    const auto g = pd_.g_map(p), e = pd_.g_map_stderr(p);
    const std::string what = "g(" + std::string(1, name[0]) + ", " + name[1] + ") averaged over |" +
                             (p == Projection::XY   ? "z"
                              : p == Projection::XZ ? "y"
                                                    : "x") +
                             "| < slab_half; rows: first axis, columns: second axis";
    out.write_array(r + "g_" + name, shape, g.data(), "1", what);
    out.write_array(r + "g_" + name + "_stderr", shape, e.data(), "1", "Poisson SE of g_" + name);
  }
  out.write_attribute("results/pair_distribution", "slab_half", number_text(pd_.config().slab_half));
  out.write_attribute("results/pair_distribution", "samples", std::to_string(pd_.samples()));
}

std::vector<double> PairDistributionObserver::save_state() const {
  StateWriter w;
  pd_.save(w);
  return w.take();
}

void PairDistributionObserver::restore_state(const std::vector<double>& state) {
  StateReader r(state, "pair_distribution");
  pd_.restore(r);
  r.finish();
}

}  // namespace fldsim::observers
