// Small helpers shared by the observers to write a blocked average and a vector.
#pragma once

#include <string>
#include <vector>

#include "fldsim-sdk/statistics/BlockAverage.hpp"
#include "fldsim/results.hpp"

namespace fldsim::observers {

// Writes mean and plateau SE; notes in the description when blocking found no plateau (`fldsim
// summary` flags a row by that phrase, io/Summary.cpp kNoPlateau: keep the two in step).
inline void write_blocked(ResultSink& out, const std::string& path, const BlockAverage& b,
                          const std::string& unit, const std::string& description, double scale = 1.0,
                          double shift = 0.0) {
  std::string d = description + " (mean over " + std::to_string(b.count()) +
                  " samples; SE by Flyvbjerg-Petersen blocking" +
                  (b.converged() ? ")" : ", no plateau reached: SE is a lower bound)");
  out.write_scalar(path, scale * b.mean() + shift, std::abs(scale) * b.stderr_mean(), unit, d);
}

inline void write_vector(ResultSink& out, const std::string& path, const std::vector<double>& v,
                         const std::string& unit, const std::string& description) {
  out.write_array(path, {v.size()}, v.data(), unit, description);
}

}  // namespace fldsim::observers
