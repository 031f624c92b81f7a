#include "app/variation_meta.h"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <map>

#include "app/routes.h"
#include "base/date.h"
#include "base/hash.h"
#include "base/text.h"
#include "crdl/site_csv.h"

namespace sb::app {

namespace {

// Characters of UTF-8 text (continuation bytes do not count).
size_t Chars(std::string_view s) {
  size_t n = 0;
  for (unsigned char c : s) n += (c & 0xC0) != 0x80;
  return n;
}

// `s` cut to at most `max` characters at a character boundary, with "…".
std::string Cut(const std::string& s, size_t max) {
  if (Chars(s) <= max) return s;
  size_t n = 0, i = 0;
  for (; i < s.size(); ++i) {
    if ((static_cast<unsigned char>(s[i]) & 0xC0) != 0x80 && ++n > max - 1) break;
  }
  return s.substr(0, i) + "\xE2\x80\xA6";
}

std::string OneLine(std::string_view s) {
  std::string out(Trim(s));
  for (char& c : out) {
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  }
  return out;
}

std::string Today() { return UtcDateText(std::time(nullptr)); }

// A move's identity for matching edits: hand and text, case and runs of
// blanks folded; "(blank)" (how a blank is written) is the empty text.
std::string MoveKey(Hand hand, std::string_view text) {
  std::string t;
  bool space = false;
  for (char c : Trim(text)) {
    bool blank = c == ' ' || c == '\t';
    if (blank) {
      space = true;
      continue;
    }
    if (space && !t.empty()) t += ' ';
    space = false;
    t += static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  }
  if (t == "(blank)") t.clear();
  return std::string(HandLetter(hand)) + "|" + t;
}

// The largest table the in-order matching fills (cells of 2 bytes: 8 MB);
// longer pairs of move lists are matched greedily instead.
constexpr size_t kMaxLcsCells = 4'000'000;

// Pairs (generated index, edited index) of a longest common subsequence of
// the two key lists, in order.
std::vector<std::pair<int, int>> InOrderMatches(const std::vector<std::string>& a,
                                                const std::vector<std::string>& b) {
  std::vector<std::pair<int, int>> out;
  const size_t n = a.size(), m = b.size();
  if (n * m <= kMaxLcsCells) {
    // len[i][j] = LCS of a[i..] and b[j..].
    std::vector<uint16_t> len((n + 1) * (m + 1), 0);
    auto at = [&](size_t i, size_t j) -> uint16_t& { return len[i * (m + 1) + j]; };
    for (size_t i = n; i-- > 0;) {
      for (size_t j = m; j-- > 0;) {
        at(i, j) = a[i] == b[j] ? at(i + 1, j + 1) + 1 : std::max(at(i + 1, j), at(i, j + 1));
      }
    }
    size_t i = 0, j = 0;
    while (i < n && j < m) {
      if (a[i] == b[j]) {
        out.emplace_back(static_cast<int>(i++), static_cast<int>(j++));
      } else if (at(i + 1, j) >= at(i, j + 1)) {
        ++i;
      } else {
        ++j;
      }
    }
    return out;
  }
  // Greedy: each edited move takes the next generated move with its key.
  size_t i = 0;
  for (size_t j = 0; j < m && i < n; ++j) {
    size_t k = i;
    while (k < n && a[k] != b[j]) ++k;
    if (k < n) {
      out.emplace_back(static_cast<int>(k), static_cast<int>(j));
      i = k + 1;
    }
  }
  return out;
}

}  // namespace

std::string DefaultVariationName(const std::vector<std::string>& names) {
  std::vector<std::string> n;
  for (const std::string& s : names) n.push_back(OneLine(s).empty() ? "untitled" : OneLine(s));
  std::string list;
  if (n.empty()) {
    list = "nothing";
  } else if (n.size() == 1) {
    list = n[0];
  } else if (n.size() <= 3) {
    for (size_t i = 0; i + 1 < n.size(); ++i) list += (i ? ", " : "") + n[i];
    list += " and " + n.back();
  } else {
    list = n[0] + ", " + n[1] + " and " + std::to_string(n.size() - 2) + " more";
  }
  return Cut("Variation of " + list, kMaxDefaultNameChars);
}

Status ValidateMetadata(const VariationMetadata& m) {
  const std::pair<const char*, const std::string*> one_line[] = {
      {"name", &m.name},     {"grade", &m.grade},   {"colour", &m.colour},
      {"wall", &m.wall},     {"setter", &m.setter}, {"date", &m.date}};
  for (const auto& [field, value] : one_line) {
    if (Chars(*value) > kMaxMetaFieldChars) {
      return Status::InvalidInput(std::string(field) + ": at most " +
                                  std::to_string(kMaxMetaFieldChars) + " characters");
    }
    if (value->find_first_of("\r\n") != std::string::npos) {
      return Status::InvalidInput(std::string(field) + ": one line only");
    }
  }
  if (Chars(m.notes) > kMaxNotesChars) {
    return Status::InvalidInput("notes: at most " + std::to_string(kMaxNotesChars) +
                                " characters");
  }
  return Status::Ok();
}

Route VariationRoute(const VariationMetadata& meta, const std::vector<int64_t>& ids,
                     const chaos::Variation& variation) {
  Route r;
  r.header.push_back({"name", OneLine(meta.name)});
  const std::pair<const char*, const std::string*> fields[] = {{"grade", &meta.grade},
                                                               {"colour", &meta.colour},
                                                               {"wall", &meta.wall},
                                                               {"setter", &meta.setter}};
  for (const auto& [key, value] : fields) {
    if (!Trim(*value).empty()) r.header.push_back({key, OneLine(*value)});
  }
  r.header.push_back({"date", OneLine(meta.date).empty() ? Today() : OneLine(meta.date)});
  std::string from;
  for (size_t i = 0; i < ids.size(); ++i) from += (i ? "," : "") + std::to_string(ids[i]);
  r.header.push_back({"varied-from", from});
  for (std::string_view line : SplitLines(meta.notes)) {
    if (!Trim(line).empty()) r.header.push_back({"", SafeHeaderText(line)});
  }
  for (const chaos::VariedMove& m : variation.moves) {
    r.moves.push_back({m.hand, m.text.empty() ? "(blank)" : m.text, 0, m.crux});
  }
  return r;
}

Result<bool> VariationVisibility(const std::vector<store::RouteRecord>& inputs,
                                 std::optional<bool> asked, std::optional<int64_t> gym) {
  bool private_source = std::any_of(inputs.begin(), inputs.end(), [](const store::RouteRecord& r) {
    return HasPrivateSource(r, /*self=*/true);
  });
  if (asked.value_or(false) && private_source) {
    return Status::InvalidInput(kPrivateSourceMessage);
  }
  return asked.value_or(!private_source && DefaultInLibrary(gym));
}

std::string RequestKey(const std::string& params_json, bool smooth,
                       const std::vector<store::RouteRecord>& inputs,
                       std::optional<bool> is_public, const VariationMetadata& meta) {
  std::string c = params_json;
  auto add = [&](const std::string& s) {
    c += '\x1f';
    c += std::to_string(s.size());
    c += ':';
    c += s;
  };
  add(smooth ? "smooth" : "");
  for (const store::RouteRecord& r : inputs) {
    add(std::to_string(r.id));
    add(r.crdl);
  }
  add(!is_public ? "default" : *is_public ? "public" : "private");
  for (const std::string* f : {&meta.name, &meta.grade, &meta.colour, &meta.wall, &meta.setter,
                               &meta.date, &meta.notes}) {
    add(*f);
  }
  char hex[33];
  std::snprintf(hex, sizeof hex, "%016llx%016llx", static_cast<unsigned long long>(Fnv1a64(c)),
                static_cast<unsigned long long>(Fnv1a64("request key\x1f" + c)));
  return hex;
}

bool SameRequest(const store::RouteRecord& existing, const std::string& params_json, bool smooth,
                 const std::vector<store::RouteRecord>& inputs, std::optional<bool> is_public,
                 const VariationMetadata& meta) {
  if (existing.params_json != params_json || existing.smooth != smooth ||
      existing.inputs.size() != inputs.size()) {
    return false;
  }
  if (is_public && existing.is_public != *is_public) return false;
  if (!meta.name.empty() && existing.name != meta.name) return false;
  for (size_t i = 0; i < inputs.size(); ++i) {
    const store::VariationInput& vi = existing.inputs[i];
    if (vi.route_id != inputs[i].id || vi.crdl != inputs[i].crdl) return false;
  }
  return true;
}

EditSummary ApplyEdits(const Route& edited, plan::RoutePlan* plan) {
  std::vector<chaos::VariedMove>& gen = plan->variation.moves;
  std::vector<std::string> a, b;
  for (const chaos::VariedMove& m : gen) a.push_back(MoveKey(m.hand, m.text));
  for (const Move& m : edited.moves) b.push_back(MoveKey(m.hand, m.text));
  EditSummary sum;
  if (a == b) {
    // Unchanged moves: only the crux flags can differ.
    for (size_t i = 0; i < gen.size(); ++i) gen[i].crux = edited.moves[i].crux;
    sum.kept = static_cast<int>(gen.size());
    return sum;
  }
  std::vector<int> from(b.size(), -1);  // edited index -> generated index
  std::vector<bool> used(a.size(), false);
  for (auto [i, j] : InOrderMatches(a, b)) {
    from[j] = i;
    used[i] = true;
    ++sum.kept;
  }
  // Moves the setter moved: the first unused generated move with that key.
  std::multimap<std::string, int> unused;
  for (size_t i = 0; i < a.size(); ++i) {
    if (!used[i]) unused.emplace(a[i], static_cast<int>(i));
  }
  for (size_t j = 0; j < b.size(); ++j) {
    if (from[j] >= 0) continue;
    auto it = unused.find(b[j]);
    if (it == unused.end()) continue;
    from[j] = it->second;
    used[it->second] = true;
    unused.erase(it);
    ++sum.moved;
  }
  std::vector<chaos::VariedMove> out;
  std::vector<int> landed(a.size(), -1);  // generated index -> edited index
  for (size_t j = 0; j < b.size(); ++j) {
    const Move& e = edited.moves[j];
    chaos::VariedMove m;
    if (from[j] >= 0) {
      m = gen[from[j]];
      landed[from[j]] = static_cast<int>(j);
    } else {
      m.changed = true;
      m.added = true;
      m.notes.push_back(kAddedNote);
      ++sum.added;
    }
    m.hand = e.hand;
    m.text = MoveKey(e.hand, e.text).size() == 2 ? "" : e.text;  // "(blank)" stays a blank
    m.crux = e.crux;
    out.push_back(std::move(m));
  }
  for (bool u : used) sum.removed += u ? 0 : 1;
  std::vector<plan::Suggestion> kept;
  for (plan::Suggestion& s : plan->smoothing) {
    if (s.after < 0 || static_cast<size_t>(s.after) >= landed.size() || landed[s.after] < 0) {
      continue;
    }
    s.after = landed[s.after];
    kept.push_back(std::move(s));
  }
  std::stable_sort(kept.begin(), kept.end(), [](const plan::Suggestion& x,
                                                const plan::Suggestion& y) {
    return x.after < y.after;
  });
  plan->smoothing = std::move(kept);
  gen = std::move(out);
  return sum;
}

}  // namespace sb::app
