#include "studies/instrument.h"

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>

#include "base/files.h"

namespace sb::studies {
namespace {

using nlohmann::json;

// "q<n>" (built with += : GCC 12 warns falsely (-Wrestrict) about "q" + std::string).
std::string ItemId(int n) {
  std::string id(1, 'q');
  id += std::to_string(n);
  return id;
}

Instrument MakeBrc() {
  // Paper appendix B, table 5 ("Neg." column: items 1, 2, 8, 12).
  static const char* const kTexts[] = {
      "Too easy for the grade",
      "Too difficult for the grade",
      "Difficulty is consistent throughout the climb",
      "Requires thoughtful/nontrivial beta",
      "Has good flow throughout",
      "Appears to be well thought out",
      "Is creative/has interesting moves",
      "Climbs awkwardly",
      "Good variety of handholds/types of grips",
      "Has a definite crux",
      "Crux is technically engaging",
      "Has an unpleasant/stopper crux",
      "Is a route I would climb again",
      "Is a route I would recommend to others",
  };
  Instrument in{"BRC 14-item instrument (Strange Beta, table 5)", -2, 2, {}};
  for (int i = 0; i < 14; ++i) {
    const int n = i + 1;
    in.items.push_back({ItemId(n), kTexts[i], n == 1 || n == 2 || n == 8 || n == 12});
  }
  return in;
}

Instrument MakePilot() {
  // Paper appendix B, table 4; no item is negatively keyed.
  static const char* const kTexts[] = {
      "Appropriate difficulty",
      "Sustained difficulty",
      "Has good flow/seems consonant",
      "Is creative/has interesting moves",
      "Requires thought/non-obvious beta",
  };
  Instrument in{"Pilot 5-item instrument (Strange Beta, table 4)", 1, 5, {}};
  for (int i = 0; i < 5; ++i) in.items.push_back({ItemId(i + 1), kTexts[i], false});
  return in;
}

Status Invalid(std::string_view name, const std::string& field, const std::string& msg) {
  return Status::InvalidInput(std::string(name) + ": " + field + ": " + msg);
}

bool IdChar(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '.';
}

// Text without control characters (tabs and newlines included: one line each).
bool CleanText(std::string_view s) {
  return std::none_of(s.begin(), s.end(),
                      [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
}

Status CheckKeys(const json& obj, std::initializer_list<const char*> allowed, std::string_view name,
                 const std::string& where) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool ok =
        std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return it.key() == a; });
    if (!ok) return Invalid(name, where + it.key(), "unknown field");
  }
  return Status::Ok();
}

// The 1-based line and column of byte offset `end` of `text`.
std::pair<int, int> LineCol(std::string_view text, size_t end) {
  end = std::min(end, text.size());
  int line = 1, col = 1;
  for (size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return {line, col};
}

// "name:line:col: message" for a JSON syntax error at byte offset `byte`.
Status SyntaxError(std::string_view text, std::string_view name, const json::parse_error& e) {
  auto [line, col] = LineCol(text, e.byte == 0 ? 0 : e.byte - 1);
  std::string what = e.what(), detail = what;
  if (size_t p = what.find("column "); p != std::string::npos) {
    if (size_t q = what.find(": ", p); q != std::string::npos) detail = what.substr(q + 2);
  }
  return Status::InvalidInputAt({std::string(name), line, col}, "JSON syntax error: " + detail);
}

// "name:line:col: number out of range: 4e10058" for the other error the JSON
// reader raises while parsing (a number beyond double's range). The reader
// names the token, not its place: the token's first occurrence is it.
Status NumberError(std::string_view text, std::string_view name, const json::exception& e) {
  std::string what = e.what(), token;
  if (size_t a = what.find('\''); a != std::string::npos) {
    if (size_t b = what.find('\'', a + 1); b != std::string::npos)
      token = what.substr(a + 1, b - a - 1);
  }
  size_t at = token.empty() ? std::string_view::npos : text.find(token);
  auto [line, col] = LineCol(text, at == std::string_view::npos ? 0 : at);
  return Status::InvalidInputAt({std::string(name), line, col},
                                "number out of range: " + (token.empty() ? what : token));
}

Status ReadScale(const json& j, std::string_view name, Instrument* out) {
  if (!j.contains("scale")) return Invalid(name, "scale", "missing (expected [min, max])");
  const json& s = j["scale"];
  if (!s.is_array() || s.size() != 2 || !s[0].is_number_integer() || !s[1].is_number_integer()) {
    return Invalid(name, "scale", "expected two integers [min, max], got " + s.dump());
  }
  // Compared as doubles first: a huge unsigned value must not wrap around.
  const double dlo = s[0].get<double>(), dhi = s[1].get<double>();
  if (dlo < -kMaxScaleValue || dlo > kMaxScaleValue || dhi < -kMaxScaleValue ||
      dhi > kMaxScaleValue) {
    return Invalid(name, "scale",
                   "values must lie in [-" + std::to_string(kMaxScaleValue) + ", " +
                       std::to_string(kMaxScaleValue) + "]");
  }
  out->scale_min = int(dlo);
  out->scale_max = int(dhi);
  return Status::Ok();
}

Status ReadItem(const json& it, size_t index, std::string_view name, Item* out) {
  const std::string where = "items[" + std::to_string(index) + "]";
  if (!it.is_object()) return Invalid(name, where, "expected an object {\"id\", \"text\", ...}");
  SB_RETURN_IF_ERROR(CheckKeys(it, {"id", "text", "negative"}, name, where + "."));
  if (!it.contains("id") || !it["id"].is_string()) {
    return Invalid(name, where + ".id", "missing or not a string");
  }
  if (!it.contains("text") || !it["text"].is_string()) {
    return Invalid(name, where + ".text", "missing or not a string");
  }
  out->id = it["id"].get<std::string>();
  out->text = it["text"].get<std::string>();
  out->negative = false;
  if (it.contains("negative")) {
    if (!it["negative"].is_boolean())
      return Invalid(name, where + ".negative", "expected true or false");
    out->negative = it["negative"].get<bool>();
  }
  return Status::Ok();
}

}  // namespace

int Instrument::IndexOf(std::string_view id) const {
  for (size_t i = 0; i < items.size(); ++i) {
    if (items[i].id == id) return int(i);
  }
  return -1;
}

bool IsReservedColumn(std::string_view id) {
  return id == "participant" || id == "route" || id == "rank" || id == "order" || id == "ability";
}

const Instrument& BrcInstrument() {
  static const Instrument kBrc = MakeBrc();
  return kBrc;
}

const Instrument& PilotInstrument() {
  static const Instrument kPilot = MakePilot();
  return kPilot;
}

const std::vector<Question>& BrcDemographics() {
  static const std::vector<Question> kQuestions = {
      {"years_climbing", "Years climbing?", AnswerKind::kNumber},
      {"years_gym", "Years climbing in a gym?", AnswerKind::kNumber},
      {"hardest_indoor", "Hardest indoor redpoint?", AnswerKind::kGrade},
      {"hardest_outdoor", "Hardest outdoor redpoint?", AnswerKind::kGrade},
      {"days_outside", "Days per week climbing outside?", AnswerKind::kNumber},
      {"days_gym", "Days per week climbing at the gym?", AnswerKind::kNumber},
      {"indoor_range", "Typical indoor grade range?", AnswerKind::kGradeRange},
      {"outdoor_range", "Typical outdoor grade range?", AnswerKind::kGradeRange},
      {"order", "In what order did you climb the routes (e.g., 1,4,3,2)?", AnswerKind::kRouteOrder},
      {"rank", "What is your overall ranking of the routes from best to worst (e.g., 4,2,1,3)?",
       AnswerKind::kRouteRanking},
      {"ice_cream", "What is your favorite ice cream flavor?", AnswerKind::kText},
  };
  return kQuestions;
}

Status ValidateInstrument(const Instrument& in, std::string_view name) {
  if (in.name.empty() || in.name.size() > size_t(kMaxTextLength) || !CleanText(in.name)) {
    return Invalid(name, "name",
                   "must be 1-" + std::to_string(kMaxTextLength) + " bytes on one line");
  }
  if (in.scale_min < -kMaxScaleValue || in.scale_max > kMaxScaleValue) {
    return Invalid(name, "scale",
                   "values must lie in [-" + std::to_string(kMaxScaleValue) + ", " +
                       std::to_string(kMaxScaleValue) + "]");
  }
  if (in.scale_min >= in.scale_max || in.scale_max - in.scale_min > kMaxScaleWidth) {
    return Invalid(name, "scale",
                   "need min < max and at most " + std::to_string(kMaxScaleWidth + 1) +
                       " categories, got [" + std::to_string(in.scale_min) + ", " +
                       std::to_string(in.scale_max) + "]");
  }
  if (in.items.empty() || in.items.size() > size_t(kMaxItems)) {
    return Invalid(
        name, "items",
        "need 1-" + std::to_string(kMaxItems) + " items, got " + std::to_string(in.items.size()));
  }
  std::map<std::string, size_t> seen;
  for (size_t i = 0; i < in.items.size(); ++i) {
    const Item& it = in.items[i];
    const std::string where = "items[" + std::to_string(i) + "]";
    if (it.id.empty() || it.id.size() > size_t(kMaxItemIdLength) ||
        !std::all_of(it.id.begin(), it.id.end(), IdChar)) {
      return Invalid(name, where + ".id",
                     "\"" + it.id + "\" must be 1-" + std::to_string(kMaxItemIdLength) +
                         " characters from A-Z a-z 0-9 _ - .");
    }
    if (IsReservedColumn(it.id)) {
      return Invalid(name, where + ".id",
                     "\"" + it.id + "\" is reserved (participant, route, rank, order, ability)");
    }
    if (auto [pos, fresh] = seen.emplace(it.id, i); !fresh) {
      return Invalid(
          name, where + ".id",
          "duplicate id \"" + it.id + "\" (also items[" + std::to_string(pos->second) + "])");
    }
    if (it.text.empty() || it.text.size() > size_t(kMaxTextLength) || !CleanText(it.text)) {
      return Invalid(name, where + ".text",
                     "must be 1-" + std::to_string(kMaxTextLength) + " bytes on one line");
    }
  }
  return Status::Ok();
}

Result<Instrument> ParseInstrument(std::string_view text, std::string_view name) {
  if (text.size() > kMaxInstrumentBytes) {
    return Status::InvalidInput(std::string(name) + ": instrument file larger than " +
                                std::to_string(kMaxInstrumentBytes) + " bytes");
  }
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    return SyntaxError(text, name, e);
  } catch (const json::exception& e) {
    return NumberError(text, name, e);
  }
  if (!j.is_object()) {
    return Status::InvalidInput(std::string(name) +
                                ": expected a JSON object {\"name\", \"scale\", \"items\"}");
  }
  SB_RETURN_IF_ERROR(CheckKeys(j, {"name", "scale", "items"}, name, ""));
  Instrument in;
  if (!j.contains("name") || !j["name"].is_string()) {
    return Invalid(name, "name", "missing or not a string");
  }
  in.name = j["name"].get<std::string>();
  SB_RETURN_IF_ERROR(ReadScale(j, name, &in));
  if (!j.contains("items") || !j["items"].is_array()) {
    return Invalid(name, "items", "missing or not an array");
  }
  if (j["items"].size() > size_t(kMaxItems)) {
    return Invalid(name, "items", "more than " + std::to_string(kMaxItems) + " items");
  }
  in.items.resize(j["items"].size());
  for (size_t i = 0; i < in.items.size(); ++i) {
    SB_RETURN_IF_ERROR(ReadItem(j["items"][i], i, name, &in.items[i]));
  }
  SB_RETURN_IF_ERROR(ValidateInstrument(in, name));
  return in;
}

Result<Instrument> LoadInstrument(const std::string& spec) {
  if (spec == "brc") return BrcInstrument();
  if (spec == "pilot") return PilotInstrument();
  Result<std::string> text = ReadFile(spec);
  if (!text.ok()) return text.status();
  return ParseInstrument(*text, spec);
}

std::string InstrumentToJson(const Instrument& in) {
  nlohmann::ordered_json out;
  out["name"] = in.name;
  out["scale"] = {in.scale_min, in.scale_max};
  out["items"] = nlohmann::ordered_json::array();
  for (const Item& it : in.items) {
    out["items"].push_back({{"id", it.id}, {"text", it.text}, {"negative", it.negative}});
  }
  return out.dump(2) + "\n";
}

}  // namespace sb::studies
