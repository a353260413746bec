#include <gtest/gtest.h>

#include "config/DidYouMean.hpp"

namespace {

TEST(DidYouMean, EditDistanceKnownValues) {
  // Classic examples: kitten -> sitting needs 3 edits (Levenshtein 1966); a transposition costs
  // 1 in the optimal-string-alignment distance (Damerau 1964).
  EXPECT_EQ(fldsim::edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(fldsim::edit_distance("fdl", "fld"), 1u);
  EXPECT_EQ(fldsim::edit_distance("", "abc"), 3u);
  EXPECT_EQ(fldsim::edit_distance("cutoff", "cutoff"), 0u);
}

TEST(DidYouMean, Suggestions) {
  const std::vector<std::string> hydro = {"fld", "free_draining", "lubrication"};
  EXPECT_EQ(fldsim::did_you_mean("fdl", hydro), "fld");
  EXPECT_EQ(fldsim::did_you_mean("lubricaton", hydro), "lubrication");
  EXPECT_EQ(fldsim::did_you_mean("free", hydro), "free_draining");  // prefix
  EXPECT_EQ(fldsim::did_you_mean("stokesian", hydro), "");
  EXPECT_EQ(fldsim::did_you_mean("Cutoff", {"cutoff", "skin"}), "cutoff");  // case only
  EXPECT_EQ(fldsim::did_you_mean("lamps", {"jeffrey_onishi", "lammps"}), "lammps");
  EXPECT_EQ(fldsim::did_you_mean("", hydro), "");
}

}  // namespace
