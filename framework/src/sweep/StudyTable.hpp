// The study table of a sweep: one row per point with its axis values and every steady-state
// result of its run (value, standard error, plateau flag), written as study.csv and study.h5 in
// the sweep's output folder (docs/sweep.md). tools/plot_study.py draws figures from it.
#pragma once

#include <string>
#include <vector>

#include "sweep/SweepPoints.hpp"

namespace fldsim {

struct StudyFiles {
  std::string csv, h5;
  std::size_t rows = 0, with_results = 0;
};

// Reads each point's result file (points without one are listed with status "missing" and no
// results) and writes both files atomically (temporary name, then rename).
StudyFiles write_study_table(const SweepPlan& plan);

}  // namespace fldsim
