#include "base/number.h"

#include <cmath>
#include <cstdio>

#include "base/text.h"

namespace sb {

std::string FormatDouble(double v, int significant_digits) {
  if (v == 0) v = 0;  // no "-0"
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  if (significant_digits > 0) {
    std::snprintf(buf, sizeof buf, "%.*g", significant_digits, v);
    return buf;
  }
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, p);
}

std::string FormatTriple(const double (&v)[3]) {
  return FormatDouble(v[0]) + "," + FormatDouble(v[1]) + "," + FormatDouble(v[2]);
}

bool ParseDouble(std::string_view s, double* out) {
  if (s.empty()) return false;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return ec == std::errc() && p == s.data() + s.size() && std::isfinite(*out);
}

bool ParseTriple(std::string_view s, double (&out)[3]) {
  std::vector<std::string_view> parts = Split(s, ',');
  if (parts.size() != 3) return false;
  for (int i = 0; i < 3; ++i) {
    if (!ParseDouble(Trim(parts[i]), &out[i])) return false;
  }
  return true;
}

}  // namespace sb
