// String helpers (ASCII-only case folding; UTF-8 passes through untouched).
#ifndef SB_BASE_TEXT_H_
#define SB_BASE_TEXT_H_

#include <string>
#include <string_view>
#include <vector>

namespace sb {

// Strips ASCII whitespace (space, tab, CR, LF, VT, FF) from both ends.
std::string_view Trim(std::string_view s);
// ASCII lower-case copy.
std::string ToLower(std::string_view s);
// Splits on `sep`, keeping empty fields.
std::vector<std::string_view> Split(std::string_view s, char sep);
// Splits `data` into lines, accepting LF and CRLF; a final newline does not
// make an extra empty line.
std::vector<std::string_view> SplitLines(std::string_view data);
// Escapes a string for inclusion in XML/HTML text or attributes.
std::string XmlEscape(std::string_view s);
// Byte offset of the first byte that does not start a well-formed UTF-8
// sequence (RFC 3629: no overlongs, no surrogates, at most U+10FFFF), or
// std::string_view::npos when all of `s` is valid UTF-8. Pure.
size_t Utf8ErrorOffset(std::string_view s);

}  // namespace sb

#endif  // SB_BASE_TEXT_H_
