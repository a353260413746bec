// The hydrodynamic model shared by the three hydro plugins: body resistance
//     R_FU = R_0 + R_delta,
// with R_0 the isotropic part (IsotropicResistance) and R_delta the pairwise lubrication
// (BodyResistance, optional). Brownian forces F_B = sqrt(2 kT/dt) (A alpha + sum_p B_p beta_p)
// with A the Cholesky factor of each body's R_0 block; solve by block-Jacobi PCG, or directly per
// body when there is no lubrication (free draining).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fldsim-sdk/lubrication/BodyResistance.hpp"
#include "fldsim-sdk/lubrication/IsotropicResistance.hpp"
#include "fldsim/block_sparse.hpp"
#include "fldsim/hydro.hpp"
#include "fldsim/params.hpp"

namespace fldsim::hydro {

// The phi correction of R_0: none (isolated spheres), Kumar & Higdon's fit made with the LAMMPS
// lubrication forms (reference §1a), fldsim's refit for its Jeffrey-Onishi forms, or Kumar &
// Higdon's fit made for pairs without log terms (LAMMPS flaglog 0).
enum class IsotropicFit { None, KumarHigdon, Fldsim, KumarHigdonSqueeze };
// `tapered`: the lubrication has the smooth taper (fldsim's fit differs for the two cutoff forms).
IsotropicFactors isotropic_factors(IsotropicFit fit, double phi, bool tapered = false);

struct ModelSettings {
  bool lubrication = true;
  IsotropicForm isotropic = IsotropicForm::Sphere;
  IsotropicFit fit = IsotropicFit::None;          // which R_0(phi) correction (fld)
  std::optional<IsotropicFactors> fixed_factors;  // calibration only: use these, ignore fit
  LubricationOptions lub;
  double tolerance = 1e-6;
  int max_iterations = 1000;
  Preconditioner preconditioner = Preconditioner::IncompleteCholesky;
  // An assembly (of the same step or a later one) reuses the last preconditioner while R has moved
  // by at most this much since it was built, relative: its diagonal blocks in one Frobenius norm
  // over all bodies (IncompleteCholesky), or each body's block row against its diagonal block
  // (EisenstatDilu, whose measured best is 0.3); 0 rebuilds it at every assembly. The matrix it was
  // built from is the model's checkpoint state, so a resumed run solves bit-identically.
  double refactor_threshold = 0.15;
  // Where IC(0) breaks down: the diagonal shifts tried before D-ILU takes over (BlockPCG::set_shifts).
  std::vector<double> ic_shifts{BlockPCG::kDefaultShifts.begin(), BlockPCG::kDefaultShifts.end()};
  // IC(0)'s row order (BlockPCG::set_row_order).
  RowOrder ic_order = RowOrder::Automatic;
};

// Declare and read the parameters common to lubrication and fld. `conventions: lammps` presets
// the pair forms of LAMMPS pair lubricateU (pump, twist, lever, strain arm, no taper); a key set
// explicitly to a different value is an error.
void describe_lubrication_params(ParamSchema& schema);
ModelSettings read_lubrication_params(const Params& params);
// True when `conventions: lammps` was chosen (fld also presets r0_fit from it).
bool lammps_conventions(const Params& params);
// The value of choice `key`: the user's if given, else `preset` under conventions: lammps, else
// the schema default. A given value that contradicts the preset is a configuration error.
const std::string& convention_choice(const Params& params, const std::string& key, const std::string& preset);

class ResistanceModel : public HydroModel, public RunNotes {
 public:
  explicit ResistanceModel(ModelSettings settings) : settings_(settings), pcg_(settings.preconditioner) {
    pcg_.set_shifts(settings_.ic_shifts);
    pcg_.set_row_order(settings_.ic_order);
  }

  double pair_range(const System& system) const override;
  std::vector<std::string> configure(const System& system, const HydroRequest& request) override;
  void assemble(const System& system, const NodePairList& pairs) override;
  void brownian_force(const System& system, const NodePairList& pairs, const RandomStream& noise, double dt,
                      double* FB) override;
  void solve(const System& system, const double* F, double* dU) override;
  SolveStats last_solve() const override { return stats_; }
  bool provides_stresslets() const override { return true; }
  Eigen::Matrix3d stresslet_sum(const System& system, const NodePairList& pairs, const double* dU) override;
  // The matrix the carried preconditioner was built from (empty without one); restore_state
  // rebuilds the identical factor from it.
  std::vector<double> save_state() const override;
  void restore_state(const std::vector<double>& state) override;
  // Run-log lines: the chosen preconditioner broke down and another one took over (the first
  // time in full, then at the 2nd, 4th, 8th, ... breakdown with the counts so far).
  std::vector<std::string> take_notes() override;

  // For tests: the assembled R_FU and R_FE:E_inf.
  const BlockSparseMatrix& resistance() const { return current(); }
  const std::vector<double>& strain_force() const { return strain_force_; }
  const BodyResistance& lubrication() const { return lub_; }
  // The preconditioner of the last factorisation (settings' choice, or the fallback it needed).
  Preconditioner active_preconditioner() const { return pcg_.active(); }

 private:
  ModelSettings settings_;
  HydroRequest request_;
  Eigen::Matrix3d E_ = Eigen::Matrix3d::Zero();
  IsotropicResistance iso_;
  BodyResistance lub_;
  BlockSparseMatrix A_;
  BlockPCG pcg_;
  std::vector<double> strain_force_, rhs_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> body_pairs_;  // pattern scratch
  SolveStats stats_;
  // The matrix the current preconditioner was built from (kept for the reuse test and for
  // checkpoints). A new factor is built from the R just assembled by swapping the two matrices
  // (no copy of R: at N = 64000 that was 2 x 112 MB of memory traffic a step); the next assembly
  // then writes into A_, which gets the current pattern from factor_source_ if it had an older one.
  BlockSparseMatrix factor_source_;
  bool current_is_source_ = false;   // the last assembly's R is factor_source_ (swapped), else A_
  std::uint64_t pairs_pattern_ = 0;  // pattern_id of the current pair list's pattern
  const BlockSparseMatrix& current() const { return current_is_source_ ? factor_source_ : A_; }
  mutable std::vector<double> row_change_;  // reuse_factor() scratch (EisenstatDilu)
  bool has_factor_ = false;
  bool reuse_factor() const;
  // Builds the preconditioner from factor_source_ and notes a change of the one in use.
  void factorise();
  bool falling_back_ = false;  // the last factorisation needed a shift or a fallback
  std::int64_t factorisations_ = 0, fallbacks_ = 0, jacobi_fallbacks_ = 0, shifted_ = 0, breakdowns_ = 0;
  std::vector<std::string> notes_;
  bool configured_ = false;
};

}  // namespace fldsim::hydro
