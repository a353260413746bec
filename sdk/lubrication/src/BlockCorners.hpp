// Writers of a 6 x 6 block's 3 x 3 corners, for the closed-form Gram blocks (LubricationPair.cpp's
// centred_corners, BodyResistance.cpp's offset_corners): corner(row, column, value) assigns the
// value to the corner or adds it, so one formula fills a pair's own blocks or adds into R's with the
// same values element for element. Private to the lubrication library (not installed).
#pragma once

#include "fldsim/rigid.hpp"

namespace fldsim::hydro {

inline auto assigning(Mat6& M) {
  return [&M](int r, int c, const auto& v) { M.block<3, 3>(r, c) = v; };
}
inline auto adding(Mat6& M) {
  return [&M](int r, int c, const auto& v) { M.block<3, 3>(r, c) += v; };
}

}  // namespace fldsim::hydro
