// Pairwise lubrication (Jeffrey-Onishi near-field modes between visible node pairs) plus the
// isolated-sphere drag of the node radius per body, without the FLD phi correction.
#include "fldsim-sdk/lubrication/ResistanceModel.hpp"
#include "fldsim/plugin.hpp"

namespace {

class Lubrication : public fldsim::hydro::ResistanceModel {
 public:
  static void describe(fldsim::ParamSchema& s) { fldsim::hydro::describe_lubrication_params(s); }
  explicit Lubrication(const fldsim::Params& p) : ResistanceModel(settings(p)) {}

 private:
  static fldsim::hydro::ModelSettings settings(const fldsim::Params& p) {
    auto s = fldsim::hydro::read_lubrication_params(p);
    s.lubrication = true;
    s.isotropic = fldsim::hydro::IsotropicForm::Sphere;
    return s;
  }
};

}  // namespace

FLDSIM_PLUGIN(hydro, Lubrication, "lubrication", "1.1.0",
              "pairwise lubrication plus isolated-sphere drag (no phi correction)")
