#include "fldsim-sdk/lubrication/IsotropicResistance.hpp"

#include <cmath>

#include "fldsim/parallel_loop.hpp"

namespace fldsim::hydro {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

void IsotropicResistance::configure(const System& system) {
  const std::size_t n = system.size();
  scale_.setIdentity();
  if (form_ == IsotropicForm::Body) {
    scale_.topLeftCorner<3, 3>() *= std::sqrt(f_.translation);
    scale_.bottomRightCorner<3, 3>() *= std::sqrt(f_.rotation);
  }
  const std::size_t stored = form_ == IsotropicForm::Sphere ? 1 : n;
  blocks_.assign(stored, Mat6::Zero());
  // Copies of a computed factor: a default-constructed LLT leaves its ComputationInfo unset, and
  // copying it reads an indeterminate enum (UBSan: "load of value ..., not a valid value").
  factors_.assign(stored, Eigen::LLT<Mat6>(Mat6::Identity()));
  strain_.assign(n, Vec6::Zero());
  if (form_ == IsotropicForm::Sphere) {
    const double mu = system.physics().viscosity;
    const double a = system.node_radius(0);
    blocks_[0].topLeftCorner<3, 3>() = 6.0 * kPi * mu * a * f_.translation * Eigen::Matrix3d::Identity();
    blocks_[0].bottomRightCorner<3, 3>() =
        8.0 * kPi * mu * a * a * a * f_.rotation * Eigen::Matrix3d::Identity();
    factors_[0].compute(blocks_[0]);
  }
}

Mat6 IsotropicResistance::node_sum(const System& system, std::size_t body) const {
  const double mu = system.physics().viscosity;
  const std::size_t m = system.nodes_per_body();
  Mat6 R = Mat6::Zero();
  for (std::size_t k = 0; k < m; ++k) {
    const double a = system.node_radius(k);
    Vec6 drag;
    drag << Vec3::Constant(6.0 * kPi * mu * a), Vec3::Constant(8.0 * kPi * mu * a * a * a);
    const Mat6 K = node_kinematics(system.node_offsets()[body * m + k]);
    R.noalias() += K.transpose() * drag.asDiagonal() * K;
  }
  return R;
}

void IsotropicResistance::update(const System& system, const Eigen::Matrix3d& E, bool shear) {
  if (form_ == IsotropicForm::Sphere) return;  // constant, strain force zero
  const std::size_t n = system.size();
  const std::size_t m = system.nodes_per_body();
  const double mu = system.physics().viscosity;
  parallel_for(std::int64_t(n), [&](std::int64_t i) {
    blocks_[i] = scale_ * node_sum(system, std::size_t(i)) * scale_;
    factors_[i].compute(blocks_[i]);
    Vec6 s = Vec6::Zero();
    if (shear) {
      // Each node at offset x_n sits in the ambient strain: relative to the body's rigid motion
      // U_inf(centre) + Omega_inf x x_n the fluid moves with E x_n, dragging the node along.
      for (std::size_t k = 0; k < m; ++k) {
        const Vec3& off = system.node_offsets()[std::size_t(i) * m + k];
        add_node_wrench(s.data(), off, 6.0 * kPi * mu * system.node_radius(k) * (E * off), Vec3::Zero());
      }
    }
    strain_[i] = scale_ * s;
  });
}

Eigen::Matrix3d IsotropicResistance::stresslet_sum(const System& system, const Eigen::Matrix3d& E,
                                                   const double* dU) const {
  const double mu = system.physics().viscosity;
  const std::size_t n = system.size();
  const std::size_t m = system.nodes_per_body();
  // Force- and torque-free sphere in a strain E: S = (20/3) pi mu a^3 E (Batchelor 1970); the FLD
  // fit scales it by f_s(phi).
  double rs0 = 0.0;
  for (std::size_t k = 0; k < (form_ == IsotropicForm::Sphere ? 1 : m); ++k)
    rs0 += 20.0 / 3.0 * kPi * mu * std::pow(system.node_radius(k), 3);
  Eigen::Matrix3d S = double(n) * f_.stresslet * rs0 * E;
  if (form_ == IsotropicForm::Sphere) return S;
  // Node-force moment about the body centre: S += sum_n sym(x_n (x) f_n), f_n the hydrodynamic
  // drag on node n, f_n = -6 pi mu a (U + Omega x x_n - E x_n) (Batchelor 1970: S = int sym(x sigma.n)).
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 U = Eigen::Map<const Vec3>(dU + 6 * i), W = Eigen::Map<const Vec3>(dU + 6 * i + 3);
    for (std::size_t k = 0; k < m; ++k) {
      const Vec3& off = system.node_offsets()[i * m + k];
      const Vec3 f = -6.0 * kPi * mu * system.node_radius(k) * (node_velocity(U, W, off) - E * off);
      const Eigen::Matrix3d M = off * f.transpose();
      S += 0.5 * f_.stresslet * (M + M.transpose());
    }
  }
  return S;
}

}  // namespace fldsim::hydro
