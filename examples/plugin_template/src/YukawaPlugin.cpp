// Registers the force law with fldsim: exports the plain descriptor (API version, kind "force",
// name "yukawa", version, summary, build tag) and the describe/create entry points.
#include <fldsim/plugin.hpp>

#include "YukawaForce.hpp"

FLDSIM_PLUGIN(force, yukawa::YukawaForce, "yukawa", "1.0.0",
              "screened electrostatic (Yukawa/DLVO) repulsion between nodes, cut at a few Debye lengths")
