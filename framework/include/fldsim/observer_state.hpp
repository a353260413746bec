// Packing an observer's accumulators into the flat vector of doubles that Observer::save_state()
// returns, and reading them back in restore_state() with checks, so a resumed run continues its
// averages exactly. Vectors are stored length-first; a reader that expects another length (the
// parameters changed between the runs) throws with the observer's name.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "fldsim/error.hpp"

namespace fldsim {

class StateWriter {
 public:
  StateWriter& put(double x) {
    data_.push_back(x);
    return *this;
  }
  StateWriter& put(const std::vector<double>& v) {
    data_.push_back(double(v.size()));
    data_.insert(data_.end(), v.begin(), v.end());
    return *this;
  }
  template <class Derived>
  StateWriter& put(const Eigen::DenseBase<Derived>& m) {
    data_.push_back(double(m.size()));
    for (Eigen::Index j = 0; j < m.cols(); ++j)
      for (Eigen::Index i = 0; i < m.rows(); ++i) data_.push_back(m(i, j));
    return *this;
  }
  std::vector<double> take() { return std::move(data_); }

 private:
  std::vector<double> data_;
};

class StateReader {
 public:
  StateReader(const std::vector<double>& data, std::string owner) : data_(data), owner_(std::move(owner)) {}

  double get() {
    need(1);
    return data_[pos_++];
  }
  // A vector of any length.
  std::vector<double> get_vector() {
    const std::size_t n = length();
    need(n);
    std::vector<double> v(data_.begin() + std::ptrdiff_t(pos_), data_.begin() + std::ptrdiff_t(pos_ + n));
    pos_ += n;
    return v;
  }
  // Into an existing vector or matrix whose size the parameters fixed: the sizes must agree.
  void get_into(std::vector<double>& v) {
    expect_length(v.size());
    for (double& x : v) x = data_[pos_++];
  }
  template <class Derived>
  void get_into(Eigen::DenseBase<Derived>& m) {
    expect_length(std::size_t(m.size()));
    for (Eigen::Index j = 0; j < m.cols(); ++j)
      for (Eigen::Index i = 0; i < m.rows(); ++i) m(i, j) = data_[pos_++];
  }
  // Call at the end: all of the state must have been read.
  void finish() const {
    if (pos_ != data_.size()) fail("has " + std::to_string(data_.size() - pos_) + " values left over");
  }

 private:
  std::size_t length() {
    const double n = get();
    if (n < 0 || n != double(std::size_t(n))) fail("holds a bad length");
    return std::size_t(n);
  }
  void expect_length(std::size_t expected) {
    const std::size_t n = length();
    if (n != expected)
      fail("holds " + std::to_string(n) + " values where the observer's parameters need " +
           std::to_string(expected));
    need(n);
  }
  void need(std::size_t n) const {
    if (pos_ + n > data_.size()) fail("is shorter than the observer's state");
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw Error("checkpoint state of observer " + owner_ + " " + what +
                " (were its parameters changed since the checkpoint?)");
  }

  const std::vector<double>& data_;
  std::string owner_;
  std::size_t pos_ = 0;
};

}  // namespace fldsim
