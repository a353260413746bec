// Checkpoint round trip must be bit-exact (exact restart), including awkward doubles, and
// the write must be atomic (no temporary left, an older checkpoint replaced in one rename).
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>

#include "IoTestSupport.hpp"
#include "fldsim/error.hpp"
#include "io/Checkpoint.hpp"
#include "io/Hdf5ResultSink.hpp"

namespace fldsim {
namespace {

// Random bit patterns of finite doubles (any exponent, any mantissa) plus signed zero,
// subnormals and extremes: a round trip through text or float would change some of them.
double random_double(std::mt19937_64& rng) {
  for (;;) {
    const double x = std::bit_cast<double>(rng());
    if (std::isfinite(x)) return x;
  }
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

Checkpoint random_checkpoint(std::mt19937_64& rng, std::size_t n) {
  Checkpoint c;
  auto vec = [&] { return Vec3(random_double(rng), random_double(rng), random_double(rng)); };
  for (std::size_t i = 0; i < n; ++i) {
    c.positions.push_back(vec());
    c.displacement.push_back(vec());
    c.nonaffine.push_back(vec());
    c.orientations.emplace_back(random_double(rng), random_double(rng), random_double(rng),
                                random_double(rng));
  }
  c.positions[0] = Vec3(-0.0, std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max());
  c.time = random_double(rng);
  c.strain = random_double(rng);
  c.box_edge = random_double(rng);
  c.step = static_cast<std::int64_t>(rng());
  c.seed = rng();
  c.experiment_yaml = "system: {count: 7}\nrun: {dt: 1.0e-3}\n";
  for (int k = 0; k < 6 * static_cast<int>(n); ++k) c.warm_start.push_back(random_double(rng));
  c.blobs["orientation"] = {random_double(rng), random_double(rng)};
  c.blobs["pair_distribution"] = {};
  return c;
}

void expect_bit_identical(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int d = 0; d < 3; ++d) EXPECT_TRUE(same_bits(a[i][d], b[i][d])) << i << "," << d;
}

TEST(Checkpoint, RoundTripIsBitExact) {
  test::ScratchDir dir;
  std::mt19937_64 rng(20240611);
  const Checkpoint c = random_checkpoint(rng, 7);
  const std::string path = dir.file("ckpt/run.ckpt.h5");
  write_checkpoint(path, c);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  const Checkpoint r = read_checkpoint(path);

  expect_bit_identical(r.positions, c.positions);
  expect_bit_identical(r.displacement, c.displacement);
  expect_bit_identical(r.nonaffine, c.nonaffine);
  ASSERT_EQ(r.orientations.size(), c.orientations.size());
  for (std::size_t i = 0; i < c.orientations.size(); ++i)
    for (int k = 0; k < 4; ++k)
      EXPECT_TRUE(same_bits(r.orientations[i].coeffs()[k], c.orientations[i].coeffs()[k]));
  EXPECT_TRUE(same_bits(r.time, c.time));
  EXPECT_TRUE(same_bits(r.strain, c.strain));
  EXPECT_TRUE(same_bits(r.box_edge, c.box_edge));
  EXPECT_EQ(r.step, c.step);
  EXPECT_EQ(r.seed, c.seed);
  EXPECT_EQ(r.experiment_yaml, c.experiment_yaml);
  ASSERT_EQ(r.warm_start.size(), c.warm_start.size());
  for (std::size_t i = 0; i < c.warm_start.size(); ++i)
    EXPECT_TRUE(same_bits(r.warm_start[i], c.warm_start[i]));
  ASSERT_EQ(r.blobs.size(), 2u);
  ASSERT_EQ(r.blobs.at("orientation").size(), 2u);
  EXPECT_TRUE(same_bits(r.blobs.at("orientation")[1], c.blobs.at("orientation")[1]));
  EXPECT_TRUE(r.blobs.at("pair_distribution").empty());
}

TEST(Checkpoint, RewriteReplacesThePreviousCheckpoint) {
  test::ScratchDir dir;
  std::mt19937_64 rng(7);
  const std::string path = dir.file("run.ckpt.h5");
  write_checkpoint(path, random_checkpoint(rng, 3));
  const Checkpoint second = random_checkpoint(rng, 5);
  write_checkpoint(path, second);
  const Checkpoint r = read_checkpoint(path);
  EXPECT_EQ(r.positions.size(), 5u);
  EXPECT_EQ(r.step, second.step);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(Checkpoint, BadFilesAreErrorsNamingTheFile) {
  test::ScratchDir dir;
  const std::string missing = dir.file("missing.h5");
  try {
    read_checkpoint(missing);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos);
  }
  // A result file is HDF5 but not a checkpoint.
  const std::string result = dir.file("result.h5");
  {
    Hdf5ResultSink sink(result, false);
    sink.commit();
  }
  try {
    read_checkpoint(result);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not an fldsim checkpoint"), std::string::npos) << e.what();
  }
  // Not HDF5 at all.
  const std::string text = dir.file("text.h5");
  std::ofstream(text) << "hello\n";
  EXPECT_THROW(read_checkpoint(text), Error);
  // Inconsistent body counts are refused before anything is written.
  Checkpoint bad;
  bad.positions.resize(2, Vec3::Zero());
  EXPECT_THROW(write_checkpoint(dir.file("bad.h5"), bad), Error);
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.h5")));
}

}  // namespace
}  // namespace fldsim
