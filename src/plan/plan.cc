#include "plan/plan.h"

#include <cairo-svg.h>
#include <cairo.h>

#include <charconv>
#include <cmath>
#include <set>

#include "base/text.h"
#include "plan/draw.h"
#include "plan/format.h"

namespace sb::plan {

using chaos::VaryParams;
using nlohmann::json;

std::string FormatNumber(double v) {
  if (v == 0) v = 0;  // no "-0"
  char buf[64];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, p);
}

std::string FormatTriple(const std::array<double, 3>& v) {
  return FormatNumber(v[0]) + "," + FormatNumber(v[1]) + "," + FormatNumber(v[2]);
}

Result<Format> ParseFormat(std::string_view s) {
  std::string l = ToLower(s);
  if (l == "text" || l == "txt") return Format::kText;
  if (l == "markdown" || l == "md") return Format::kMarkdown;
  if (l == "json") return Format::kJson;
  if (l == "svg") return Format::kSvg;
  return Status::InvalidInput("unknown format \"" + std::string(s) +
                              "\" (text, markdown, json or svg)");
}

// ---------------------------------------------------------------------------
// Parameters.

json ParamsToJson(const VaryParams& p) {
  json j;
  j["preset"] = p.preset;
  j["system"] = chaos::SystemKindName(p.system.kind);
  j["params"] = p.system.params;
  j["integrator"] = chaos::IntegratorKindName(p.integrator);
  j["step"] = p.step;
  j["ref_ic"] = p.ref_ic;
  j["var_ic"] = p.var_ic;
  j["skip"] = p.skip;
  j["mapping"] = chaos::MappingKindName(p.mapping.kind);
  j["mask"] = chaos::MaskString(p.mapping.mask);
  j["dabby_direction"] = chaos::DabbyDirectionName(p.mapping.dabby_direction);
  j["max_repeat"] = p.mapping.max_repeat;
  return j;
}

namespace {

Status FieldError(const std::string& field, const std::string& what) {
  return Status::InvalidInput(field + ": " + what);
}

Status GetTriple(const json& j, const char* field, std::array<double, 3>* out) {
  if (!j.contains(field)) return Status::Ok();
  const json& v = j.at(field);
  if (v.is_string()) {
    const std::string text = v.get<std::string>();  // Split's views point into it
    auto parts = Split(text, ',');
    if (parts.size() != 3) return FieldError(field, "expected three numbers x,y,z");
    for (int i = 0; i < 3; ++i) {
      std::string_view t = Trim(parts[i]);
      auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), (*out)[i]);
      if (ec != std::errc() || p != t.data() + t.size() || t.empty()) {
        return FieldError(field, "expected three numbers x,y,z");
      }
    }
    return Status::Ok();
  }
  if (!v.is_array() || v.size() != 3) return FieldError(field, "expected an array of 3 numbers");
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number()) return FieldError(field, "expected an array of 3 numbers");
    (*out)[i] = v[i].get<double>();
  }
  return Status::Ok();
}

template <typename T, typename ParseFn>
Status GetEnum(const json& j, const char* field, ParseFn parse, T* out) {
  if (!j.contains(field)) return Status::Ok();
  if (!j.at(field).is_string()) return FieldError(field, "expected a string");
  auto r = parse(j.at(field).get<std::string>());
  if (!r.ok()) return FieldError(field, r.status().message());
  *out = *r;
  return Status::Ok();
}

Status GetInt(const json& j, const char* field, int lo, int hi, int* out) {
  if (!j.contains(field)) return Status::Ok();
  const json& v = j.at(field);
  if (!v.is_number_integer()) return FieldError(field, "expected a whole number");
  long long x = v.get<long long>();
  if (x < lo || x > hi) {
    return FieldError(field, "must be between " + std::to_string(lo) + " and " +
                                 std::to_string(hi));
  }
  *out = static_cast<int>(x);
  return Status::Ok();
}

}  // namespace

Result<VaryParams> ParamsFromJson(const json& j) {
  if (!j.is_object()) return Status::InvalidInput("parameters: expected an object");
  VaryParams p;
  if (j.contains("preset")) {
    if (!j["preset"].is_string()) return FieldError("preset", "expected a string");
    auto pr = VaryParams::Preset(j["preset"].get<std::string>());
    if (!pr.ok()) return FieldError("preset", pr.status().message());
    p = *pr;
  }
  SB_RETURN_IF_ERROR(GetEnum(j, "system", chaos::ParseSystemKind, &p.system.kind));
  if (j.contains("system") && !j.contains("params")) p.system.params = chaos::DefaultParams(p.system.kind);
  SB_RETURN_IF_ERROR(GetTriple(j, "params", &p.system.params));
  SB_RETURN_IF_ERROR(GetEnum(j, "integrator", chaos::ParseIntegratorKind, &p.integrator));
  if (j.contains("step")) {
    if (!j["step"].is_number()) return FieldError("step", "expected a number");
    p.step = j["step"].get<double>();
  }
  SB_RETURN_IF_ERROR(GetTriple(j, "ref_ic", &p.ref_ic));
  SB_RETURN_IF_ERROR(GetTriple(j, "var_ic", &p.var_ic));
  SB_RETURN_IF_ERROR(GetInt(j, "skip", 0, 100000000, &p.skip));
  SB_RETURN_IF_ERROR(GetEnum(j, "mapping", chaos::ParseMappingKind, &p.mapping.kind));
  SB_RETURN_IF_ERROR(GetEnum(j, "mask", chaos::ParseMask, &p.mapping.mask));
  SB_RETURN_IF_ERROR(
      GetEnum(j, "dabby_direction", chaos::ParseDabbyDirection, &p.mapping.dabby_direction));
  SB_RETURN_IF_ERROR(GetInt(j, "max_repeat", 0, 1000000, &p.mapping.max_repeat));
  SB_RETURN_IF_ERROR(p.Validate());
  return p;
}

std::string ReproduceOptions(const VaryParams& p) {
  std::string s = "--system " + std::string(chaos::SystemKindName(p.system.kind)) +
                  " --params " + FormatTriple(p.system.params) + " --integrator " +
                  chaos::IntegratorKindName(p.integrator) + " --step " + FormatNumber(p.step) +
                  " --ref-ic=" + FormatTriple(p.ref_ic) + " --var-ic=" + FormatTriple(p.var_ic) +
                  " --skip " + std::to_string(p.skip) + " --mapping " +
                  chaos::MappingKindName(p.mapping.kind) + " --mask " +
                  chaos::MaskString(p.mapping.mask);
  if (p.mapping.kind == chaos::MappingKind::kDabby) {
    s += std::string(" --dabby-direction ") + chaos::DabbyDirectionName(p.mapping.dabby_direction);
  }
  if (p.mapping.max_repeat > 0) s += " --max-repeat " + std::to_string(p.mapping.max_repeat);
  return s;
}

// ---------------------------------------------------------------------------
// Text and Markdown.

namespace {

std::string ParamNames(chaos::SystemKind k) {
  return k == chaos::SystemKind::kLorenz ? "a, r, b" : "a, b, c";
}

std::vector<std::string> ParameterLines(const VaryParams& p) {
  std::vector<std::string> out;
  out.push_back("preset " + p.preset + "; system " + chaos::SystemKindName(p.system.kind) + " (" +
                ParamNames(p.system.kind) + " = " + FormatNumber(p.system.params[0]) + ", " +
                FormatNumber(p.system.params[1]) + ", " + FormatNumber(p.system.params[2]) + ")");
  out.push_back(std::string("integrator ") + chaos::IntegratorKindName(p.integrator) + ", step " +
                FormatNumber(p.step) + ", skip " + std::to_string(p.skip));
  out.push_back("reference IC (" + FormatTriple(p.ref_ic) + "), variation IC (" +
                FormatTriple(p.var_ic) + ")");
  std::string mapping = std::string("mapping ") + chaos::MappingKindName(p.mapping.kind);
  if (p.mapping.kind == chaos::MappingKind::kEuclidean) {
    mapping += ", mask " + chaos::MaskString(p.mapping.mask);
  } else {
    mapping += std::string(", direction ") + chaos::DabbyDirectionName(p.mapping.dabby_direction);
  }
  mapping += ", max-repeat " +
             (p.mapping.max_repeat > 0 ? std::to_string(p.mapping.max_repeat) : std::string("off"));
  out.push_back(mapping);
  return out;
}

std::string Provenance(const RoutePlan& plan, const chaos::VariedMove& m) {
  if (!m.source) return "-";
  const auto& in = plan.variation.inputs;
  std::string name = m.source->route < static_cast<int>(in.size()) ? in[m.source->route].name : "?";
  return name + " #" + std::to_string(m.source->move + 1);
}

std::string MoveText(const chaos::VariedMove& m) {
  std::string t = m.source ? m.text : "________ (fill in)";
  for (const auto& n : m.notes) {
    if (n.rfind("(blank", 0) == 0) continue;
    t += " " + n;
  }
  return t;
}

// Display width in code points (UTF-8 continuation bytes do not count).
size_t Width(const std::string& s) {
  size_t w = 0;
  for (unsigned char c : s) w += (c & 0xC0) != 0x80;
  return w;
}

std::string Pad(const std::string& s, size_t w) {
  size_t n = Width(s);
  return n >= w ? s : s + std::string(w - n, ' ');
}

int ChangedCount(const RoutePlan& plan) {
  int c = 0;
  for (const auto& m : plan.variation.moves) c += m.changed;
  return c;
}

std::string InputsLine(const RoutePlan& plan) {
  std::string s;
  for (size_t i = 0; i < plan.variation.inputs.size(); ++i) {
    if (i) s += ", ";
    s += "\"" + plan.variation.inputs[i].name + "\" (" +
         std::to_string(plan.variation.inputs[i].route.moves.size()) + " moves)";
  }
  return s;
}

std::string SuggestionText(const InsertedMove& m) {
  std::string s = m.hand.empty() ? "" : m.hand + " ";
  return s + (m.description.empty() ? m.symbol : m.description);
}

}  // namespace

std::string RenderText(const RoutePlan& plan) {
  const auto& moves = plan.variation.moves;
  size_t w = 4;
  for (const auto& m : moves) w = std::max(w, Width(MoveText(m)));
  w = std::min<size_t>(w, 60);
  std::string out;
  out.reserve(512 + moves.size() * (w + 40));
  out += "CHAOTIC ROUTE PLAN\n";
  out += "Variation of " + InputsLine(plan) + "\n";
  out += std::to_string(moves.size()) + " moves, " + std::to_string(ChangedCount(plan)) +
         " changed\n\n";
  out += "  #  hand  " + Pad("move", w) + "  status   from\n";
  size_t next = 0;
  for (size_t j = 0; j < moves.size(); ++j) {
    const auto& m = moves[j];
    char num[16];
    std::snprintf(num, sizeof num, "%3zu", j + 1);
    out += std::string(num) + "  " + HandLetter(m.hand) + "     " + Pad(MoveText(m), w) +
           (m.changed ? "  changed  " : "  kept     ") + Provenance(plan, m) + "\n";
    while (next < plan.smoothing.size() && plan.smoothing[next].after == static_cast<int>(j)) {
      const Suggestion& s = plan.smoothing[next++];
      for (size_t i = 0; i < s.moves.size(); ++i) {
        std::string ins = "insert: " + SuggestionText(s.moves[i]);
        out += "  +  " + (i == 0 ? Pad(ins, w + 6) : ins);
        if (i == 0) {
          out += "  (smoothing saves " + FormatNumber(std::round(s.bits_saved() * 100) / 100) +
                 " bits)";
        }
        out += "\n";
      }
    }
  }
  out += "\nchanged: the move differs from the input's move at that position; from: the input "
         "route and move number it comes from.\n";
  if (!plan.smoothing_model.empty()) {
    out += "+ smoothing suggestions from model " + plan.smoothing_model + ".\n";
  }
  out += "\nParameters\n";
  for (const auto& l : ParameterLines(plan.variation.params)) out += "  " + l + "\n";
  out += "  reproduce: strangebeta vary " + ReproduceOptions(plan.variation.params) + " ROUTES...\n";
  return out;
}

static std::string MdEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '|' || c == '*' || c == '_' || c == '`' || c == '\\' || c == '[' || c == ']' ||
        c == '<' || c == '>') {
      out += '\\';
    }
    out += c;
  }
  return out;
}

std::string RenderMarkdown(const RoutePlan& plan) {
  const auto& moves = plan.variation.moves;
  std::string out = "# Chaotic route plan\n\n";
  out += "Variation of " + MdEscape(InputsLine(plan)) + ": " + std::to_string(moves.size()) +
         " moves, " + std::to_string(ChangedCount(plan)) + " changed.\n\n";
  out += "| # | hand | move | changed | from |\n|---:|:---:|---|:---:|---|\n";
  size_t next = 0;
  for (size_t j = 0; j < moves.size(); ++j) {
    const auto& m = moves[j];
    std::string text = MdEscape(MoveText(m));
    if (m.changed) text = "**" + text + "**";
    out += "| " + std::to_string(j + 1) + " | " + HandLetter(m.hand) + " | " + text + " | " +
           (m.changed ? "yes" : "") + " | " + MdEscape(Provenance(plan, m)) + " |\n";
    while (next < plan.smoothing.size() && plan.smoothing[next].after == static_cast<int>(j)) {
      const Suggestion& s = plan.smoothing[next++];
      for (const auto& ins : s.moves) {
        out += "| + | " + ins.hand + " | *insert: " + MdEscape(ins.description.empty() ? ins.symbol : ins.description) +
               "* | smoothing | saves " + FormatNumber(std::round(s.bits_saved() * 100) / 100) +
               " bits |\n";
      }
    }
  }
  out += "\n## Parameters\n\n";
  for (const auto& l : ParameterLines(plan.variation.params)) out += "- " + MdEscape(l) + "\n";
  if (!plan.smoothing_model.empty()) out += "- smoothing model " + MdEscape(plan.smoothing_model) + "\n";
  out += "\nReproduce: `strangebeta vary " + ReproduceOptions(plan.variation.params) +
         " ROUTES...`\n";
  return out;
}

// ---------------------------------------------------------------------------
// JSON and SVG.

json ToJson(const RoutePlan& plan) {
  json j;
  j["parameters"] = ParamsToJson(plan.variation.params);
  json inputs = json::array();
  for (const auto& in : plan.variation.inputs) {
    inputs.push_back({{"name", in.name}, {"moves", in.route.moves.size()}});
  }
  j["inputs"] = inputs;
  json moves = json::array();
  for (const auto& m : plan.variation.moves) {
    json jm;
    jm["hand"] = HandLetter(m.hand);
    jm["text"] = m.text;
    if (m.source) {
      jm["source"] = {{"route", m.source->route}, {"move", m.source->move}};
    } else {
      jm["source"] = nullptr;
    }
    jm["changed"] = m.changed;
    jm["notes"] = m.notes;
    moves.push_back(jm);
  }
  j["moves"] = moves;
  j["reference"] = plan.variation.reference;
  j["variation"] = plan.variation.variation;
  if (!plan.smoothing_model.empty()) {
    json sm = json::array();
    for (const auto& s : plan.smoothing) {
      json ins = json::array();
      for (const auto& m : s.moves) {
        ins.push_back({{"hand", m.hand}, {"symbol", m.symbol}, {"description", m.description}});
      }
      sm.push_back({{"after", s.after},
                    {"insert", ins},
                    {"bits_before", s.bits_before},
                    {"bits_after", s.bits_after},
                    {"bits_saved", s.bits_saved()}});
    }
    j["smoothing"] = {{"model", plan.smoothing_model}, {"suggestions", sm}};
  }
  return j;
}

namespace {

// JSON string literal (quotes included). Input is valid UTF-8 (CRDL checks
// it), so only quotes, backslashes and control characters need escapes.
void AppendJsonString(std::string* out, std::string_view s) {
  out->push_back('"');
  for (char c : s) {
    switch (c) {
      case '"': *out += "\\\""; break;
      case '\\': *out += "\\\\"; break;
      case '\n': *out += "\\n"; break;
      case '\r': *out += "\\r"; break;
      case '\t': *out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          *out += buf;
        } else {
          out->push_back(c);
        }
    }
  }
  out->push_back('"');
}

void AppendPoints(std::string* out, const char* key, const std::vector<chaos::State>& pts) {
  *out += "  \"";
  *out += key;
  *out += "\": [";
  for (size_t i = 0; i < pts.size(); ++i) {
    *out += i ? ",\n    [" : "\n    [";
    *out += FormatNumber(pts[i][0]) + "," + FormatNumber(pts[i][1]) + "," + FormatNumber(pts[i][2]);
    *out += "]";
  }
  *out += pts.empty() ? "]" : "\n  ]";
}

}  // namespace

std::string RenderJson(const RoutePlan& plan) {
  // Written directly rather than through a document tree: one line per move
  // and per trajectory point keeps million-move plans fast and readable.
  const auto& v = plan.variation;
  std::string out;
  out.reserve(256 + v.moves.size() * 150);
  out += "{\n  \"parameters\": " + ParamsToJson(v.params).dump() + ",\n  \"inputs\": [";
  for (size_t i = 0; i < v.inputs.size(); ++i) {
    out += i ? ", {\"name\": " : "{\"name\": ";
    AppendJsonString(&out, v.inputs[i].name);
    out += ", \"moves\": " + std::to_string(v.inputs[i].route.moves.size()) + "}";
  }
  out += "],\n  \"moves\": [";
  for (size_t j = 0; j < v.moves.size(); ++j) {
    const auto& m = v.moves[j];
    out += j ? ",\n    {\"hand\": \"" : "\n    {\"hand\": \"";
    out += HandLetter(m.hand);
    out += "\", \"text\": ";
    AppendJsonString(&out, m.text);
    if (m.source) {
      out += ", \"source\": {\"route\": " + std::to_string(m.source->route) +
             ", \"move\": " + std::to_string(m.source->move) + "}";
    } else {
      out += ", \"source\": null";
    }
    out += m.changed ? ", \"changed\": true, \"notes\": [" : ", \"changed\": false, \"notes\": [";
    for (size_t k = 0; k < m.notes.size(); ++k) {
      if (k) out += ", ";
      AppendJsonString(&out, m.notes[k]);
    }
    out += "]}";
  }
  out += v.moves.empty() ? "],\n" : "\n  ],\n";
  AppendPoints(&out, "reference", v.reference);
  out += ",\n";
  AppendPoints(&out, "variation", v.variation);
  json full = ToJson(RoutePlan{chaos::Variation{}, plan.smoothing, plan.smoothing_model});
  if (full.contains("smoothing")) out += ",\n  \"smoothing\": " + full["smoothing"].dump();
  out += "\n}\n";
  return out;
}

bool SmoothingFromJson(const json& j, RoutePlan* plan) {
  if (!j.is_object() || !j.contains("smoothing")) return false;
  const json& sm = j["smoothing"];
  if (!sm.is_object() || !sm.contains("model") || !sm["model"].is_string() ||
      !sm.contains("suggestions") || !sm["suggestions"].is_array()) {
    return false;
  }
  std::vector<Suggestion> out;
  for (const json& s : sm["suggestions"]) {
    if (!s.is_object() || !s.value("after", json()).is_number_integer() ||
        !s.value("bits_before", json()).is_number() || !s.value("bits_after", json()).is_number() ||
        !s.value("insert", json()).is_array()) {
      return false;
    }
    Suggestion sug;
    sug.after = s["after"].get<int>();
    sug.bits_before = s["bits_before"].get<double>();
    sug.bits_after = s["bits_after"].get<double>();
    for (const json& m : s["insert"]) {
      if (!m.is_object()) return false;
      InsertedMove im;
      for (auto [field, dst] : {std::pair{"hand", &im.hand}, std::pair{"symbol", &im.symbol},
                                std::pair{"description", &im.description}}) {
        if (!m.value(field, json()).is_string()) return false;
        *dst = m[field].get<std::string>();
      }
      sug.moves.push_back(std::move(im));
    }
    out.push_back(std::move(sug));
  }
  plan->smoothing = std::move(out);
  plan->smoothing_model = sm["model"].get<std::string>();
  return true;
}

namespace {
cairo_status_t AppendToString(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}
}  // namespace

std::string RenderTrajectorySvg(const RoutePlan& plan) {
  std::string out;
  const double w = 640, h = 480;
  cairo_surface_t* surface = cairo_svg_surface_create_for_stream(AppendToString, &out, w, h);
  cairo_svg_surface_restrict_to_version(surface, CAIRO_SVG_VERSION_1_1);
  cairo_svg_surface_set_document_unit(surface, CAIRO_SVG_UNIT_PX);
  cairo_t* cr = cairo_create(surface);
  DrawTrajectory(cr, plan, w, h);
  cairo_destroy(cr);
  cairo_surface_finish(surface);
  cairo_surface_destroy(surface);
  // Cairo numbers surfaces process-wide ("surface1", "surface6", ...): pin the
  // id so the same plan always gives the same bytes.
  const std::string key = "<g id=\"surface";
  if (size_t pos = out.find(key); pos != std::string::npos) {
    size_t digits = pos + key.size(), end = digits;
    while (end < out.size() && out[end] >= '0' && out[end] <= '9') ++end;
    out.replace(digits, end - digits, "1");
  }
  return out;
}

std::string Render(const RoutePlan& plan, Format format) {
  switch (format) {
    case Format::kText: return RenderText(plan);
    case Format::kMarkdown: return RenderMarkdown(plan);
    case Format::kJson: return RenderJson(plan);
    case Format::kSvg: return RenderTrajectorySvg(plan);
  }
  return "";
}

}  // namespace sb::plan
