// Params getters and fail(): the error format plugins rely on for their own checks.
#include <gtest/gtest.h>

#include "fldsim/params.hpp"

namespace {

fldsim::Params sample() {
  fldsim::Params p("system.shape", "exp.yaml:4:10");
  p.set("c", 0.2, {"exp.yaml:4:30", "system.shape.c"});
  p.set("count", 7L, {"exp.yaml:5:10", "system.count"});
  p.set("a", 1.0, {"exp.yaml:4:10", "system.shape.a"}, false);  // a default
  return p;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const fldsim::ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Params, FailNamesLocationAndPath) {
  const fldsim::Params p = sample();
  EXPECT_EQ(error_of([&] { p.fail("c", "must be < a + b"); }),
            "exp.yaml:4:30: system.shape.c: must be < a + b");
  // A key without an origin falls back to the block's location and path.
  EXPECT_EQ(error_of([&] { p.fail("b", "must be set with c"); }),
            "exp.yaml:4:10: system.shape.b: must be set with c");
}

TEST(Params, GettersCheckTypes) {
  const fldsim::Params p = sample();
  EXPECT_EQ(p.number("c"), 0.2);
  EXPECT_EQ(p.integer("count"), 7);
  EXPECT_EQ(p.number("count"), 7.0);  // an integer reads as a number
  EXPECT_TRUE(p.given("c"));
  EXPECT_FALSE(p.given("a"));
  EXPECT_FALSE(p.given("nothing"));
  EXPECT_EQ(error_of([&] { p.integer("c"); }), "exp.yaml:4:30: system.shape.c: is a number, not an integer");
  EXPECT_EQ(error_of([&] { p.text("count"); }), "exp.yaml:5:10: system.count: is an integer, not a string");
  EXPECT_EQ(error_of([&] { p.number("zz"); }),
            "exp.yaml:4:10: system.shape.zz: no such parameter (the plugin reads a key its schema does not "
            "declare)");
}

}  // namespace
