#include "config/DidYouMean.hpp"

#include <algorithm>
#include <cctype>
#include <limits>

namespace fldsim {

namespace {
std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
bool starts_with(const std::string& s, const std::string& prefix) {
  return s.size() >= prefix.size() && s.compare(0, prefix.size(), prefix) == 0;
}
}  // namespace

std::size_t edit_distance(const std::string& a, const std::string& b) {
  // d[i][j] = distance between a[0..i) and b[0..j) (Damerau 1964, restricted form).
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

std::string did_you_mean(const std::string& key, const std::vector<std::string>& known) {
  if (key.empty()) return "";
  const std::string k = lower(key);
  std::string best;
  std::size_t best_score = std::numeric_limits<std::size_t>::max();
  for (const auto& name : known) {
    const std::string n = lower(name);
    if (n == k && name == key) continue;  // the key itself is not a suggestion
    std::size_t score = edit_distance(k, n);
    if (score > 2) {
      if (!starts_with(n, k) && !starts_with(k, n)) continue;
      score = 3;  // a prefix match ranks after every edit-distance-2 match
    }
    if (score < best_score) {
      best_score = score;
      best = name;
    }
  }
  return best;
}

}  // namespace fldsim
