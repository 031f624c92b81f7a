// Case folding for search (issue 21: "überhang" finds "Überhang"): the one
// fold the store applies to the text it searches and to the needle, in C++,
// so SQLite and PostgreSQL agree whatever their collations.
#ifndef SB_BASE_FOLD_H_
#define SB_BASE_FOLD_H_

#include <string>
#include <string_view>

namespace sb {

// `text` with upper-case letters mapped to lower case: ASCII, Latin-1,
// Latin Extended-A, Latin Extended Additional (Vietnamese), Greek and
// Cyrillic; "ß" and "ẞ" fold to "ss" (as Unicode's full case folding does).
// Other characters, and bytes that are not well-formed UTF-8, are kept as
// they are. Pure; the output is never longer than twice the input.
std::string FoldCase(std::string_view text);

}  // namespace sb

#endif  // SB_BASE_FOLD_H_
