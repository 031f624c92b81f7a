#include "crdl/route.h"

#include <cctype>
#include <filesystem>
#include <string>

#include "base/files.h"
#include "base/text.h"

namespace sb {

const char* HandLetter(Hand hand) { return hand == Hand::kLeft ? "L" : "R"; }

std::optional<Hand> ParseHand(std::string_view word) {
  std::string lw = ToLower(word);
  if (lw == "l" || lw == "left") return Hand::kLeft;
  if (lw == "r" || lw == "right") return Hand::kRight;
  return std::nullopt;
}

static bool EqualsIgnoreCase(std::string_view a, std::string_view b) {
  return ToLower(a) == ToLower(b);
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

namespace {

// Returns the byte offset of the first invalid UTF-8 sequence, or npos.
size_t FindInvalidUtf8(std::string_view s) {
  size_t i = 0;
  while (i < s.size()) {
    unsigned char c = static_cast<unsigned char>(s[i]);
    size_t len = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    if (len == 0 || i + len > s.size()) return i;
    for (size_t k = 1; k < len; ++k) {
      if ((static_cast<unsigned char>(s[i + k]) >> 6) != 0x2) return i;
    }
    if (len == 2 && c < 0xC2) return i;  // overlong
    i += len;
  }
  return std::string_view::npos;
}

bool IsKeyChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
}

// Splits "key: value" when the line has that form.
bool SplitMeta(std::string_view line, std::string* key, std::string* value) {
  size_t colon = line.find(':');
  if (colon == std::string_view::npos || colon == 0) return false;
  for (size_t i = 0; i < colon; ++i) {
    if (!IsKeyChar(line[i])) return false;
  }
  // "http://..." style values in free text must not turn into metadata.
  if (colon + 1 < line.size() && line[colon + 1] != ' ' && line[colon + 1] != '\t') return false;
  *key = std::string(line.substr(0, colon));
  *value = std::string(Trim(line.substr(colon + 1)));
  return true;
}

std::string Where(std::string_view file, size_t line, size_t col) {
  return std::string(file) + ":" + std::to_string(line) + ":" + std::to_string(col) + ": ";
}

}  // namespace

Result<Route> ParseCrdl(std::string_view text, std::string_view filename) {
  if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  std::vector<std::string_view> lines = SplitLines(text);
  Route route;
  size_t sep = lines.size();
  for (size_t i = 0; i < lines.size(); ++i) {
    std::string_view line = lines[i];
    if (size_t bad = FindInvalidUtf8(line); bad != std::string_view::npos) {
      return Status::InvalidInput(Where(filename, i + 1, bad + 1) + "invalid UTF-8");
    }
    if (line.find('\0') != std::string_view::npos) {
      return Status::InvalidInput(Where(filename, i + 1, line.find('\0') + 1) + "NUL byte in text");
    }
    if (sep == lines.size()) {
      if (Trim(line) == "---") {
        if (line != "---") {
          return Status::InvalidInput(Where(filename, i + 1, 1) +
                                      "the separator line must be exactly \"---\"");
        }
        sep = i;
        continue;
      }
      std::string key, value;
      if (SplitMeta(line, &key, &value)) {
        route.header.push_back({key, value});
      } else {
        route.header.push_back({"", std::string(line)});
      }
      continue;
    }
    // Move section.
    std::string_view body = line;
    size_t indent = 0;
    while (indent < body.size() && (body[indent] == ' ' || body[indent] == '\t')) ++indent;
    std::string_view rest = Trim(body);
    if (rest.empty() || rest.front() == '#') continue;
    size_t word_end = 0;
    while (word_end < rest.size() && rest[word_end] != ' ' && rest[word_end] != '\t') ++word_end;
    std::string_view word = rest.substr(0, word_end);
    Move move;
    std::optional<Hand> hand = ParseHand(word);
    if (!hand) {
      std::string shown(word.substr(0, 20));
      return Status::InvalidInput(Where(filename, i + 1, indent + 1) +
                                  "expected hand L or R, got \"" + shown + "\"");
    }
    move.hand = *hand;
    std::string_view move_text = Trim(rest.substr(word_end));
    if (move_text.empty()) {
      return Status::InvalidInput(Where(filename, i + 1, indent + word_end + 1) +
                                  "empty move text after hand " + HandLetter(move.hand));
    }
    move.text = std::string(move_text);
    move.line = static_cast<int>(i + 1);
    route.moves.push_back(std::move(move));
  }
  if (sep == lines.size()) {
    return Status::InvalidInput(Where(filename, lines.empty() ? 1 : lines.size(), 1) +
                                "missing \"---\" line between the header and the moves");
  }
  if (route.moves.empty()) {
    return Status::InvalidInput(Where(filename, sep + 1, 1) + "route has no moves after \"---\"");
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
  Result<std::string> data = ReadFile(path);
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
    out += '\n';
  }
  return out;
}

}  // namespace sb
