#include "plan/plan.h"

#include <cairo-svg.h>
#include <cairo.h>

#include <array>
#include <cstdio>

#include <cmath>
#include <nlohmann/json.hpp>

#include "base/number.h"
#include "base/text.h"
#include "plan/draw.h"

namespace sb::plan {

using chaos::VaryParams;
using nlohmann::json;

namespace {
std::string FormatNumber(double v) { return FormatDouble(v); }
}  // namespace

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
  std::string t = m.source || m.added ? m.text : "________ (fill in)";
  if (m.crux) t += " (crux)";
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
    char num[24];
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

namespace {

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

void AppendMoves(std::string* out, const chaos::Variation& v) {
  *out += "[";
  for (size_t j = 0; j < v.moves.size(); ++j) {
    const auto& m = v.moves[j];
    *out += j ? ",\n    {\"hand\": \"" : "\n    {\"hand\": \"";
    *out += HandLetter(m.hand);
    *out += "\", \"text\": ";
    AppendJsonString(out, m.text);
    if (m.source) {
      *out += ", \"source\": {\"route\": " + std::to_string(m.source->route) +
              ", \"move\": " + std::to_string(m.source->move) + "}";
    } else {
      *out += ", \"source\": null";
    }
    *out += m.changed ? ", \"changed\": true" : ", \"changed\": false";
    if (m.added) *out += ", \"added\": true";
    *out += m.crux ? ", \"crux\": true, \"notes\": [" : ", \"crux\": false, \"notes\": [";
    for (size_t k = 0; k < m.notes.size(); ++k) {
      if (k) *out += ", ";
      AppendJsonString(out, m.notes[k]);
    }
    *out += "]}";
  }
  *out += v.moves.empty() ? "]" : "\n  ]";
}

// A JSON number; non-finite values (never produced by the engine) as null.
std::string JsonNumber(double v) { return std::isfinite(v) ? FormatNumber(v) : "null"; }

void AppendSmoothing(std::string* out, const RoutePlan& plan) {
  *out += "{\"model\": ";
  AppendJsonString(out, plan.smoothing_model);
  *out += ", \"suggestions\": [";
  for (size_t i = 0; i < plan.smoothing.size(); ++i) {
    const Suggestion& s = plan.smoothing[i];
    *out += i ? ", {\"after\": " : "{\"after\": ";
    *out += std::to_string(s.after) + ", \"insert\": [";
    for (size_t k = 0; k < s.moves.size(); ++k) {
      *out += k ? ", {\"hand\": " : "{\"hand\": ";
      AppendJsonString(out, s.moves[k].hand);
      *out += ", \"symbol\": ";
      AppendJsonString(out, s.moves[k].symbol);
      *out += ", \"description\": ";
      AppendJsonString(out, s.moves[k].description);
      *out += "}";
    }
    *out += "], \"bits_before\": " + JsonNumber(s.bits_before) +
            ", \"bits_after\": " + JsonNumber(s.bits_after) +
            ", \"bits_saved\": " + JsonNumber(s.bits_saved()) + "}";
  }
  *out += "]}";
}

}  // namespace

std::string RenderMovesJson(const RoutePlan& plan) {
  std::string out;
  AppendMoves(&out, plan.variation);
  return out;
}

std::string RenderJson(const RoutePlan& plan) {
  // Written directly rather than through a document tree: one line per move
  // and per trajectory point keeps million-move plans fast and readable.
  const auto& v = plan.variation;
  std::string out;
  out.reserve(256 + v.moves.size() * 150);
  out += "{\n  \"parameters\": " + chaos::ParamsToJson(v.params) + ",\n  \"inputs\": [";
  for (size_t i = 0; i < v.inputs.size(); ++i) {
    out += i ? ", {\"name\": " : "{\"name\": ";
    AppendJsonString(&out, v.inputs[i].name);
    out += ", \"moves\": " + std::to_string(v.inputs[i].route.moves.size()) + "}";
  }
  out += "],\n  \"moves\": ";
  AppendMoves(&out, v);
  out += ",\n";
  AppendPoints(&out, "reference", v.reference);
  out += ",\n";
  AppendPoints(&out, "variation", v.variation);
  if (!plan.smoothing_model.empty()) {
    out += ",\n  \"smoothing\": ";
    AppendSmoothing(&out, plan);
  }
  out += "\n}\n";
  return out;
}

bool SmoothingFromJson(std::string_view plan_json, RoutePlan* plan) {
  json j = json::parse(plan_json, nullptr, /*allow_exceptions=*/false);
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
