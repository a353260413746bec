// The expectation text is what every validation error prints; check it word for word.
#include <gtest/gtest.h>

#include "fldsim/params.hpp"

namespace {

TEST(ParamSchema, ExpectationTextForEachTypeAndRange) {
  fldsim::ParamSchema s;
  EXPECT_EQ(s.number("cutoff", 2.5, "a", "").greater(2).expectation(), "a number > 2");
  EXPECT_EQ(s.integer("steps", 10, "steps", "").at_least(1).expectation(), "an integer >= 1");
  EXPECT_EQ(s.number("phi", 0.3, "", "").at_least(0).less(0.74).expectation(), "a number >= 0 and < 0.74");
  EXPECT_EQ(s.number("x", std::nullopt, "", "").at_most(1e-6).expectation(), "a number <= 1e-06");
  EXPECT_EQ(s.number("free", 0.0, "", "").expectation(), "a number");
  EXPECT_EQ(s.flag("brownian", true, "").expectation(), "true or false");
  EXPECT_EQ(s.text("label", std::string("x"), "").expectation(), "a string");
  EXPECT_EQ(s.choice("method", std::string("lammps"), {"jeffrey_onishi", "lammps"}, "").expectation(),
            "one of: jeffrey_onishi, lammps");
  EXPECT_EQ(s.numbers("box", std::nullopt, "a", "").length(3).expectation(), "a list of 3 numbers");
  EXPECT_EQ(s.numbers("radii", std::nullopt, "a", "").greater(0).expectation(), "a list of numbers > 0");
  EXPECT_EQ(s.table("spheres", std::nullopt, "a", "").length(4).expectation(), "a list of rows of 4 numbers");
}

TEST(ParamSchema, FindAndDefaults) {
  fldsim::ParamSchema s;
  s.number("a", std::nullopt, "a", "radius").greater(0);
  s.integer("n", 7, "", "count");
  ASSERT_EQ(s.specs().size(), 2u);
  ASSERT_NE(s.find("a"), nullptr);
  EXPECT_FALSE(s.find("a")->default_value.has_value());  // absent default = required
  ASSERT_NE(s.find("n"), nullptr);
  EXPECT_EQ(std::get<long>(*s.find("n")->default_value), 7);
  EXPECT_EQ(s.find("missing"), nullptr);
  // Redeclaring a key replaces it rather than listing it twice.
  s.integer("n", 9, "", "count");
  EXPECT_EQ(s.specs().size(), 2u);
  EXPECT_EQ(std::get<long>(*s.find("n")->default_value), 9);
}

TEST(ParamSchema, TypeNames) {
  EXPECT_STREQ(fldsim::to_string(fldsim::ParamType::Number), "number");
  EXPECT_STREQ(fldsim::to_string(fldsim::ParamType::Integer), "integer");
  EXPECT_STREQ(fldsim::to_string(fldsim::ParamType::Flag), "flag");
  EXPECT_STREQ(fldsim::to_string(fldsim::ParamType::Text), "text");
  EXPECT_STREQ(fldsim::to_string(fldsim::ParamType::Choice), "choice");
  EXPECT_STREQ(fldsim::to_string(fldsim::ParamType::NumberList), "number list");
  EXPECT_STREQ(fldsim::to_string(fldsim::ParamType::NumberTable), "number table");
}

}  // namespace
