#include "app/feedback.h"

#include <algorithm>
#include <memory>
#include <mutex>
#include <string_view>

#include "app/limits.h"
#include "crdl/scan.h"
#include "language/styles.h"
#include "language/symbols.h"

namespace sb::app {

namespace {

// One MoveLanguage per thread (it is not thread-safe), cloned from a shared
// prototype that holds the grammar; null when the grammar cannot be loaded.
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

const char* KindName(CrdlLineKind k) {
  switch (k) {
    case CrdlLineKind::kBlank: return "blank";
    case CrdlLineKind::kMeta: return "meta";
    case CrdlLineKind::kDescription: return "description";
    case CrdlLineKind::kSeparator: return "separator";
    case CrdlLineKind::kComment: return "comment";
    case CrdlLineKind::kMove: return "move";
    case CrdlLineKind::kBadSeparator:
    case CrdlLineKind::kBadHand:
    case CrdlLineKind::kEmptyMove: return "error";
  }
  return "error";
}

// Optimal string alignment distance, stopping early above `cap`.
int Distance(std::string_view a, std::string_view b, int cap) {
  const size_t n = a.size(), m = b.size();
  if ((n > m ? n - m : m - n) > static_cast<size_t>(cap)) return cap + 1;
  std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1));
  for (size_t i = 0; i <= n; ++i) d[i][0] = static_cast<int>(i);
  for (size_t j = 0; j <= m; ++j) d[0][j] = static_cast<int>(j);
  for (size_t i = 1; i <= n; ++i) {
    for (size_t j = 1; j <= m; ++j) {
      int cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[n][m];
}

// The lower-case alphabetic words of a move text.
std::vector<std::string> Words(std::string_view text) {
  std::vector<std::string> out;
  std::string w;
  for (char c : text) {
    if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z')) {
      w += static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    } else if (!w.empty()) {
      out.push_back(std::move(w));
      w.clear();
    }
  }
  if (!w.empty()) out.push_back(std::move(w));
  return out;
}

// Common English words climbers write between the climbing words ("the",
// "and", "with", ...): the grammar skips them, so they are not misspellings
// and the editor must not suggest a climbing word for them ("the" is one
// letter from "toe"). Sorted, for binary search.
constexpr std::string_view kCommonWords[] = {
    "about", "after", "again", "all",   "also",  "and",   "any",   "are",   "around", "bad",
    "bit",   "bolt",  "bolts", "but",   "can",   "each",  "first", "for",   "from",   "gets",
    "good",  "has",   "have",  "her",   "here",  "his",   "into",  "its",   "just",   "last",
    "more",  "most",  "next",  "not",   "off",   "one",   "only",  "onto",  "other",  "our",
    "own",   "same",  "second","she",   "some",  "than",  "that",  "the",   "their",  "them",
    "then",  "there", "these", "they",  "this",  "three", "too",   "two",   "upon",   "use",
    "very",  "was",   "way",   "were",  "what",  "when",  "where", "which", "while",  "will",
    "with",  "you",   "your",
};

bool IsCommonWord(std::string_view w) {
  return std::binary_search(std::begin(kCommonWords), std::end(kCommonWords), w);
}

}  // namespace

std::string DidYouMean(std::string_view word, const std::vector<std::string>& vocabulary) {
  if (word.size() < 3 || IsCommonWord(word)) return "";
  const int cap = word.size() <= 4 ? 1 : 2;
  std::string best;
  int best_d = cap + 1;
  for (const std::string& v : vocabulary) {
    if (v == word) return "";
    if (v.size() < 3) continue;
    int d = Distance(word, v, cap);
    if (d < best_d) {
      best_d = d;
      best = v;
    }
  }
  return best_d <= cap ? best : "";
}

bool LanguageAvailable() { return ThreadLanguage() != nullptr; }

EditorFeedback ReadForEditor(std::string_view crdl, const RouteLimits& limits) {
  EditorFeedback out;
  if (crdl.size() > kMaxEditorBytes ||
      std::count(crdl.begin(), crdl.end(), '\n') >= kMaxEditorLines) {
    out.error_reason = "too long for live feedback: at most " + std::to_string(kMaxEditorBytes) +
                       " bytes and " + std::to_string(kMaxEditorLines) + " lines";
    return out;
  }
  Result<Route> parsed = ParseCrdl(crdl, "route.crdl");
  out.ok = parsed.ok();
  if (!parsed.ok()) {
    out.error = parsed.status().location();
    out.error_reason = parsed.status().reason();
  } else if (Status lim = CheckRouteLimits(*parsed, limits, "route.crdl"); !lim.ok()) {
    out.ok = false;
    out.error = lim.location();
    out.error_reason = lim.location() ? lim.reason() : lim.message();
  }
  language::MoveLanguage* lang = ThreadLanguage();
  out.language = lang != nullptr;
  CrdlSection section = CrdlSection::kHeader;
  int n = 0;
  for (std::string_view raw : SplitCrdlLines(crdl)) {
    EditorLine l;
    l.line = ++n;
    l.text = std::string(raw);
    CrdlLine c = ScanCrdlLine(raw, section);
    l.kind = KindName(c.kind);
    l.error = CrdlLineError(c);
    if (c.kind == CrdlLineKind::kSeparator || c.kind == CrdlLineKind::kBadSeparator) {
      section = CrdlSection::kMoves;
    }
    if (c.kind == CrdlLineKind::kMove) {
      l.hand = HandLetter(c.hand);
      l.move = std::string(c.text);
      l.crux = c.crux;
      ++out.moves;
      if (lang && c.text.size() <= kMaxEditorMoveBytes) {
        const language::MoveReading reading = lang->Read(c.text);
        l.parsed = reading.parse.ok();
        l.style = language::StyleOfParse(reading.parse).Describe();
        l.reading = lang->Explain(c.text);
        const language::Grammar& g = lang->grammar();
        for (const std::string& w : Words(c.text)) {
          if (g.WordId(w) >= 0) continue;
          std::string near = DidYouMean(w, g.words());
          if (!near.empty()) l.did_you_mean.emplace_back(w, near);
        }
      }
    }
    // The parser's verdict wins (invalid UTF-8, NUL bytes, a missing "---").
    if (out.error && out.error->line == n) {
      l.kind = "error";
      l.error = out.error_reason;
    }
    out.lines.push_back(std::move(l));
  }
  return out;
}

std::vector<std::string> MoveReadings(const Route& route) {
  std::vector<std::string> out;
  language::MoveLanguage* lang = ThreadLanguage();
  if (!lang) return out;
  for (const Move& m : route.moves) {
    out.push_back(lang->Read(m.text).parse.ok() ? lang->Explain(m.text) : "");
  }
  return out;
}

}  // namespace sb::app
