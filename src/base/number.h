// The one way to print and parse numbers in strangebeta.
#ifndef SB_BASE_NUMBER_H_
#define SB_BASE_NUMBER_H_

#include <charconv>
#include <concepts>
#include <string>
#include <string_view>

namespace sb {

// The shortest decimal that reads back as the same double ("0.015", "-13.5",
// "16", "1e+300"); -0 prints "0"; non-finite values print "nan", "inf",
// "-inf". With `significant_digits` > 0 the value is printed with printf's
// %.Ng instead (the fixed formats of `landscape`/`pick` text output use 17).
// Deterministic; thread-safe.
std::string FormatDouble(double v, int significant_digits = 0);
// "x,y,z" with FormatDouble for each (the command-line form of a triple).
std::string FormatTriple(const double (&v)[3]);
template <typename Array>
std::string FormatTriple(const Array& v) {
  const double t[3] = {v[0], v[1], v[2]};
  return FormatTriple(t);
}

// Parses a whole decimal integer ("42", "-7"; no spaces, no '+', no leading
// garbage or trailing text) into `*out`. False, leaving *out unspecified, for
// anything else, including values outside T's range. Thread-safe.
template <std::integral T>
bool ParseInt(std::string_view s, T* out) {
  if (s.empty()) return false;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return ec == std::errc() && p == s.data() + s.size();
}

// Parses a whole finite decimal number ("0.015", "-1e3"); false for anything
// else, including "nan", "inf" and out-of-range values. Thread-safe.
bool ParseDouble(std::string_view s, double* out);

// Parses "x,y,z" (spaces around the numbers allowed) into three finite
// doubles. False for anything else. Thread-safe.
bool ParseTriple(std::string_view s, double (&out)[3]);
template <typename Array>
bool ParseTriple(std::string_view s, Array* out) {
  double t[3];
  if (!ParseTriple(s, t)) return false;
  for (int i = 0; i < 3; ++i) (*out)[i] = t[i];
  return true;
}

}  // namespace sb

#endif  // SB_BASE_NUMBER_H_
