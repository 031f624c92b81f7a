// Calendar dates as text: the one check of an ISO date "YYYY-MM-DD" and the
// one way to write a moment as UTC text.
#ifndef SB_BASE_DATE_H_
#define SB_BASE_DATE_H_

#include <cstdint>
#include <string>
#include <string_view>

namespace sb {

// Whether `text` is exactly "YYYY-MM-DD" (ten ASCII characters, digits and
// two dashes, no surrounding space) naming a real day of the proleptic
// Gregorian calendar: month 01-12, day 01 up to that month's length (February
// has 29 days in years divisible by 4, except centuries not divisible by 400).
// Year 0000 is accepted as a year like any other. Callers keep their own error
// text. Pure; thread-safe.
bool IsIsoDate(std::string_view text);

// The UTC calendar day of `unix_seconds` as "YYYY-MM-DD". Pure; thread-safe.
std::string UtcDateText(int64_t unix_seconds);

// The UTC moment `unix_seconds` as "YYYY-MM-DD HH:MM:SS", the text the
// database keeps (and orders by). Pure; thread-safe.
std::string UtcTimeText(int64_t unix_seconds);

}  // namespace sb

#endif  // SB_BASE_DATE_H_
