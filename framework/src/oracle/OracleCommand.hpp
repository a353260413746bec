// `fldsim oracle FILE.yaml`: the exact equilibrium (Pe = 0) of the experiment's force potential
// for its shape, N and phi, by Metropolis Monte Carlo (EquilibriumOracle). Writes g(r) of body
// centres and of nodes with block errors to a CSV file and prints the compressibility factor Z
// (molecular virial), the node-node Z for comparison and the contact value.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace fldsim {

extern const char* const kOracleHelp;

// Exit code 0 on success; throws ConfigError (bad input, exit 2) or Error (exit 1).
int oracle_command(const std::vector<std::string>& args, std::ostream& out, std::ostream& log);

}  // namespace fldsim
