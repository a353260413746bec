// Where a validated value came from ("file:line:col" or "--set KEY=VALUE", and its dotted key
// path), for checks made after validation that report at the value's own place.
#pragma once

#include <string>

#include "fldsim/params.hpp"

namespace fldsim {

// Params keeps origins private and shows them only in the messages of Params::fail; this reads
// them back from such a message (the public plugin header stays as it is).
ParamOrigin origin_of(const Params& params, const std::string& name);

}  // namespace fldsim
