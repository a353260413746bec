#include "io/H5mdUnits.hpp"

#include <cctype>
#include <vector>

namespace fldsim::io {
namespace {

bool is_symbol(const std::string& s) {
  if (s.empty() || !std::isalpha(static_cast<unsigned char>(s[0]))) return false;
  for (char c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  return true;
}

bool is_number(const std::string& s) {
  if (s.empty()) return false;
  bool dot = false;
  for (char c : s) {
    if (c == '.' && !dot)
      dot = true;
    else if (!std::isdigit(static_cast<unsigned char>(c)))
      return false;
  }
  return true;
}

}  // namespace

std::string h5md_unit(const std::string& text) {
  if (text.empty()) return text;
  std::string number;
  std::vector<std::pair<std::string, int>> factors;  // symbol, power (each symbol once)
  int sign = 1;
  std::size_t i = 0;
  while (i <= text.size()) {
    const std::size_t end = text.find_first_of("*/", i);
    const std::string token = text.substr(i, end == std::string::npos ? std::string::npos : end - i);
    std::string base = token;
    int power = 1;
    if (const auto caret = token.find('^'); caret != std::string::npos) {
      base = token.substr(0, caret);
      const std::string p = token.substr(caret + 1);
      if (p.empty() || p.find_first_not_of("+-0123456789") != std::string::npos) return text;
      power = std::stoi(p);
    }
    if (is_number(base) && power == 1 && sign == 1 && factors.empty() && number.empty()) {
      number = base;
    } else if (is_symbol(base)) {
      bool merged = false;
      for (auto& f : factors)
        if (f.first == base) {
          f.second += sign * power;
          merged = true;
        }
      if (!merged) factors.emplace_back(base, sign * power);
    } else if (!(is_number(base) && base == "1")) {  // "1/x": the 1 only marks the division
      return text;
    }
    if (end == std::string::npos) break;
    sign = text[end] == '/' ? -1 : 1;
    i = end + 1;
  }
  std::string out;
  if (!number.empty() && (number != "1" || factors.empty())) out = number;
  for (const auto& [symbol, power] : factors) {
    if (power == 0) continue;
    if (!out.empty()) out += ' ';
    out += symbol;
    if (power != 1) out += (power > 0 ? "+" : "") + std::to_string(power);
  }
  return out.empty() ? "1" : out;
}

}  // namespace fldsim::io
