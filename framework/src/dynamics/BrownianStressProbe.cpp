#include "dynamics/BrownianStressProbe.hpp"

#include <algorithm>

namespace fldsim {

BrownianStressProbe::BrownianStressProbe(std::shared_ptr<HydroModel> hydro, const System& s, double range,
                                         double skin, double delta, std::uint64_t seed)
    : hydro_(std::move(hydro)),
      probe_(s),
      W_(6 * s.size(), 0.0),
      u_(6 * s.size(), 0.0),
      delta_(delta),
      seed_(seed) {
  // No flow in the probe's copy: L is the response to forces alone (R_FE:E_inf and R_SE:E_inf
  // would add a deterministic O(delta) difference whose noise grows with Pe).
  probe_.physics().shear_rate = 0.0;
  HydroRequest request;
  request.brownian = false;
  request.shear = false;
  request.stresslets = true;
  hydro_->configure(probe_, request);
  list_.configure(range, skin);
  base_.save(probe_);
}

Eigen::Matrix3d BrownianStressProbe::response_at(double h) {
  move_from(probe_, base_, W_.data(), h);
  list_.update(probe_);
  hydro_->assemble(probe_, list_.pairs());
  hydro_->solve(probe_, W_.data(), u_.data());  // warm start: the other point's solution
  iterations_ += hydro_->last_solve().iterations;
  return hydro_->stresslet_sum(probe_, list_.pairs(), u_.data());
}

Eigen::Matrix3d BrownianStressProbe::measure(const System& s) {
  iterations_ = 0;
  probe_ = s;  // same sizes: no allocation
  probe_.physics().shear_rate = 0.0;
  base_.save(probe_);
  const RandomStream normals(seed_, RandomPurpose::StressProbe, std::uint64_t(s.step()));
  for (std::size_t i = 0; i < s.size(); ++i) normals.normals(i, W_.data() + 6 * i, 6);
  std::fill(u_.begin(), u_.end(), 0.0);
  const Eigen::Matrix3d plus = response_at(0.5 * delta_);
  const Eigen::Matrix3d minus = response_at(-0.5 * delta_);
  return (s.physics().kT / delta_) * (plus - minus);
}

}  // namespace fldsim
