// An SPD 4-cycle on which block IC(0) breaks down in most row orders: the fill it drops leaves the
// last pivot negative (Kershaw's kind of example, J. Comput. Phys. 26, 43 (1978)). Minimum
// eigenvalue 0.40. Used times the 6x6 identity, so the block factorisations are the scalar ones.
#pragma once

namespace fldsim::hydro::test {
constexpr double kKershawCycle[4][4] = {{6, 0, 2, 4}, {0, 5, -2, 3}, {2, -2, 2, 0}, {4, 3, 0, 6}};
}  // namespace fldsim::hydro::test
