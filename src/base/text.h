// String helpers (ASCII-only case folding; UTF-8 passes through untouched),
// UTF-8 validation and the one JSON string escaper.
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
// ASCII case-insensitive equality.
bool EqualsIgnoreCase(std::string_view a, std::string_view b);
// Splits on `sep`, keeping empty fields.
std::vector<std::string_view> Split(std::string_view s, char sep);
// Splits `data` into lines, accepting LF and CRLF; a final newline does not
// make an extra empty line.
std::vector<std::string_view> SplitLines(std::string_view data);
// Escapes a string for inclusion in XML/HTML text or attributes.
std::string XmlEscape(std::string_view s);

// The byte offset of the first byte that does not start a well-formed UTF-8
// sequence (RFC 3629: no overlong forms, no surrogates U+D800..U+DFFF, nothing
// above U+10FFFF, no truncated sequence), or npos when `s` is valid. Pure.
size_t FindInvalidUtf8(std::string_view s);
// `s` with every ill-formed sequence replaced by U+FFFD. Pure.
std::string ToValidUtf8(std::string_view s);

// Appends `s` as a JSON string literal (quotes included): quotes, backslashes
// and control characters escaped, ill-formed UTF-8 replaced by U+FFFD, so the
// output is always valid JSON. Never throws (beyond allocation). Pure.
void AppendJsonString(std::string* out, std::string_view s);
// The same, returned.
std::string JsonString(std::string_view s);

}  // namespace sb

#endif  // SB_BASE_TEXT_H_
