#include "app/feedback.h"

#include <algorithm>
#include <memory>
#include <mutex>

#include "crdl/scan.h"
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

}  // namespace

bool LanguageAvailable() { return ThreadLanguage() != nullptr; }

EditorFeedback ReadForEditor(std::string_view crdl) {
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
        l.parsed = lang->Read(c.text).parse.ok();
        l.reading = lang->Explain(c.text);
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
