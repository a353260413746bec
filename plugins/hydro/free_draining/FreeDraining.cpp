// Free draining: every node has the isolated-sphere drag 6 pi mu a, 8 pi mu a^3 and sits in the
// ambient strain; a body's resistance is the rigid-body sum over its nodes. No interactions
// between bodies, so each body is solved directly (6x6 Cholesky).
#include "fldsim-sdk/lubrication/ResistanceModel.hpp"
#include "fldsim/plugin.hpp"

namespace {

fldsim::hydro::ModelSettings free_draining_settings() {
  fldsim::hydro::ModelSettings s;
  s.lubrication = false;
  s.isotropic = fldsim::hydro::IsotropicForm::NodeSum;
  return s;
}

class FreeDraining : public fldsim::hydro::ResistanceModel {
 public:
  static void describe(fldsim::ParamSchema&) {}
  explicit FreeDraining(const fldsim::Params&) : ResistanceModel(free_draining_settings()) {}
};

}  // namespace

FLDSIM_PLUGIN(hydro, FreeDraining, "free_draining", "1.0.0",
              "isolated-sphere drag on every node, no hydrodynamic interactions")
