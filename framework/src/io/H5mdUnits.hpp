// Unit strings of the result file in the grammar of the H5MD units module (nongnu.org/h5md/
// modules/units.html): unit factors separated by spaces, each a symbol with an optional signed
// power ("a+2 D0-1"), at most one leading number ("6 pi mu gammadot"). fldsim's symbols are
// reduced units, named in the module's `system` attribute (kUnitSystem).
#pragma once

#include <string>

namespace fldsim::io {

inline constexpr const char* kUnitSystem =
    "fldsim reduced units: a = node radius (length), kT = thermal energy, mu = solvent viscosity, "
    "D0 = kT/(6 pi mu a), gammadot = shear rate, pi = 3.14159..., rad = radian; a time series' "
    "time is in the run's time unit (a+2 D0-1 or gammadot-1, /parameters time_unit)";

// "kT/a^3" -> "kT a-3", "a^2/D0" -> "a+2 D0-1", "1/gammadot" -> "gammadot-1", "6*pi*mu*gammadot"
// -> "6 pi mu gammadot", "rad" -> "rad", "1" -> "1"; "" stays "" (dimensionless: no attribute).
// Text that is not a product of powers (spaces, brackets) is returned unchanged.
std::string h5md_unit(const std::string& text);

}  // namespace fldsim::io
