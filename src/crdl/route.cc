#include "crdl/route.h"

#include <cctype>
#include <filesystem>
#include <string>

#include "base/files.h"
#include "base/text.h"
#include "crdl/scan.h"

namespace sb {

const char* HandLetter(Hand hand) { return hand == Hand::kLeft ? "L" : "R"; }

std::optional<Hand> ParseHand(std::string_view word) {
  std::string lw = ToLower(word);
  if (lw == "l" || lw == "left") return Hand::kLeft;
  if (lw == "r" || lw == "right") return Hand::kRight;
  return std::nullopt;
}

std::optional<std::string> Route::Meta(std::string_view key) const {
  for (const HeaderLine& h : header) {
    if (!h.key.empty() && EqualsIgnoreCase(h.key, key)) return h.value;
  }
  return std::nullopt;
}

void Route::SetMeta(std::string_view key, std::string_view value) {
  for (HeaderLine& h : header) {
    if (!h.key.empty() && EqualsIgnoreCase(h.key, key)) {
      h.value = std::string(value);
      return;
    }
  }
  header.push_back({std::string(key), std::string(value)});
}

std::string Route::Name(std::string_view fallback) const {
  auto n = Meta("name");
  if (n && !n->empty()) return *n;
  return std::string(fallback);
}

bool IsMatchText(std::string_view text) {
  std::string_view t = Trim(text);
  while (!t.empty() && std::ispunct(static_cast<unsigned char>(t.back()))) t.remove_suffix(1);
  return ToLower(Trim(t)) == "match";
}

Result<Route> ParseCrdl(std::string_view text, std::string_view filename) {
  auto at = [&](size_t line, size_t col) {
    return SourceLocation{std::string(filename), static_cast<int>(line), static_cast<int>(col)};
  };
  if (text.size() > kMaxCrdlBytes) {
    return Status::InvalidInputAt(at(1, 1), "larger than " + std::to_string(kMaxCrdlBytes) +
                                                " bytes (the limit for a CRDL text)");
  }
  std::vector<std::string_view> lines = SplitCrdlLines(text);
  Route route;
  CrdlSection section = CrdlSection::kHeader;
  size_t sep = lines.size();
  for (size_t i = 0; i < lines.size(); ++i) {
    std::string_view line = lines[i];
    if (size_t bad = FindInvalidUtf8(line); bad != std::string_view::npos) {
      return Status::InvalidInputAt(at(i + 1, bad + 1), "invalid UTF-8");
    }
    if (size_t nul = line.find('\0'); nul != std::string_view::npos) {
      return Status::InvalidInputAt(at(i + 1, nul + 1), "NUL byte in text");
    }
    CrdlLine l = ScanCrdlLine(line, section);
    switch (l.kind) {
      case CrdlLineKind::kSeparator:
        sep = i;
        section = CrdlSection::kMoves;
        break;
      case CrdlLineKind::kMeta:
        route.header.push_back({std::string(l.key), std::string(l.value)});
        break;
      case CrdlLineKind::kBlank:
      case CrdlLineKind::kDescription:
        if (section == CrdlSection::kHeader) route.header.push_back({"", std::string(line)});
        break;
      case CrdlLineKind::kComment:
        break;
      case CrdlLineKind::kMove:
        route.moves.push_back({l.hand, std::string(l.text), static_cast<int>(i + 1), l.crux});
        break;
      case CrdlLineKind::kBadSeparator:
      case CrdlLineKind::kBadHand:
      case CrdlLineKind::kEmptyMove:
        return Status::InvalidInputAt(at(i + 1, l.column), CrdlLineError(l));
    }
  }
  if (sep == lines.size()) {
    return Status::InvalidInputAt(at(lines.empty() ? 1 : lines.size(), 1),
                                  "missing \"---\" line between the header and the moves");
  }
  // Trailing blank description lines carry no information; dropping them makes
  // PrintCrdl ∘ ParseCrdl stable.
  while (!route.header.empty() && route.header.back().key.empty() &&
         Trim(route.header.back().value).empty()) {
    route.header.pop_back();
  }
  return route;
}

std::string RouteFileStem(const std::string& path) {
  if (path == "-") return "stdin";
  return std::filesystem::path(path).stem().string();
}

Result<Route> ReadCrdlFile(const std::string& path) {
  Result<std::string> data = ReadFile(path, kMaxCrdlBytes);
  if (!data.ok()) return data.status();
  return ParseCrdl(*data, path == "-" ? "<stdin>" : path);
}

std::string PrintCrdl(const Route& route) {
  std::string out;
  for (const HeaderLine& h : route.header) {
    if (h.key.empty()) {
      out += h.value;
    } else {
      out += h.key;
      out += ": ";
      out += h.value;
    }
    out += '\n';
  }
  out += "---\n";
  for (const Move& m : route.moves) {
    out += HandLetter(m.hand);
    out += ' ';
    out += m.text;
    if (m.crux) {
      out += ' ';
      out += kCruxMarker;
    }
    out += '\n';
  }
  return out;
}

}  // namespace sb
