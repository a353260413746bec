// Unit strings in the H5MD units-module grammar (nongnu.org/h5md/modules/units.html): factors
// separated by spaces, signed powers, one leading number. Exact expected strings.
#include <gtest/gtest.h>

#include "io/H5mdUnits.hpp"

namespace fldsim::io {
namespace {

TEST(H5mdUnits, ProductsOfPowersFollowTheModuleGrammar) {
  EXPECT_EQ(h5md_unit("a"), "a");
  EXPECT_EQ(h5md_unit("a^2"), "a+2");
  EXPECT_EQ(h5md_unit("a^2/D0"), "a+2 D0-1");
  EXPECT_EQ(h5md_unit("1/gammadot"), "gammadot-1");
  EXPECT_EQ(h5md_unit("D0/a^2"), "D0 a-2");
  EXPECT_EQ(h5md_unit("kT/a^3"), "kT a-3");
  EXPECT_EQ(h5md_unit("6*pi*mu*gammadot"), "6 pi mu gammadot");
  EXPECT_EQ(h5md_unit("a*a"), "a+2");  // a symbol occurs once
  EXPECT_EQ(h5md_unit("rad"), "rad");
  EXPECT_EQ(h5md_unit("1"), "1");
}

TEST(H5mdUnits, DimensionlessIsEmptyAndProseIsKept) {
  EXPECT_EQ(h5md_unit(""), "");
  EXPECT_EQ(h5md_unit("6*pi*mu/t0 (internal time unit t0)"), "6*pi*mu/t0 (internal time unit t0)");
}

}  // namespace
}  // namespace fldsim::io
