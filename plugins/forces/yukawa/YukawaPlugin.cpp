#include "ScreenedRepulsion.hpp"
#include "fldsim/plugin.hpp"

FLDSIM_PLUGIN(force, fldsim::ScreenedRepulsion, "yukawa", "1.0.0",
              "screened (Yukawa) repulsion between sphere surfaces, LAMMPS's pair yukawa/colloid")
