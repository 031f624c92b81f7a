#include "plan/colour.h"

#include <algorithm>
#include <cctype>
#include <map>

namespace sb::plan {

namespace {

// One colour of the table: its English name, swatch and the names it goes
// by in the UI's languages (German and French; feminine and ASCII spellings
// too: "grün" and "gruen", "vert" and "verte").
struct Entry {
  const char* english;
  Rgb rgb;
  std::vector<const char*> names;
};

// The one colour table (issue 32). English names first (the table's order
// breaks ties between suggestions).
const std::vector<Entry>& Table() {
  static const auto* table = new std::vector<Entry>{
      {"black", {0.05, 0.05, 0.05}, {"black", "schwarz", "noir", "noire"}},
      {"white", {1, 1, 1}, {"white", "weiß", "weiss", "blanc", "blanche"}},
      {"grey", {0.55, 0.55, 0.55}, {"grey", "gray", "grau", "gris", "grise"}},
      {"red", {0.85, 0.1, 0.1}, {"red", "rot", "rouge"}},
      {"orange", {1.0, 0.55, 0.0}, {"orange"}},
      {"yellow", {1.0, 0.87, 0.0}, {"yellow", "gelb", "jaune"}},
      {"green", {0.1, 0.6, 0.2}, {"green", "grün", "gruen", "vert", "verte"}},
      {"lime", {0.6, 0.85, 0.1}, {"lime", "limette", "limettengrün", "citron"}},
      {"teal", {0.0, 0.55, 0.55}, {"teal", "petrol", "sarcelle"}},
      {"cyan", {0.0, 0.75, 0.9}, {"cyan"}},
      {"turquoise", {0.25, 0.85, 0.8}, {"turquoise", "türkis", "tuerkis"}},
      {"blue", {0.1, 0.3, 0.85}, {"blue", "blau", "bleu", "bleue"}},
      {"navy", {0.05, 0.1, 0.45}, {"navy", "marine", "marineblau"}},
      {"purple", {0.5, 0.15, 0.65}, {"purple", "lila", "pourpre", "mauve"}},
      {"violet", {0.55, 0.3, 0.85}, {"violet", "violett", "violette"}},
      {"magenta", {0.9, 0.1, 0.6}, {"magenta", "fuchsia", "fuchsie"}},
      {"pink", {1.0, 0.55, 0.75}, {"pink", "rosa", "rose"}},
      {"brown", {0.5, 0.3, 0.12}, {"brown", "braun", "marron", "brun", "brune"}},
      {"beige", {0.9, 0.85, 0.7}, {"beige"}},
      {"gold", {0.85, 0.68, 0.15}, {"gold", "golden", "doré", "dorée"}},
      {"silver", {0.75, 0.75, 0.78}, {"silver", "silber", "argent", "argenté", "argentée"}},
  };
  return *table;
}

// name (any language) -> index into Table().
const std::map<std::string, size_t>& ByName() {
  static const auto* by = [] {
    auto* m = new std::map<std::string, size_t>;
    for (size_t i = 0; i < Table().size(); ++i) {
      for (const char* n : Table()[i].names) m->emplace(n, i);
    }
    return m;
  }();
  return *by;
}

// Lower case for ASCII and the Latin-1 letters À..Þ (German and French
// capitals: "GRÜN" -> "grün", "É" -> "é"); other bytes unchanged.
std::string Lower(std::string_view s) {
  std::string out(s);
  for (size_t i = 0; i < out.size(); ++i) {
    unsigned char c = static_cast<unsigned char>(out[i]);
    if (c < 0x80) {
      out[i] = static_cast<char>(std::tolower(c));
    } else if (c == 0xC3 && i + 1 < out.size()) {
      unsigned char d = static_cast<unsigned char>(out[i + 1]);
      if (d >= 0x80 && d <= 0x9E && d != 0x97) out[i + 1] = static_cast<char>(d + 0x20);
      ++i;
    }
  }
  return out;
}

std::string_view TrimSpace(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

int HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

std::optional<Rgb> HexColour(std::string_view s) {
  if (s.size() != 4 && s.size() != 7) return std::nullopt;
  const bool short_form = s.size() == 4;
  double v[3];
  for (int i = 0; i < 3; ++i) {
    int hi = HexDigit(s[1 + (short_form ? i : 2 * i)]);
    int lo = HexDigit(s[short_form ? 1 + i : 2 + 2 * i]);
    if (hi < 0 || lo < 0) return std::nullopt;
    v[i] = (short_form ? hi * 17 : hi * 16 + lo) / 255.0;
  }
  return Rgb{v[0], v[1], v[2]};
}

// One word's table entry: the word itself, or a German compound with a
// shade prefix ("hellblau", "dunkelgrün", "neongelb").
std::optional<size_t> WordEntry(const std::string& word) {
  if (auto it = ByName().find(word); it != ByName().end()) return it->second;
  for (const char* prefix : {"hell", "dunkel", "neon", "pastell", "leucht"}) {
    const std::string p = prefix;
    if (word.size() > p.size() && word.compare(0, p.size(), p) == 0) {
      if (auto it = ByName().find(word.substr(p.size())); it != ByName().end()) return it->second;
    }
  }
  return std::nullopt;
}

// The table entry of a colour name or phrase: its last known colour word.
std::optional<size_t> NamedEntry(const std::string& lower) {
  std::optional<size_t> found;
  std::string word;
  auto take = [&] {
    if (!word.empty()) {
      if (std::optional<size_t> e = WordEntry(word)) found = e;
    }
    word.clear();
  };
  for (char c : lower) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u >= 0x80 || std::isalpha(u)) {
      word += c;
    } else {
      take();
    }
  }
  take();
  return found;
}

size_t Nearest(const Rgb& c) {
  size_t best = 0;
  double best_d = 1e9;
  for (size_t i = 0; i < Table().size(); ++i) {
    const Rgb& t = Table()[i].rgb;
    const double d = (t.r - c.r) * (t.r - c.r) + (t.g - c.g) * (t.g - c.g) +
                     (t.b - c.b) * (t.b - c.b);
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  return best;
}

// Levenshtein distance over bytes (the names are short).
size_t EditDistance(std::string_view a, std::string_view b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

}  // namespace

std::optional<Rgb> ColourSwatch(const std::string& colour) {
  const std::string s = Lower(TrimSpace(colour));
  if (!s.empty() && s[0] == '#') return HexColour(s);
  if (std::optional<size_t> e = NamedEntry(s)) return Table()[*e].rgb;
  return std::nullopt;
}

std::string ColourName(const std::string& colour) {
  const std::string s = Lower(TrimSpace(colour));
  if (!s.empty() && s[0] == '#') {
    std::optional<Rgb> rgb = HexColour(s);
    return rgb ? Table()[Nearest(*rgb)].english : "";
  }
  std::optional<size_t> e = NamedEntry(s);
  return e ? Table()[*e].english : "";
}

std::string ColourLabel(const std::string& colour) {
  const std::string_view t = TrimSpace(colour);
  if (!t.empty() && t[0] == '#') {
    const std::string name = ColourName(std::string(t));
    if (!name.empty()) return name + " (" + std::string(t) + ")";
  }
  return std::string(t);
}

const std::vector<std::string>& KnownColourNames() {
  static const auto* names = [] {
    auto* v = new std::vector<std::string>;
    for (const Entry& e : Table()) {
      for (const char* n : e.names) v->push_back(n);
    }
    return v;
  }();
  return *names;
}

std::vector<std::string> ColourSuggestions(std::string_view text, size_t n) {
  const std::string s = Lower(TrimSpace(text));
  std::vector<std::pair<size_t, size_t>> scored;  // (distance, position)
  const std::vector<std::string>& names = KnownColourNames();
  for (size_t i = 0; i < names.size(); ++i) scored.emplace_back(EditDistance(s, names[i]), i);
  std::stable_sort(scored.begin(), scored.end());
  std::vector<std::string> out;
  for (const auto& [d, i] : scored) {
    if (out.size() >= n) break;
    out.push_back(names[i]);
  }
  return out;
}

Status CheckColour(std::string_view field, const std::string& colour) {
  const std::string_view t = TrimSpace(colour);
  if (t.empty() || ColourSwatch(colour)) return Status::Ok();
  std::string msg = std::string(field) + ": \"" + std::string(t) +
                    "\" is not a colour name or #rgb/#rrggbb code";
  if (t[0] != '#') {
    std::string list;
    for (const std::string& s : ColourSuggestions(t)) list += (list.empty() ? "" : ", ") + s;
    msg += " (did you mean " + list + "?)";
  }
  return Status::InvalidInput(msg);
}

}  // namespace sb::plan
