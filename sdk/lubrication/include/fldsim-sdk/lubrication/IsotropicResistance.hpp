// The body-level far-field (isotropic) resistance R_0 that FLD adds to the pairwise lubrication:
//   Sphere:  R_0 = diag(6 pi mu a f_t I, 8 pi mu a^3 f_r I) at the body centre (node radius a);
//   NodeSum: the rigid-body sum over nodes of isolated-sphere drag, R_0 = sum_n K_n^T R_n K_n
//            (free draining: a dicolloid then has a Jeffery orbit), each node sitting in the
//            strain field, so R_FE:E = sum_n K_n^T R_n (E x_n, 0);
//   Body:    the NodeSum resistance scaled as D R D with D = diag(sqrt(f_t) I, sqrt(f_r) I),
//            which keeps it SPD and reduces to the Sphere factors for one node.
// f_t, f_r, f_s are the phi-dependent factors of the FLD fit (1 for no phi correction).
#pragma once

#include <Eigen/Cholesky>
#include <vector>

#include "fldsim/rigid.hpp"
#include "fldsim/system.hpp"

namespace fldsim::hydro {

enum class IsotropicForm { Sphere, NodeSum, Body };

struct IsotropicFactors {
  double translation = 1.0;  // f_t
  double rotation = 1.0;     // f_r
  double stresslet = 1.0;    // f_s
};

class IsotropicResistance {
 public:
  IsotropicResistance() = default;
  IsotropicResistance(IsotropicForm form, IsotropicFactors factors) : form_(form), f_(factors) {}

  void configure(const System& system);
  // Per-body blocks, Cholesky factors and R_FE:E for the current orientations.
  void update(const System& system, const Eigen::Matrix3d& E, bool shear);

  const Mat6& block(std::size_t body) const { return blocks_[form_ == IsotropicForm::Sphere ? 0 : body]; }
  const Eigen::LLT<Mat6>& factor(std::size_t body) const {
    return factors_[form_ == IsotropicForm::Sphere ? 0 : body];
  }
  // R_FE:E_inf of body i (zero for the Sphere form: a sphere at the centre feels no net force).
  const Vec6& strain_force(std::size_t body) const { return strain_[body]; }
  // Sum over bodies of the stresslet of the isotropic part for velocities dU.
  Eigen::Matrix3d stresslet_sum(const System& system, const Eigen::Matrix3d& E, const double* dU) const;

 private:
  Mat6 node_sum(const System& system, std::size_t body) const;
  IsotropicForm form_ = IsotropicForm::Sphere;
  IsotropicFactors f_;
  Mat6 scale_ = Mat6::Identity();  // D
  std::vector<Mat6> blocks_;
  std::vector<Eigen::LLT<Mat6>> factors_;
  std::vector<Vec6> strain_;
};

}  // namespace fldsim::hydro
