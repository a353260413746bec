// Observer `squeeze`: at every sample, the Jeffrey–Onishi squeeze resistance X^A_11 (the
// singular terms FLD keeps, in units of the Stokes drag 6 pi mu a_i) averaged over the node pairs
// closer than `max_gap`, computed by fldsim::lubrication's LubricationPair; over the run, its mean
// and standard error by Flyvbjerg–Petersen blocking (fldsim::statistics' BlockAverage), written
// as results that `fldsim summary` prints.
#include <cmath>
#include <cstddef>
#include <fldsim-sdk/lubrication/LubricationPair.hpp>
#include <fldsim-sdk/statistics/BlockAverage.hpp>
#include <fldsim-sdk/statistics/ObserverOutput.hpp>
#include <fldsim/observer.hpp>
#include <fldsim/plugin.hpp>
#include <vector>

namespace squeeze {

class SqueezeObserver : public fldsim::Observer {
 public:
  static void describe(fldsim::ParamSchema& s) {
    s.number("max_gap", 0.5, "a", "node pairs with a surface gap below this are counted").greater(0.0);
  }
  explicit SqueezeObserver(const fldsim::Params& p) : max_gap_(p.number("max_gap")) {}

  void sample(const fldsim::StepView& view, fldsim::ResultSink&) override {
    const fldsim::System& system = view.system;
    const double mu = system.physics().viscosity;
    double sum = 0.0;
    std::size_t near = 0;
    // The core's pair list holds every pair within the plugins' ranges (here the hydro model's).
    for (const fldsim::NodePair& p : view.pairs.pairs()) {
      const double a_i = system.node_radius(p.node_a);
      const double a_j = system.node_radius(p.node_b);
      if (p.distance - a_i - a_j >= max_gap_) continue;
      const fldsim::hydro::LubricationCoefficients c =
          fldsim::hydro::LubricationPair::coefficients(a_i, a_j, p.distance, mu, options_);
      sum += c.squeeze / (6.0 * M_PI * mu * a_i);
      ++near;
    }
    near_pairs_.add(double(near));
    if (near > 0) x_a_.add(sum / double(near));
  }

  void finish(const fldsim::RunInfo&, fldsim::ResultSink& out) override {
    fldsim::observers::write_blocked(out, "results/squeeze/X_A", x_a_, "1",
                                     "Jeffrey-Onishi squeeze resistance X^A_11 of the near node pairs");
    fldsim::observers::write_blocked(out, "results/squeeze/near_pairs", near_pairs_, "1",
                                     "node pairs with a surface gap below max_gap");
  }

  // Exact restart: the two sample series.
  std::vector<double> save_state() const override {
    fldsim::StateWriter w;
    x_a_.save(w);
    near_pairs_.save(w);
    return w.take();
  }
  void restore_state(const std::vector<double>& state) override {
    fldsim::StateReader r(state, "squeeze");
    x_a_.restore(r);
    near_pairs_.restore(r);
    r.finish();
  }

 private:
  double max_gap_;
  fldsim::hydro::LubricationOptions options_;  // Jeffrey-Onishi forms, no taper
  fldsim::observers::BlockAverage x_a_, near_pairs_;
};

}  // namespace squeeze

FLDSIM_PLUGIN(observer, squeeze::SqueezeObserver, "squeeze", "1.0.0",
              "Jeffrey-Onishi squeeze resistance X^A_11 of near node pairs, block averaged")
