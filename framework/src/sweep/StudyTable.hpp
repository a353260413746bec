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
  std::size_t rows = 0, with_results = 0;  // with_results: finished runs
  std::size_t partial = 0;                 // interrupted runs (partial results, flagged)
};

// Reads each point's result file and writes both files atomically (temporary name, then
// rename). Status per point: done; interrupted (a signal stopped its run: partial results, listed
// but flagged); unfinished (only a checkpoint); missing; unreadable.
StudyFiles write_study_table(const SweepPlan& plan);

}  // namespace fldsim
