#include "web/feedback.h"

#include <charconv>
#include <memory>
#include <mutex>
#include <string>

#include "base/text.h"
#include "crdl/route.h"
#if SB_HAVE_LANGUAGE
#include "language/symbols.h"
#endif

namespace sb::web {

namespace {

#if SB_HAVE_LANGUAGE
// One MoveLanguage per thread (it is not thread-safe), cloned from a shared
// prototype that holds the grammar.
language::MoveLanguage* ThreadLanguage() {
  static std::once_flag once;
  static std::unique_ptr<language::MoveLanguage> proto;
  std::call_once(once, [] {
    Result<language::MoveLanguage> l = language::MoveLanguage::LoadDefault();
    if (l.ok()) proto = std::make_unique<language::MoveLanguage>(std::move(l).value());
  });
  if (!proto) return nullptr;
  thread_local std::unique_ptr<language::MoveLanguage> mine;
  if (!mine) mine = std::make_unique<language::MoveLanguage>(proto->Clone());
  return mine.get();
}
#endif

bool IsKeyChar(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

bool LooksLikeMeta(std::string_view line) {
  size_t colon = line.find(':');
  if (colon == std::string_view::npos || colon == 0) return false;
  for (size_t i = 0; i < colon; ++i) {
    if (!IsKeyChar(line[i])) return false;
  }
  return colon + 1 >= line.size() || line[colon + 1] == ' ' || line[colon + 1] == '\t';
}

}  // namespace

bool LanguageAvailable() {
#if SB_HAVE_LANGUAGE
  return ThreadLanguage() != nullptr;
#else
  return false;
#endif
}

bool SplitLocatedError(std::string_view msg, int* line, int* col, std::string* reason) {
  // file names may contain ':' — find ":<digits>:<digits>: " from the left.
  for (size_t p = msg.find(':'); p != std::string_view::npos; p = msg.find(':', p + 1)) {
    size_t a = p + 1, b = a;
    while (b < msg.size() && msg[b] >= '0' && msg[b] <= '9') ++b;
    if (b == a || b >= msg.size() || msg[b] != ':') continue;
    size_t c = b + 1, d = c;
    while (d < msg.size() && msg[d] >= '0' && msg[d] <= '9') ++d;
    if (d == c || d >= msg.size() || msg[d] != ':') continue;
    std::from_chars(msg.data() + a, msg.data() + b, *line);
    std::from_chars(msg.data() + c, msg.data() + d, *col);
    *reason = std::string(Trim(msg.substr(d + 1)));
    return true;
  }
  return false;
}

nlohmann::json CrdlFeedback(std::string_view crdl) {
  using nlohmann::json;
  json out;
  Result<Route> parsed = ParseCrdl(crdl, "route.crdl");
  int err_line = 0, err_col = 0;
  std::string reason;
  if (parsed.ok()) {
    out["ok"] = true;
    out["error"] = nullptr;
  } else {
    out["ok"] = false;
    if (SplitLocatedError(parsed.status().message(), &err_line, &err_col, &reason)) {
      out["error"] = {{"line", err_line}, {"column", err_col}, {"message", reason}};
    } else {
      out["error"] = {{"line", 0}, {"column", 0}, {"message", parsed.status().message()}};
    }
  }
#if SB_HAVE_LANGUAGE
  language::MoveLanguage* lang = ThreadLanguage();
#endif
  out["language"] = LanguageAvailable();
  json lines = json::array();
  std::string text(crdl);
  if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);
  bool in_moves = false;
  int n = 0;
  int moves = 0;
  for (std::string_view raw : SplitLines(text)) {
    ++n;
    json l;
    l["line"] = n;
    l["text"] = std::string(raw);
    std::string_view t = Trim(raw);
    if (!in_moves) {
      if (t == "---") {
        l["kind"] = "separator";
        in_moves = true;
      } else if (t.empty()) {
        l["kind"] = "blank";
      } else if (LooksLikeMeta(raw)) {
        l["kind"] = "meta";
      } else {
        l["kind"] = "description";
      }
    } else if (t.empty()) {
      l["kind"] = "blank";
    } else if (t[0] == '#') {
      l["kind"] = "comment";
    } else {
      size_t sp = t.find_first_of(" \t");
      std::string hand = ToLower(t.substr(0, sp));
      std::string_view rest =
          sp == std::string_view::npos ? std::string_view() : Trim(t.substr(sp));
      if (hand == "l" || hand == "left" || hand == "r" || hand == "right") {
        l["kind"] = "move";
        l["hand"] = hand[0] == 'l' ? "L" : "R";
        l["move"] = std::string(rest);
        ++moves;
        bool ok = false;
        std::string reading;
#if SB_HAVE_LANGUAGE
        if (lang) {
          language::MoveReading r = lang->Read(rest);
          ok = r.parse.ok();
          reading = lang->Explain(rest);
        }
#endif
        l["parsed"] = ok;
        l["reading"] = reading;
      } else {
        l["kind"] = "error";
      }
    }
    if (err_line == n) {
      l["kind"] = "error";
      l["error"] = reason;
    }
    lines.push_back(std::move(l));
  }
  out["lines"] = std::move(lines);
  out["moves"] = moves;
  return out;
}

}  // namespace sb::web
