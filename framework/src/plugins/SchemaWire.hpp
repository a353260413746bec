// A ParamSchema as bytes, so a library probed in a child process (LibraryProbe) hands its
// declared parameters to the parent without the parent loading the library. Same machine,
// same build: numbers travel as their raw bytes, strings length-prefixed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fldsim/params.hpp"

namespace fldsim {

class WireWriter {
 public:
  void text(const std::string& s);
  void u64(std::uint64_t v);
  void real(double v);
  void schema(const ParamSchema& s);
  const std::string& bytes() const { return out_; }

 private:
  std::string out_;
};

// Reads what WireWriter wrote; throws PluginError("malformed probe reply") on short input.
class WireReader {
 public:
  explicit WireReader(const std::string& bytes) : in_(bytes) {}
  std::string text();
  std::uint64_t u64();
  double real();
  ParamSchema schema();

 private:
  void need(std::size_t n) const;
  // A count read before `count` elements of at least `element_bytes` each (bounded by what is left).
  std::uint64_t count_of(std::size_t element_bytes);
  std::vector<double> reals();
  const std::string& in_;
  std::size_t pos_ = 0;
};

}  // namespace fldsim
