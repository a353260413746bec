// Fast Lubrication Dynamics (Kumar & Higdon 2010): R_FU = R_0(phi) + R_delta, with the isotropic
// R_0(phi) of the LAMMPS pair_lubricateU fit, phi = the true volume fraction of the system.
#include "ResistanceModel.hpp"
#include "fldsim/plugin.hpp"

namespace {

class Fld : public fldsim::hydro::ResistanceModel {
 public:
  static void describe(fldsim::ParamSchema& s) {
    fldsim::hydro::describe_lubrication_params(s);
    s.choice("isotropic", std::string("sphere"), {"sphere", "body"},
             "R_0 per body: a sphere of the node radius, or the body's own free-draining resistance; both "
             "scaled by the phi fit");
  }
  explicit Fld(const fldsim::Params& p) : ResistanceModel(settings(p)) {}

 private:
  static fldsim::hydro::ModelSettings settings(const fldsim::Params& p) {
    auto s = fldsim::hydro::read_lubrication_params(p);
    s.lubrication = true;
    s.phi_fit = true;
    s.isotropic = p.text("isotropic") == "body" ? fldsim::hydro::IsotropicForm::Body
                                                : fldsim::hydro::IsotropicForm::Sphere;
    return s;
  }
};

}  // namespace

FLDSIM_PLUGIN(hydro, Fld, "fld", "1.0.0",
              "Fast Lubrication Dynamics: lubrication plus R_0(phi) (Kumar & Higdon 2010)")
