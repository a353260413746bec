#include "plugins/SchemaWire.hpp"

#include <cstring>

namespace fldsim {

void WireWriter::u64(std::uint64_t v) {
  out_.append(reinterpret_cast<const char*>(&v), sizeof v);
}

void WireWriter::real(double v) {
  out_.append(reinterpret_cast<const char*>(&v), sizeof v);
}

void WireWriter::text(const std::string& s) {
  u64(s.size());
  out_ += s;
}

void WireWriter::schema(const ParamSchema& schema) {
  u64(schema.specs().size());
  for (const auto& s : schema.specs()) {
    text(s.name);
    u64(static_cast<std::uint64_t>(s.type));
    text(s.unit);
    text(s.help);
    real(s.min);
    real(s.max);
    u64((s.min_exclusive ? 1u : 0u) | (s.max_exclusive ? 2u : 0u));
    u64(s.choices.size());
    for (const auto& c : s.choices) text(c);
    u64(s.list_size);
    u64(s.default_value ? s.default_value->index() + 1 : 0);
    if (!s.default_value) continue;
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, double>)
            real(v);
          else if constexpr (std::is_same_v<T, long> || std::is_same_v<T, bool>)
            u64(static_cast<std::uint64_t>(v));
          else if constexpr (std::is_same_v<T, std::string>)
            text(v);
          else if constexpr (std::is_same_v<T, std::vector<double>>) {
            u64(v.size());
            for (double x : v) real(x);
          } else {
            u64(v.size());
            for (const auto& row : v) {
              u64(row.size());
              for (double x : row) real(x);
            }
          }
        },
        *s.default_value);
  }
}

void WireReader::need(std::size_t n) const {
  if (n > in_.size() || pos_ > in_.size() - n) throw PluginError("malformed probe reply");
}

std::uint64_t WireReader::u64() {
  need(sizeof(std::uint64_t));
  std::uint64_t v;
  std::memcpy(&v, in_.data() + pos_, sizeof v);
  pos_ += sizeof v;
  return v;
}

double WireReader::real() {
  need(sizeof(double));
  double v;
  std::memcpy(&v, in_.data() + pos_, sizeof v);
  pos_ += sizeof v;
  return v;
}

std::string WireReader::text() {
  const std::uint64_t n = u64();
  need(n);
  std::string s = in_.substr(pos_, n);
  pos_ += n;
  return s;
}

std::uint64_t WireReader::count_of(std::size_t element_bytes) {
  const std::uint64_t n = u64();
  if (n > (in_.size() - pos_) / element_bytes) throw PluginError("malformed probe reply");
  return n;
}

std::vector<double> WireReader::reals() {
  std::vector<double> v(count_of(sizeof(double)));
  for (auto& x : v) x = real();
  return v;
}

ParamSchema WireReader::schema() {
  ParamSchema schema;
  const std::uint64_t count = count_of(1);
  for (std::uint64_t i = 0; i < count; ++i) {
    ParamSpec s;
    s.name = text();
    const std::uint64_t type = u64();
    if (type > static_cast<std::uint64_t>(ParamType::NumberTable)) throw PluginError("malformed probe reply");
    s.type = static_cast<ParamType>(type);
    s.unit = text();
    s.help = text();
    s.min = real();
    s.max = real();
    const std::uint64_t flags = u64();
    s.min_exclusive = flags & 1u;
    s.max_exclusive = flags & 2u;
    const std::uint64_t choices = count_of(sizeof(std::uint64_t));
    for (std::uint64_t c = 0; c < choices; ++c) s.choices.push_back(text());
    s.list_size = u64();
    switch (u64()) {
      case 0:
        break;
      case 1:
        s.default_value = real();
        break;
      case 2:
        s.default_value = static_cast<long>(u64());
        break;
      case 3:
        s.default_value = u64() != 0;
        break;
      case 4:
        s.default_value = text();
        break;
      case 5:
        s.default_value = reals();
        break;
      case 6: {
        std::vector<std::vector<double>> table(count_of(sizeof(std::uint64_t)));
        for (auto& row : table) row = reals();
        s.default_value = std::move(table);
        break;
      }
      default:
        throw PluginError("malformed probe reply");
    }
    schema.add(std::move(s));
  }
  return schema;
}

}  // namespace fldsim
