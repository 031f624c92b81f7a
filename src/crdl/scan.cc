#include "crdl/scan.h"

#include <string>
#include <vector>

#include "base/text.h"

namespace sb {

namespace {

bool IsKeyChar(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

bool IsBlank(char c) { return c == ' ' || c == '\t'; }

// "key: value" (see ScanCrdlLine).
bool SplitMeta(std::string_view line, CrdlLine* out) {
  size_t colon = line.find(':');
  if (colon == std::string_view::npos || colon == 0) return false;
  for (size_t i = 0; i < colon; ++i) {
    if (!IsKeyChar(line[i])) return false;
  }
  std::string_view rest = line.substr(colon + 1);
  if (!rest.empty() && !IsBlank(rest[0])) return false;
  out->key = line.substr(0, colon);
  out->value = Trim(rest);
  return true;
}

}  // namespace

CrdlLine ScanCrdlLine(std::string_view line, CrdlSection section) {
  CrdlLine out;
  std::string_view t = Trim(line);
  if (t.empty()) return out;  // kBlank
  if (section == CrdlSection::kHeader) {
    if (t == "---") {
      out.kind = line == "---" ? CrdlLineKind::kSeparator : CrdlLineKind::kBadSeparator;
      return out;
    }
    out.kind = SplitMeta(line, &out) ? CrdlLineKind::kMeta : CrdlLineKind::kDescription;
    return out;
  }
  size_t indent = 0;
  while (indent < line.size() && IsBlank(line[indent])) ++indent;
  out.column = static_cast<int>(indent) + 1;
  if (t.front() == '#') {
    out.kind = CrdlLineKind::kComment;
    return out;
  }
  size_t word_end = 0;
  while (word_end < t.size() && !IsBlank(t[word_end])) ++word_end;
  out.word = t.substr(0, word_end);
  std::optional<Hand> hand = ParseHand(out.word);
  if (!hand) {
    out.kind = CrdlLineKind::kBadHand;
    return out;
  }
  out.hand = *hand;
  std::string_view text = Trim(t.substr(word_end));
  // " (crux)" at the end (any case) flags the move; it is not part of the text.
  if (text.size() > kCruxMarker.size() &&
      EqualsIgnoreCase(text.substr(text.size() - kCruxMarker.size()), kCruxMarker) &&
      IsBlank(text[text.size() - kCruxMarker.size() - 1])) {
    out.crux = true;
    text = Trim(text.substr(0, text.size() - kCruxMarker.size()));
  } else if (EqualsIgnoreCase(text, kCruxMarker)) {
    out.crux = true;
    text = {};
  }
  if (text.empty()) {
    out.kind = CrdlLineKind::kEmptyMove;
    out.column = static_cast<int>(indent + word_end) + 1;
    return out;
  }
  out.kind = CrdlLineKind::kMove;
  out.text = text;
  return out;
}

std::vector<std::string_view> SplitCrdlLines(std::string_view text) {
  while (text.substr(0, kByteOrderMark.size()) == kByteOrderMark) {
    text.remove_prefix(kByteOrderMark.size());
  }
  std::vector<std::string_view> lines = SplitLines(text);
  for (std::string_view& l : lines) {
    while (!l.empty() && l.back() == '\r') l.remove_suffix(1);
  }
  return lines;
}

std::string CrdlLineError(const CrdlLine& line) {
  switch (line.kind) {
    case CrdlLineKind::kBadSeparator:
      return "the separator line must be exactly \"---\"";
    case CrdlLineKind::kBadHand:
      return "expected hand L or R, got \"" + std::string(line.word.substr(0, 20)) + "\"";
    case CrdlLineKind::kEmptyMove:
      return std::string("empty move text after hand ") + HandLetter(line.hand);
    default:
      return "";
  }
}

}  // namespace sb
