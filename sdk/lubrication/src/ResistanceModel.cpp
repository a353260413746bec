#include "fldsim-sdk/lubrication/ResistanceModel.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <sstream>
#include <utility>

#include "fldsim/error.hpp"
#include "fldsim/number_text.hpp"
#include "fldsim/parallel_loop.hpp"

namespace fldsim::hydro {

namespace {
// The `preconditioner` key's values, for reading it and for the run log.
constexpr std::pair<Preconditioner, const char*> kPreconditionerNames[] = {
    {Preconditioner::IncompleteCholesky, "incomplete_cholesky"},
    {Preconditioner::EisenstatDilu, "eisenstat_dilu"},
    {Preconditioner::BlockJacobi, "block_jacobi"}};
constexpr std::pair<RowOrder, const char*> kRowOrderNames[] = {{RowOrder::Automatic, "auto"},
                                                               {RowOrder::StiffnessGraded, "stiffness"},
                                                               {RowOrder::CuthillMcKee, "cuthill_mckee"}};

std::string preconditioner_name(Preconditioner p) {
  for (const auto& [kind, name] : kPreconditionerNames)
    if (kind == p) return name;
  return "block_jacobi";
}

// Coefficients of fldsim's R_0(phi) fits (see isotropic_factors).
// f_t from tests/calibration/FitIsotropicResistance.cpp (N = 500, 3 configurations x 16 draws per
// phi, Newton to |d_s - target| < 2e-4 at phi = 0.1 ... 0.5); f_r is Kumar & Higdon's (fitting it
// to d_r drives it to zero by phi = 0.4, see docs/fld-r0-fit.md).
// f_t and f_s as cubics 1 + c1 phi + c2 phi^2 + c3 phi^3 (a quadratic through f(0) = 1 misses the
// tapered f_t, which first rises, by 4 %); f_r quadratic.
struct FldsimFit {
  double t1, t2, t3;  // f_t
  double r1, r2;      // f_r
  double s1, s2, s3;  // f_s
};
// The abrupt cutoff (taper: none): f_t refitted, f_s Kumar & Higdon's (never refitted for it).
constexpr FldsimFit kFldsimFitAbrupt{0.5361, -4.6621, 0.0, 0.749, -2.469, 3.64, -6.95, 0.0};
// The default smooth taper (width kDefaultTaperWidth) and contact strain arm: f_t to d_s and f_s
// to Riest et al.'s high-frequency viscosity eta'_inf (docs/fld-r0-fit.md).
constexpr FldsimFit kFldsimFitTapered{0.3788, 1.9794, -10.5060, 0.749, -2.469, 0.7956, 6.3030, -17.2213};
// Width of the default smooth taper, in a (chosen by measurement: docs/lubrication-taper.md).
constexpr double kDefaultTaperWidth = 0.3;
}  // namespace

void describe_lubrication_params(ParamSchema& s) {
  s.choice("conventions", std::string("fldsim"), {"fldsim", "lammps"},
           "pair forms: fldsim's defaults, or exactly LAMMPS pair lubricateU (pump lammps, twist false, "
           "lever contact, strain_arm contact, taper none, and for fld r0_fit kumar_higdon); keys set "
           "explicitly must agree with the preset");
  s.number("cutoff", 2.5, "a",
           "node centre distance below which a node pair is lubricated (scaled by the mean radius)")
      .greater(2.0)
      .less(3.0);
  s.choice("taper", std::string("smooth"), {"smooth", "none"},
           "switch-off of the pair terms below the cutoff: smooth (C2 over taper_width: the mobility is "
           "continuous, so the thermal drift sees no jump) or none (abrupt, as LAMMPS: a mobility jump at "
           "the cutoff that distorts g(r) there by -18 %..+5 %; docs/lubrication-taper.md)");
  s.number("taper_width", kDefaultTaperWidth, "a",
           "width of the smooth taper below the cutoff (fld's r0_fit fldsim is calibrated at the default)")
      .greater(0.0)
      .at_most(0.5);
  s.choice("visibility", std::string("sharp"), {"sharp", "smooth"},
           "node-pair visibility of multi-node bodies (Kumar & Higdon 2.1.1): sharp (on/off, as the paper: "
           "the resistance jumps when an exit point crosses a sibling node's surface) or smooth (pairs "
           "weighted by a C2 step over exit depths of visibility_width; docs/lubrication-taper.md)");
  s.number("visibility_width", 0.1, "a", "width of the smooth visibility step (exit-point depth)")
      .greater(0.0)
      .at_most(0.5);
  s.number("delta_num", 1e-5, "a", "gaps below this are evaluated at this gap").greater(0.0).less(0.1);
  s.choice(
      "pump", std::string("jeffrey_onishi"), {"jeffrey_onishi", "lammps", "none"},
      "counter-rotation (pump) coefficient: Jeffrey-Onishi (3/40), LAMMPS lubricateU (3/160), or none (no "
      "pump mode: an ablation for measuring what the mode does, not a model of two spheres)");
  s.flag("twist", true, "include the twist mode (relative rotation about the line of centres)");
  s.flag("log_terms", true,
         "include the log(1/gap) terms: false keeps the squeeze mode's 1/gap term alone (no shear or pump "
         "mode; the twist mode stays as twist says), as LAMMPS pair lubricateU with flaglog 0; fld's R_0 "
         "then uses Kumar & Higdon's fit made for it (r0_fit kumar_higdon)");
  s.choice("lever", std::string("centre"), {"centre", "contact"},
           "shear-mode lever arms: centre (r a_i/(a_i+a_j), sums to r: rigid rotation is force-free) "
           "or contact (the node radii, as LAMMPS); docs/two-body.md");
  s.choice("strain_arm", std::string("contact"), {"centre", "contact"},
           "ambient strain seen by a pair: contact, the body-centre separation less the node gap (for "
           "spheres the contact distance (a_i+a_j) d, as LAMMPS; closer to the exact two-sphere A, B, C), "
           "or centre, E R_ij with the body-centre separation; docs/two-body.md");
  s.number("tolerance", 1e-6, "",
           "relative residual of the conjugate-gradient solve, |b - R U| <= tolerance |b| with R in double "
           "precision (where R takes 8 MB or more, N of about 8000 and up, CG's products use a "
           "single-precision copy of R and the rule is checked with R itself: bench/README.md)")
      .greater(0.0)
      .less(1.0);
  s.integer("max_iterations", 1000L, "", "conjugate-gradient iteration limit").at_least(1).at_most(1000000);
  s.number("refactor_threshold", 0.15, "",
           "an assembly reuses the last CG preconditioner (IC(0) factor or D-ILU pivots), within the "
           "step and across steps, while R has moved by at most this fraction since it was built: its "
           "diagonal blocks in one Frobenius norm over all bodies (incomplete_cholesky), or each body's "
           "block row against its diagonal block (eisenstat_dilu, also as IC(0)'s fallback; there the "
           "measured best is 0.3); 0: rebuild "
           "at every assembly. The matrix it was built from is saved in checkpoints, so --resume stays "
           "bit-exact")
      .at_least(0.0)
      .at_most(10.0);
  s.choice("preconditioner", std::string("incomplete_cholesky"),
           {"incomplete_cholesky", "eisenstat_dilu", "block_jacobi"},
           "CG preconditioner: incomplete_cholesky (block IC(0) on the pair pattern plus the fill inside "
           "clusters of bodies in stiff near contact, whose loops IC(0) would leave to the iterations, "
           "factorised in reverse "
           "Cuthill-McKee order of the pair graph whatever the bodies' numbering; where IC(0) breaks down, "
           "a pivot block not positive definite, that factorisation is retried with the diagonal shifts "
           "of ic_shifts and, if none works, uses eisenstat_dilu; the run log notes it: the first time, "
           "then with counts at the 2nd, 4th, 8th, ... time), eisenstat_dilu "
           "(block D-ILU on the pair pattern applied with "
           "Eisenstat's trick: no product with R inside an "
           "iteration, but double-precision sweeps over R's own blocks and more iterations where R "
           "moves fast: 3-19 % slower per step than IC(0), whose sweeps compute in single precision, "
           "in every scene measured (dicolloids at Pe <= 10 and LAMMPS's documented sphere scene, one "
           "thread; bench/README.md \"Single-precision IC(0) sweeps\")) or "
           "block_jacobi (more iterations); the sweeps of the first two run parallel by dependency levels");
  s.numbers("ic_shifts",
            std::vector<double>(BlockPCG::kDefaultShifts.begin(), BlockPCG::kDefaultShifts.end()), "",
            "where IC(0) breaks down: factorise R + alpha diag(R) for each alpha in turn (Manteuffel's "
            "shifted incomplete Cholesky) before falling back to eisenstat_dilu; [] falls back at once. The "
            "shift changes the preconditioner only, never the solution's tolerance (1000 fused dumbbells "
            "sheared 500 strains at kT = 0: 59.6 CG iterations a step against 79.7 with the fallback; "
            "bench/README.md \"Shifted IC(0)\")");
  s.choice("ic_order", std::string("auto"), {"auto", "stiffness", "cuthill_mckee"},
           "row order of the IC(0) factor: cuthill_mckee (reverse Cuthill-McKee of the pair graph, "
           "whatever the bodies' numbering), stiffness (that order graded by each body's total "
           "resistance, the softest bodies first and those in stiff near contact last, so that the fill "
           "IC(0) drops is that of soft rows: 1000 fused dumbbells sheared at kT = 0 or Pe 1000 need "
           "27-29 % fewer CG iterations and IC(0) nearly stops breaking down; near equilibrium -9 to +5 "
           "%) or auto: stiffness where R takes less than 8 MB (N up to about 8000) and the median "
           "body's resistance is at least 5 times the smallest (a contact network), else "
           "cuthill_mckee (beyond the caches the graded rows' scattered memory costs more than the "
           "iterations save); bench/README.md \"IC(0) rows graded by stiffness\"");
}

bool lammps_conventions(const Params& p) {
  return p.text("conventions") == "lammps";
}

const std::string& convention_choice(const Params& p, const std::string& key, const std::string& preset) {
  if (!lammps_conventions(p)) return p.text(key);
  if (p.given(key) && p.text(key) != preset)
    p.fail(key, "'" + p.text(key) + "' contradicts conventions: lammps (which sets " + key + ": " + preset +
                    "); remove one of the two");
  static thread_local std::string value;
  value = preset;
  return value;
}

ModelSettings read_lubrication_params(const Params& p) {
  ModelSettings s;
  const bool lammps = lammps_conventions(p);
  s.lub.cutoff = p.number("cutoff");
  s.lub.delta_num = p.number("delta_num");
  const std::string& pump = convention_choice(p, "pump", "lammps");
  s.lub.pump = pump == "lammps" ? PumpForm::Lammps
               : pump == "none" ? PumpForm::None
                                : PumpForm::JeffreyOnishi;
  if (lammps && p.given("twist") && p.flag("twist"))
    p.fail("twist", "true contradicts conventions: lammps (which has no twist mode); remove one of the two");
  s.lub.twist = lammps ? false : p.flag("twist");
  s.lub.log_terms = p.flag("log_terms");
  s.lub.lever = convention_choice(p, "lever", "contact") == "contact" ? Lever::Contact : Lever::Centre;
  s.lub.strain_arm =
      convention_choice(p, "strain_arm", "contact") == "contact" ? StrainArm::Contact : StrainArm::Centre;
  s.lub.taper_width = convention_choice(p, "taper", "none") == "none" ? 0.0 : p.number("taper_width");
  s.lub.visibility_width = p.text("visibility") == "smooth" ? p.number("visibility_width") : 0.0;
  if (s.lub.taper_width >= s.lub.cutoff - 2.0)
    p.fail("taper_width", "must be smaller than cutoff - 2 (the taper would reach contact)");
  s.tolerance = p.number("tolerance");
  s.max_iterations = int(p.integer("max_iterations"));
  for (const auto& [kind, name] : kPreconditionerNames)
    if (p.text("preconditioner") == name) s.preconditioner = kind;
  s.ic_shifts = p.numbers("ic_shifts");
  for (const auto& [kind, name] : kRowOrderNames)
    if (p.text("ic_order") == name) s.ic_order = kind;
  for (std::size_t k = 0; k < s.ic_shifts.size(); ++k)
    if (!(s.ic_shifts[k] > 0.0 && s.ic_shifts[k] <= 100.0) || (k > 0 && s.ic_shifts[k] <= s.ic_shifts[k - 1]))
      p.fail("ic_shifts", "expected increasing shifts in (0, 100], e.g. [0.01, 0.04, 0.16, 0.64]");
  // D-ILU's threshold is per block row (reuse_factor); 0.3 measured over five scenes (bench/README.md,
  // "Eisenstat": 0.2 refactors too often on spheres, 0.5 too seldom for dicolloids at Pe 1000).
  s.refactor_threshold = p.given("refactor_threshold") || s.preconditioner != Preconditioner::EisenstatDilu
                             ? p.number("refactor_threshold")
                             : 0.3;
  return s;
}

IsotropicFactors isotropic_factors(IsotropicFit fit, double phi, bool tapered) {
  switch (fit) {
    case IsotropicFit::None:
      return {};
    case IsotropicFit::KumarHigdon:
      // R0, RT0, RS0 of LAMMPS pair_lubricateU init_style() with flaglog = 1 (Kumar & Higdon 2010).
      return {1.0 + 2.725 * phi - 6.583 * phi * phi, 1.0 + 0.749 * phi - 2.469 * phi * phi,
              1.0 + 3.64 * phi - 6.95 * phi * phi};
    case IsotropicFit::KumarHigdonSqueeze:
      // The same source with flaglog = 0 (squeeze 1/xi alone): R0 and RS0 refitted, RT0 unscaled.
      return {1.0 + 2.16 * phi, 1.0, 1.0 + 3.33 * phi + 2.80 * phi * phi};
    case IsotropicFit::Fldsim:
      // Refit for fldsim's Jeffrey-Onishi forms (pump 3/40, twist, cutoff 2.5 a), so that hard-sphere
      // suspensions reproduce d_s = 1 - 1.8315 phi (1 + 0.12 phi - 0.70 phi^2) (Riest et al. 2015)
      // at phi = 0.1 ... 0.5 within 0.01; calibrated for phi <= 0.5 (f_t reaches 0 at phi = 0.52).
      // The rotational factor is Kumar & Higdon's; with the taper the stresslet factor is fitted to
      // eta'_inf as well. Separate fits for the two cutoff forms: the taper removes resistance between
      // 2.2 and 2.5 a that R_0 must then supply. Method and residuals: docs/fld-r0-fit.md.
      {
        const FldsimFit& c = tapered ? kFldsimFitTapered : kFldsimFitAbrupt;
        const double p2 = phi * phi, p3 = p2 * phi;
        return {1.0 + c.t1 * phi + c.t2 * p2 + c.t3 * p3, 1.0 + c.r1 * phi + c.r2 * p2,
                1.0 + c.s1 * phi + c.s2 * p2 + c.s3 * p3};
      }
  }
  return {};
}

double ResistanceModel::pair_range(const System& system) const {
  if (!settings_.lubrication) return 0.0;
  double a = 0.0;
  for (std::size_t k = 0; k < system.nodes_per_body(); ++k) a = std::max(a, system.node_radius(k));
  return settings_.lub.cutoff * a;
}

std::vector<std::string> ResistanceModel::configure(const System& system, const HydroRequest& request) {
  request_ = request;
  const double gd = system.physics().shear_rate;
  E_.setZero();
  E_(0, 1) = E_(1, 0) = 0.5 * gd;  // u = gammadot y e_x: E = sym(grad u)
  const IsotropicFactors f = settings_.fixed_factors
                                 ? *settings_.fixed_factors
                                 : isotropic_factors(settings_.fit, system.physics().volume_fraction,
                                                     settings_.lub.taper_width > 0.0);
  if (f.translation <= 0.0 || f.rotation <= 0.0)
    throw Error("hydro: the R_0(phi) fit (calibrated for phi <= 0.5) is not positive at phi = " +
                number_text(system.physics().volume_fraction));
  iso_ = IsotropicResistance(settings_.isotropic, f);
  iso_.configure(system);
  lub_ = BodyResistance(settings_.lub);
  const std::size_t n = system.size();
  A_.set_pattern(n, {});
  pairs_pattern_ = A_.pattern_id();
  current_is_source_ = false;
  has_factor_ = false;
  strain_force_.assign(6 * n, 0.0);
  rhs_.assign(6 * n, 0.0);
  configured_ = true;

  std::vector<std::string> skipped;
  if (!request.brownian || system.physics().kT == 0.0) skipped.push_back("no Brownian forces (kT = 0)");
  if (!request.shear || gd == 0.0) skipped.push_back("no R_FE:E (no shear)");
  if (!request.stresslets) skipped.push_back("no stresslets (no stress observer)");
  return skipped;
}

void ResistanceModel::assemble(const System& system, const NodePairList& pairs) {
  if (!configured_) throw Error("hydro: assemble() called before configure()");
  const std::size_t n = system.size();
  const bool shear = request_.shear && system.physics().shear_rate != 0.0;
  iso_.update(system, E_, shear);
  current_is_source_ = false;
  const bool new_pairs = settings_.lubrication && (lub_.update(system, pairs) || A_.blocks() != n);
  if (!new_pairs && A_.pattern_id() != pairs_pattern_ && factor_source_.pattern_id() == pairs_pattern_) {
    // A_ held the factor's older source (swapped below); the last assembly wrote the current
    // pattern into the other matrix.
    A_.copy_pattern_from(factor_source_);
  } else if (new_pairs || A_.pattern_id() != pairs_pattern_) {  // (the latter: after a restore)
    lub_.body_pairs(body_pairs_);
    A_.set_pattern_for_overwrite(n, body_pairs_);
    lub_.bind(A_);
    pairs_pattern_ = A_.pattern_id();
  }
  // No zeroing of R (it was 10 % of a sphere assembly, bench/README.md): the diagonal is assigned
  // here and lub_.add_to writes every off-diagonal block of its pattern (without lubrication the
  // pattern has none).
  for (std::size_t i = 0; i < n; ++i) A_.diagonal(i) = iso_.block(i);
  std::fill(strain_force_.begin(), strain_force_.end(), 0.0);
  if (shear)
    for (std::size_t i = 0; i < n; ++i) Eigen::Map<Vec6>(strain_force_.data() + 6 * i) = iso_.strain_force(i);
  if (settings_.lubrication) {
    lub_.add_to(A_);
    if (shear) lub_.add_strain_force(E_, strain_force_.data());
    // The preconditioner only steers CG (it converges to the same tolerance with any SPD one), so a
    // later assembly, of this step or a later one, may keep an older factor: the factor holds its
    // own copy of the pattern it was built on, valid whatever pairs entered or left since. Kept
    // only while R has moved little: with a gap floor of 1e-5 a the 1/h squeeze terms change by
    // O(1) within dt/2 and a stale factor costs more iterations than a new one (bench/README.md).
    // The matrix it was built from is kept (factor_source_) for checkpoints: restore_state
    // rebuilds the same factor from it. It is this R: the two matrices swap roles.
    if (!reuse_factor()) {
      std::swap(A_, factor_source_);
      current_is_source_ = true;
      factorise();
    }
    pcg_.bind(current());  // the values CG's products use (single precision where R is large)
  }
  stats_.pairs = std::int64_t(lub_.size());
}

// True when the last factor may precondition the current R:
// |diag(R) - diag(R_factor)|_F <= refactor_threshold |diag(R_factor)|_F.
bool ResistanceModel::reuse_factor() const {
  if (!has_factor_ || settings_.refactor_threshold <= 0.0 || factor_source_.blocks() != A_.blocks())
    return false;
  const double t2 = settings_.refactor_threshold * settings_.refactor_threshold;
  if (pcg_.active() == Preconditioner::EisenstatDilu) {  // chosen, or IC(0)'s fallback
    // Block row by block row: the old pivots meet the current off-diagonal blocks (EisenstatDilu.hpp),
    // so what spoils a body's pivot is any change in its row, its couplings included (a pair closing
    // in, or dicolloids turning at high Pe), whatever the other bodies do:
    // |dR_ii|^2 + sum_j |dR_ij|^2 <= t^2 |R_ii(factor)|^2 for every body i (a new pair counts whole).
    const std::size_t n = A_.blocks();
    row_change_.assign(n, 0.0);
    const auto& row_start = A_.row_start();
    const auto& col = A_.col();
    for (std::size_t i = 0; i < n; ++i) {
      row_change_[i] += (A_.diagonal(i) - factor_source_.diagonal(i)).squaredNorm();
      for (std::int64_t a = row_start[i]; a < row_start[i + 1]; ++a) {
        const std::uint32_t j = col[std::size_t(a)];
        const std::int64_t old = factor_source_.find(std::uint32_t(i), j);
        const double c =
            old < 0 ? A_.upper(a).squaredNorm() : (A_.upper(a) - factor_source_.upper(old)).squaredNorm();
        row_change_[i] += c;
        row_change_[j] += c;
      }
    }
    for (std::size_t i = 0; i < n; ++i)
      if (row_change_[i] > t2 * factor_source_.diagonal(i).squaredNorm()) return false;
    return true;
  }
  double change = 0.0, size = 0.0;
  for (std::size_t i = 0; i < A_.blocks(); ++i) {
    change += (A_.diagonal(i) - factor_source_.diagonal(i)).squaredNorm();
    size += factor_source_.diagonal(i).squaredNorm();
  }
  return change <= t2 * size;
}

// [-2 (the format), n, pairs, (i, j) of each upper block, the n diagonal blocks, the upper blocks,
// k, the preconditioner's own state]: the factor's source matrix, blocks column-major, and the k
// numbers of BlockPCG::preconditioner_state (IC(0)'s row order). Empty while there is no factor.
// Format 1 (API 5.1) had no marker and no own state: [n, pairs, ..., the upper blocks].
std::vector<double> ResistanceModel::save_state() const {
  if (!has_factor_) return {};
  const std::size_t n = factor_source_.blocks(), m = factor_source_.col().size();
  std::vector<double> out;
  const std::vector<double> own = pcg_.preconditioner_state();
  out.reserve(4 + 2 * m + 36 * (n + m) + own.size());
  out.push_back(-2.0);
  out.push_back(double(n));
  out.push_back(double(m));
  for (std::size_t i = 0; i < n; ++i)
    for (std::int64_t a = factor_source_.row_start()[i]; a < factor_source_.row_start()[i + 1]; ++a) {
      out.push_back(double(i));
      out.push_back(double(factor_source_.col()[std::size_t(a)]));
    }
  for (std::size_t i = 0; i < n; ++i)
    out.insert(out.end(), factor_source_.diagonal(i).data(), factor_source_.diagonal(i).data() + 36);
  for (std::size_t a = 0; a < m; ++a)
    out.insert(out.end(), factor_source_.upper(std::int64_t(a)).data(),
               factor_source_.upper(std::int64_t(a)).data() + 36);
  out.push_back(double(own.size()));
  out.insert(out.end(), own.begin(), own.end());
  return out;
}

void ResistanceModel::restore_state(const std::vector<double>& state) {
  if (!configured_) throw Error("hydro: restore_state() called before configure()");
  if (state.empty()) return;
  const std::size_t n = A_.blocks();
  // Format 2 starts with -2; format 1 (API 5.1, no marker) resumes correctly but not bit for bit
  // (IC(0)'s row order is computed afresh).
  const bool marked = state[0] == -2.0;
  const std::span<const double> body(state.data() + (marked ? 1 : 0), state.size() - (marked ? 1 : 0));
  auto fail = [](const std::string& what) {
    throw Error("hydro state (the preconditioner's matrix) " + what +
                "; was the system changed since the checkpoint?");
  };
  if (body.size() < 2 || body[0] != double(n)) fail("is for another number of bodies");
  const double pairs = body[1];
  if (!(pairs >= 0.0) || pairs > double(n) * double(n) || pairs != std::floor(pairs)) fail("is malformed");
  const std::size_t m = std::size_t(pairs);
  const std::size_t matrix = 2 + 2 * m + 36 * (n + m);
  std::vector<double> own;
  if (!marked) {
    if (body.size() != matrix) fail("has the wrong size");
  } else {
    const double k = body.size() > matrix ? body[matrix] : -1.0;
    if (!(k >= 0.0) || k != std::floor(k) || body.size() != matrix + 1 + std::size_t(k))
      fail("has the wrong size");
    own.assign(body.begin() + std::ptrdiff_t(matrix + 1), body.end());
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> upper(m);
  for (std::size_t a = 0; a < m; ++a) {
    const double i = body[2 + 2 * a], j = body[3 + 2 * a];
    if (!(i >= 0.0 && i < j && j < double(n)) || i != std::floor(i) || j != std::floor(j))
      fail("is malformed");
    upper[a] = {std::uint32_t(i), std::uint32_t(j)};
  }
  const double* values = body.data() + 2 + 2 * m;
  if (!std::all_of(values, values + 36 * (n + m), [](double v) { return std::isfinite(v); }))
    fail("holds a non-finite value");
  factor_source_.set_pattern(n, upper);
  for (std::size_t i = 0; i < n; ++i) factor_source_.diagonal(i) = Eigen::Map<const Mat6>(values + 36 * i);
  values += 36 * n;
  for (std::size_t a = 0; a < m; ++a) {
    const std::int64_t k = factor_source_.find(upper[a].first, upper[a].second);
    if (k < 0) fail("is malformed");
    factor_source_.upper(k) = Eigen::Map<const Mat6>(values + 36 * a);
  }
  if (!pcg_.restore_preconditioner_state(own, n)) fail("is malformed (the preconditioner's row order)");
  factorise();
}

// BlockPCG::prepare retries IC(0) with diagonal shifts and then falls back (-> D-ILU -> block
// Jacobi) where a factorisation breaks down. That costs CG iterations, not accuracy. A matrix at the
// edge of breaking IC(0) switches back and forth (N = 1000 fused dumbbells at kT = 0 with LAMMPS's
// forms: about 300 breakdowns in 500 strains), so the log gets the first breakdown in full and then
// a line with the counts at the 2nd, 4th, 8th, ... breakdown: a few lines per run, never one per
// factorisation.
void ResistanceModel::factorise() {
  pcg_.prepare(factor_source_);
  has_factor_ = true;
  ++factorisations_;
  const Preconditioner now = pcg_.active();
  const double shift = pcg_.shift();
  if (now == settings_.preconditioner && shift == 0.0) {
    falling_back_ = false;
    return;
  }
  if (shift > 0.0) {
    ++shifted_;
  } else {
    ++fallbacks_;
    if (now == Preconditioner::BlockJacobi) ++jacobi_fallbacks_;
  }
  if (falling_back_) return;
  falling_back_ = true;
  ++breakdowns_;
  if ((breakdowns_ & (breakdowns_ - 1)) != 0) return;  // not a power of two
  const std::string chosen = preconditioner_name(settings_.preconditioner);
  if (breakdowns_ == 1) {
    std::ostringstream line;
    line << chosen << " preconditioner broke down (a pivot block not positive definite); ";
    if (shift > 0.0)
      line << "factorised R + " << shift << " diag(R) instead (a diagonal shift; same tolerance)";
    else
      line << "CG uses " << preconditioner_name(now)
           << " while it does (same tolerance, more iterations per solve)";
    notes_.push_back(line.str());
    return;
  }
  std::string counts = chosen + " preconditioner has broken down " + std::to_string(breakdowns_) +
                       " times: " + std::to_string(factorisations_) + " factorisations, ";
  if (shifted_ > 0) counts += std::to_string(shifted_) + " with a diagonal shift, ";
  notes_.push_back(counts + std::to_string(fallbacks_) + " fell back (" + std::to_string(jacobi_fallbacks_) +
                   " to block_jacobi)");
}

std::vector<std::string> ResistanceModel::take_notes() {
  std::vector<std::string> out;
  out.swap(notes_);
  return out;
}

void ResistanceModel::brownian_force(const System& system, const NodePairList& pairs,
                                     const RandomStream& noise, double dt, double* FB) {
  (void)pairs;
  const std::size_t n = system.size();
  std::fill(FB, FB + 6 * n, 0.0);
  const double kT = system.physics().kT;
  if (!request_.brownian || kT == 0.0) return;
  const double scale = std::sqrt(2.0 * kT / dt);
  parallel_for(std::int64_t(n), [&](std::int64_t i) {
    Vec6 alpha;
    noise.normals(std::uint64_t(i), alpha.data(), 6);
    const Vec6 f = iso_.factor(std::size_t(i)).matrixL() * alpha;
    Eigen::Map<Vec6>(FB + 6 * i) = scale * f;
  });
  if (settings_.lubrication)
    lub_.add_brownian(noise.for_purpose(RandomPurpose::PairNoise), system.nodes_per_body(), scale, FB);
}

void ResistanceModel::solve(const System& system, const double* F, double* dU) {
  const std::size_t n = system.size();
  for (std::size_t k = 0; k < 6 * n; ++k) rhs_[k] = F[k] + strain_force_[k];
  if (!settings_.lubrication) {
    // Free draining: bodies are uncoupled, a direct 6x6 solve each.
    parallel_for(std::int64_t(n), [&](std::int64_t i) {
      Eigen::Map<Vec6>(dU + 6 * i) =
          iso_.factor(std::size_t(i)).solve(Eigen::Map<const Vec6>(rhs_.data() + 6 * i));
    });
    stats_.iterations = 0;
    stats_.residual = 0.0;
    return;
  }
  const auto result = pcg_.solve(current(), rhs_.data(), dU, settings_.tolerance, settings_.max_iterations);
  stats_.iterations = result.iterations;
  stats_.residual = result.relative_residual;
  if (!result.converged) {
    std::ostringstream msg;
    msg << "hydro/" << plugin_name() << ": conjugate gradients did not converge at step " << system.step()
        << ": relative residual " << result.relative_residual << " after " << result.iterations
        << " iterations (tolerance " << settings_.tolerance
        << "; raise hydro.max_iterations or check for overlaps)";
    throw Error(msg.str());
  }
}

Eigen::Matrix3d ResistanceModel::stresslet_sum(const System& system, const NodePairList& pairs,
                                               const double* dU) {
  (void)pairs;
  Eigen::Matrix3d S = iso_.stresslet_sum(system, E_, dU);
  if (settings_.lubrication) S += lub_.stresslet_sum(E_, dU);
  return S;
}

}  // namespace fldsim::hydro
