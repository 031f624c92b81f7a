#include "plan/plan.h"

#include <cairo-svg.h>
#include <cairo.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>

#include "base/number.h"
#include "base/text.h"
#include "chaos/tokens.h"
#include "plan/draw.h"

namespace sb::plan {

using chaos::VaryParams;
using nlohmann::json;

namespace {
std::string FormatNumber(double v) { return FormatDouble(v); }
// A figure for people: rounded to 0.01, shortest form.
std::string Hundredths(double v) { return FormatNumber(std::round(v * 100) / 100); }
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

const char* SmoothingMethodName(SmoothingMethod m) {
  return m == SmoothingMethod::kAStar ? "astar" : "vomm";
}

Result<SmoothingMethod> ParseSmoothingMethod(std::string_view s) {
  std::string l = ToLower(s);
  if (l == "vomm") return SmoothingMethod::kVomm;
  if (l == "astar") return SmoothingMethod::kAStar;
  return Status::InvalidInput("unknown smoothing method \"" + std::string(s) +
                              "\" (vomm or astar)");
}

std::string Suggestion::CostNote() const {
  if (method == SmoothingMethod::kVomm) return "saves " + Hundredths(bits_saved()) + " bits";
  std::string s = "path " + Hundredths(bits_after) + " bits";
  return direct_seen ? s + ", direct " + Hundredths(bits_before) + " bits"
                     : s + "; the direct transition never occurs in the graph's data";
}

bool RoutePlan::tokens() const { return chaos::AreTokens(variation.inputs); }

SearchReport ReportOf(const chaos::SearchResult& r) {
  SearchReport s;
  s.requested_ic = r.requested_ic;
  s.used_ic = r.used_ic;
  s.offset = r.offset;
  s.distance = r.distance;
  s.evaluated = r.evaluated;
  s.hands_swapped = r.hands_swapped;
  s.constraints = r.outcomes;
  return s;
}

// ---------------------------------------------------------------------------
// The setter's parameters (one codec: plan JSON, stored variations, the API).

std::string ParametersJson(const VaryParams& p, const SetterOptions& o) {
  json j = json::parse(chaos::ParamsToJson(p));
  const chaos::Constraints& c = o.constraints;
  const chaos::Constraints dc;
  const chaos::SearchGrid dg;
  if (c.keep_start) j["keep_start"] = true;
  if (c.keep_finish) j["keep_finish"] = true;
  if (c.crux_window) j["crux_window"] = {c.crux_window->begin, c.crux_window->end};
  if (c.alternate_hands) j["alternate_hands"] = true;
  if (o.match_grammar) j["match"] = "grammar";
  if (c.target_effect) j["target_effect"] = *c.target_effect;
  if (c.target_change) j["target_change"] = *c.target_change;
  if (c.effect_tolerance != dc.effect_tolerance) j["effect_tolerance"] = c.effect_tolerance;
  if (c.change_tolerance != dc.change_tolerance) j["change_tolerance"] = c.change_tolerance;
  if (o.grid.spacing != dg.spacing) j["search_spacing"] = o.grid.spacing;
  if (o.grid.radius != dg.radius) j["search_radius"] = o.grid.radius;
  if (o.grid.plane != dg.plane) j["search_plane"] = chaos::SearchPlaneName(o.grid.plane);
  if (o.smooth_method != SmoothingMethod::kVomm) {
    j["smooth_method"] = SmoothingMethodName(o.smooth_method);
  }
  if (o.drop_inner_finishes) j["drop_inner_finishes"] = true;
  if (o.drop_inner_starts) j["drop_inner_starts"] = true;
  return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

namespace {

Status FieldError(const char* field, const std::string& what) {
  return Status::InvalidInput(std::string(field) + ": " + what);
}

Status GetBool(const json& j, const char* field, bool* out) {
  if (!j.contains(field)) return Status::Ok();
  if (!j[field].is_boolean()) return FieldError(field, "expected true or false");
  *out = j[field].get<bool>();
  return Status::Ok();
}

// A finite number >= 0 (targets, tolerances, the grid spacing).
Status GetNonNegative(const json& j, const char* field, double* out) {
  if (!j[field].is_number()) return FieldError(field, "expected a number");
  double v = j[field].get<double>();
  if (!std::isfinite(v) || v < 0) return FieldError(field, "must be a finite number >= 0");
  *out = v;
  return Status::Ok();
}

Status GetOptionalTarget(const json& j, const char* field, std::optional<double>* out) {
  if (!j.contains(field) || j[field].is_null()) return Status::Ok();
  double v = 0;
  SB_RETURN_IF_ERROR(GetNonNegative(j, field, &v));
  *out = v;
  return Status::Ok();
}

Status GetCruxWindow(const json& j, std::optional<chaos::CruxWindow>* out) {
  const char* field = "crux_window";
  if (!j.contains(field) || j[field].is_null()) return Status::Ok();
  const json& v = j[field];
  const std::string want = "expected [a, b] with 0 <= a <= b <= 1 (fractions of the length)";
  chaos::CruxWindow w;
  if (v.is_string()) {
    auto parsed = chaos::ParseCruxWindow(v.get<std::string>());
    if (!parsed.ok()) return FieldError(field, parsed.status().message());
    w = *parsed;
  } else if (v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number()) {
    w = {v[0].get<double>(), v[1].get<double>()};
  } else {
    return FieldError(field, want);
  }
  if (!(std::isfinite(w.begin) && std::isfinite(w.end) && w.begin >= 0 && w.end <= 1 &&
        w.begin <= w.end)) {
    return FieldError(field, want);
  }
  *out = w;
  return Status::Ok();
}

}  // namespace

Result<SetterOptions> SetterOptionsFromJson(std::string_view json_text) {
  json j = json::parse(json_text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return Status::InvalidInput("parameters: malformed JSON");
  if (!j.is_object()) return Status::InvalidInput("parameters: expected an object");
  SetterOptions o;
  chaos::Constraints& c = o.constraints;
  SB_RETURN_IF_ERROR(GetBool(j, "keep_start", &c.keep_start));
  SB_RETURN_IF_ERROR(GetBool(j, "keep_finish", &c.keep_finish));
  SB_RETURN_IF_ERROR(GetCruxWindow(j, &c.crux_window));
  SB_RETURN_IF_ERROR(GetBool(j, "alternate_hands", &c.alternate_hands));
  SB_RETURN_IF_ERROR(GetBool(j, "drop_inner_finishes", &o.drop_inner_finishes));
  SB_RETURN_IF_ERROR(GetBool(j, "drop_inner_starts", &o.drop_inner_starts));
  if (j.contains("match")) {
    const json& m = j["match"];
    if (!m.is_string() || (m != "text" && m != "grammar")) {
      return FieldError("match", "expected \"text\" or \"grammar\"");
    }
    o.match_grammar = m == "grammar";
  }
  SB_RETURN_IF_ERROR(GetOptionalTarget(j, "target_effect", &c.target_effect));
  SB_RETURN_IF_ERROR(GetOptionalTarget(j, "target_change", &c.target_change));
  if (j.contains("effect_tolerance")) {
    SB_RETURN_IF_ERROR(GetNonNegative(j, "effect_tolerance", &c.effect_tolerance));
  }
  if (j.contains("change_tolerance")) {
    SB_RETURN_IF_ERROR(GetNonNegative(j, "change_tolerance", &c.change_tolerance));
  }
  if (j.contains("search_spacing")) {
    SB_RETURN_IF_ERROR(GetNonNegative(j, "search_spacing", &o.grid.spacing));
    if (o.grid.spacing <= 0) return FieldError("search_spacing", "must be a number > 0");
  }
  if (j.contains("search_radius")) {
    const json& r = j["search_radius"];
    if (!r.is_number_integer() || r.get<int64_t>() < 0 || r.get<int64_t>() > std::numeric_limits<int>::max()) {
      return FieldError("search_radius", "expected a whole number of grid steps >= 0");
    }
    o.grid.radius = static_cast<int>(r.get<int64_t>());
  }
  if (j.contains("search_plane")) {
    if (!j["search_plane"].is_string()) {
      return FieldError("search_plane", "expected \"xy\", \"xz\", \"yz\" or \"cube\"");
    }
    auto plane = chaos::ParseSearchPlane(j["search_plane"].get<std::string>());
    if (!plane.ok()) return FieldError("search_plane", plane.status().message());
    o.grid.plane = *plane;
  }
  if (Status s = o.grid.Validate(); !s.ok()) {
    // The grid names its fields as options ("search-radius: ..."): the JSON
    // field is the same name with an underscore.
    std::string m = s.message();
    if (size_t dash = m.find('-'); dash != std::string::npos && dash < m.find(':')) m[dash] = '_';
    return Status::InvalidInput(m);
  }
  if (j.contains("smooth_method")) {
    if (!j["smooth_method"].is_string()) {
      return FieldError("smooth_method", "expected \"vomm\" or \"astar\"");
    }
    auto m = ParseSmoothingMethod(j["smooth_method"].get<std::string>());
    if (!m.ok()) return FieldError("smooth_method", "expected \"vomm\" or \"astar\"");
    o.smooth_method = *m;
  }
  return o;
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

std::string ReproduceOptions(const VaryParams& p, const SetterOptions& o) {
  std::string s = ReproduceOptions(p);
  const chaos::Constraints& c = o.constraints;
  const chaos::Constraints dc;
  const chaos::SearchGrid dg;
  if (c.keep_start) s += " --keep-start";
  if (c.keep_finish) s += " --keep-finish";
  if (c.crux_window) {
    s += " --crux-window " + FormatNumber(c.crux_window->begin) + "," +
         FormatNumber(c.crux_window->end);
  }
  if (c.alternate_hands) s += " --alternate-hands";
  if (o.drop_inner_finishes) s += " --drop-inner-finishes";
  if (o.drop_inner_starts) s += " --drop-inner-starts";
  if (o.match_grammar) s += " --match grammar";
  if (c.target_effect) s += " --target-effect " + FormatNumber(*c.target_effect);
  if (c.target_change) s += " --target-change " + FormatNumber(*c.target_change);
  if (c.effect_tolerance != dc.effect_tolerance) {
    s += " --effect-tolerance " + FormatNumber(c.effect_tolerance);
  }
  if (c.change_tolerance != dc.change_tolerance) {
    s += " --change-tolerance " + FormatNumber(c.change_tolerance);
  }
  if (o.grid.spacing != dg.spacing) s += " --search-spacing " + FormatNumber(o.grid.spacing);
  if (o.grid.radius != dg.radius) s += " --search-radius " + std::to_string(o.grid.radius);
  if (o.grid.plane != dg.plane) {
    s += std::string(" --search-plane ") + chaos::SearchPlaneName(o.grid.plane);
  }
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

// What a plan calls its elements: moves of routes, positions of sequences.
struct Words {
  const char* title;     // "CHAOTIC ROUTE PLAN"
  const char* md_title;  // "Chaotic route plan"
  const char* unit;      // "move" / "position"
  const char* units;     // "moves" / "positions"
  const char* what;      // "move" / "token": the column of the element's text
  const char* input;     // "input route" / "input sequence"
};
Words WordsOf(const RoutePlan& plan) {
  if (plan.tokens()) {
    return {"CHAOTIC SEQUENCE PLAN", "Chaotic sequence plan", "position", "positions", "token",
            "input sequence"};
  }
  return {"CHAOTIC ROUTE PLAN", "Chaotic route plan", "move", "moves", "move", "input route"};
}

std::string Provenance(const RoutePlan& plan, const chaos::VariedMove& m) {
  if (!m.source) return "-";
  const auto& in = plan.variation.inputs;
  std::string name = m.source->route < static_cast<int>(in.size()) ? in[m.source->route].name : "?";
  const int first = m.source->route < static_cast<int>(in.size()) ? in[m.source->route].first_move : 0;
  return name + " #" + std::to_string(first + m.source->move + 1);
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

// The one change count (issue 33): moves new against the inputs.
int NewCount(const RoutePlan& plan) {
  return NewMoveCount(plan.variation.moves, plan.variation.inputs).new_moves;
}

std::string InputsLine(const RoutePlan& plan) {
  const Words w = WordsOf(plan);
  std::string s;
  for (size_t i = 0; i < plan.variation.inputs.size(); ++i) {
    if (i) s += ", ";
    s += "\"" + plan.variation.inputs[i].name + "\" (" +
         std::to_string(plan.variation.inputs[i].route.moves.size()) + " " + w.units;
    if (plan.grades && i < plan.grades->inputs.size() && !plan.grades->inputs[i].empty()) {
      s += ", grade " + plan.grades->inputs[i];
    }
    s += ")";
  }
  return s;
}

std::string SuggestionText(const InsertedMove& m) {
  std::string s = m.hand.empty() ? "" : m.hand + " ";
  return s + (m.description.empty() ? m.symbol : m.description);
}

// "Estimated grade: 5.10 (80% interval 5.8 to 5.11; roped, from the moves)".
std::string GradeLine(const PlanGrades& g) {
  if (g.estimate.empty()) return "Estimated grade: none (" + g.note + ")";
  std::string s = "Estimated grade: " + g.estimate + " (" +
                  std::to_string(static_cast<int>(std::lround(g.level * 100))) + "% interval " +
                  g.low + " to " + g.high + "; " + g.discipline + ", from the moves)";
  return g.note.empty() ? s : s + "; " + g.note;
}

std::string SearchLine(const SearchReport& r) {
  std::string s = "IC search: IC " + FormatTriple(r.used_ic) + " used, " +
                  FormatDouble(r.distance, 4) + " from " + FormatTriple(r.requested_ic) +
                  " asked for (" + std::to_string(r.evaluated) + " ICs evaluated";
  if (r.hands_swapped > 0) {
    s += ", " + std::to_string(r.hands_swapped) + " hand" + (r.hands_swapped > 1 ? "s" : "") +
         " swapped";
  }
  return s + ")";
}

std::string ConstraintLine(const chaos::ConstraintOutcome& c) {
  return std::string(chaos::ConstraintName(c.constraint)) + ": " + (c.held ? "held" : "NOT held") +
         " (" + c.detail + ")";
}

std::string WarningLine(const Warning& w) {
  return std::string(WarningKindName(w.kind)) + ": " + w.message;
}

bool HasEstimates(const RoutePlan& plan) {
  return plan.profile && !plan.profile->difficulty.empty() &&
         plan.profile->difficulty.size() == plan.variation.moves.size();
}

bool InHardest(const RoutePlan& plan, size_t j) {
  return plan.profile && plan.profile->hardest_first >= 0 &&
         static_cast<int>(j) >= plan.profile->hardest_first &&
         static_cast<int>(j) <= plan.profile->hardest_last;
}

// "moves 16-21 (mean estimate 0.31)".
std::string HardestText(const RoutePlan& plan) {
  const DifficultyProfile& p = *plan.profile;
  std::string span = p.hardest_first == p.hardest_last
                         ? "move " + std::to_string(p.hardest_first + 1)
                         : "moves " + std::to_string(p.hardest_first + 1) + "-" +
                               std::to_string(p.hardest_last + 1);
  char mean[32];
  std::snprintf(mean, sizeof mean, "%.2f", p.hardest_mean);
  return span + " (mean estimate " + mean + ")";
}

std::string Estimate2(double d) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%.2f", d);
  return buf;
}

// The annotation lines shown above a plan's table (text: as is; Markdown
// turns them into sections).
std::vector<std::string> AnnotationLines(const RoutePlan& plan) {
  std::vector<std::string> out;
  if (plan.grades) out.push_back(GradeLine(*plan.grades));
  if (plan.search) {
    out.push_back(SearchLine(*plan.search));
    for (const auto& c : plan.search->constraints) out.push_back("  " + ConstraintLine(c));
  }
  if (plan.warnings) {
    if (plan.warnings->warnings.empty()) {
      out.push_back("Warnings: none");
    } else {
      out.push_back("Warnings:");
      for (const Warning& w : plan.warnings->warnings) out.push_back("  " + WarningLine(w));
    }
    out.push_back("Summary: " + plan.warnings->summary.message);
  }
  return out;
}

}  // namespace

std::vector<std::string> PlanNotes(const RoutePlan& plan) {
  std::vector<std::string> out = AnnotationLines(plan);
  if (plan.profile && plan.profile->hardest_first >= 0) {
    out.push_back("Hardest stretch: " + HardestText(plan));
  }
  return out;
}

std::string RenderText(const RoutePlan& plan) {
  const auto& moves = plan.variation.moves;
  const Words words = WordsOf(plan);
  const bool tokens = plan.tokens();
  const bool estimates = HasEstimates(plan);
  size_t w = 4;
  for (const auto& m : moves) w = std::max(w, Width(MoveText(m)));
  w = std::min<size_t>(w, 60);
  std::string out;
  out.reserve(1024 + moves.size() * (w + 48));
  out += std::string(words.title) + "\n";
  out += "Variation of " + InputsLine(plan) + "\n";
  out += std::to_string(moves.size()) + " " + words.units + ", " +
         std::to_string(NewCount(plan)) + " new against the inputs\n";
  for (const std::string& l : AnnotationLines(plan)) out += l + "\n";
  out += "\n";
  out += tokens ? "  pos  " + Pad(words.what, w) : "  #  hand  " + Pad(words.what, w);
  out += estimates ? "  diff   status   from\n" : "  status   from\n";
  size_t next = 0;
  for (size_t j = 0; j < moves.size(); ++j) {
    const auto& m = moves[j];
    char num[24];
    std::snprintf(num, sizeof num, tokens ? "%5zu" : "%3zu", j + 1);
    out += std::string(num) + "  ";
    if (!tokens) out += std::string(HandLetter(m.hand)) + "     ";
    out += Pad(MoveText(m), w);
    if (estimates) {
      out += "  " + Estimate2(plan.profile->difficulty[j]) + (InHardest(plan, j) ? "*" : " ");
    }
    out += (m.changed ? "  changed  " : "  kept     ") + Provenance(plan, m) + "\n";
    while (next < plan.smoothing.size() && plan.smoothing[next].after == static_cast<int>(j)) {
      const Suggestion& s = plan.smoothing[next++];
      for (size_t i = 0; i < s.moves.size(); ++i) {
        std::string ins = "insert: " + SuggestionText(s.moves[i]);
        out += (tokens ? "    +  " : "  +  ") + (i == 0 ? Pad(ins, w + 6) : ins);
        if (i == 0) out += "  (smoothing " + s.CostNote() + ")";
        out += "\n";
      }
    }
  }
  out += std::string("\nchanged: the ") + words.unit + " differs from the input's " + words.unit +
         " at that position; from: the " + words.input + " and " + words.unit +
         " number it comes from.\n";
  if (estimates) {
    out += "diff: the move's difficulty estimate (0 to 1, how likely climbers flag it as a crux)";
    if (plan.profile->hardest_first >= 0) out += "; * the hardest stretch, " + HardestText(plan);
    out += ".\n";
  }
  if (!plan.smoothing_model.empty()) {
    out += "+ smoothing suggestions (" +
           std::string(SmoothingMethodName(plan.setter.smooth_method)) + ") from " +
           plan.smoothing_model + ".\n";
  }
  out += "\nParameters\n";
  for (const auto& l : ParameterLines(plan.variation.params)) out += "  " + l + "\n";
  out += std::string("  reproduce: strangebeta vary ") + (tokens ? "--tokens FILE... " : "") +
         ReproduceOptions(plan.variation.params, plan.setter) + (tokens ? "\n" : " ROUTES...\n");
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
  const Words words = WordsOf(plan);
  const bool tokens = plan.tokens();
  const bool estimates = HasEstimates(plan);
  std::string out = std::string("# ") + words.md_title + "\n\n";
  out += "Variation of " + MdEscape(InputsLine(plan)) + ": " + std::to_string(moves.size()) + " " +
         words.units + ", " + std::to_string(NewCount(plan)) + " new against the inputs.\n\n";
  if (plan.grades) out += MdEscape(GradeLine(*plan.grades)) + ".\n\n";
  if (plan.search) {
    out += "## IC search\n\n" + MdEscape(SearchLine(*plan.search)) + ".\n\n";
    for (const auto& c : plan.search->constraints) out += "- " + MdEscape(ConstraintLine(c)) + "\n";
    out += "\n";
  }
  if (plan.warnings) {
    out += "## Warnings\n\n";
    if (plan.warnings->warnings.empty()) out += "None.\n";
    for (const Warning& w : plan.warnings->warnings) out += "- " + MdEscape(WarningLine(w)) + "\n";
    out += "\nSummary: " + MdEscape(plan.warnings->summary.message) + ".\n\n";
  }
  if (plan.search || plan.warnings || plan.grades) out += std::string("## ") + words.md_title + "\n\n";
  out += tokens ? "| # | token |" : "| # | hand | move |";
  out += estimates ? " difficulty | changed | from |\n" : " changed | from |\n";
  out += tokens ? "|---:|---|" : "|---:|:---:|---|";
  out += estimates ? "---:|:---:|---|\n" : ":---:|---|\n";
  size_t next = 0;
  for (size_t j = 0; j < moves.size(); ++j) {
    const auto& m = moves[j];
    std::string text = MdEscape(MoveText(m));
    if (m.changed) text = "**" + text + "**";
    out += "| " + std::to_string(j + 1) + " | ";
    if (!tokens) out += std::string(HandLetter(m.hand)) + " | ";
    out += text + " | ";
    if (estimates) {
      out += Estimate2(plan.profile->difficulty[j]) + (InHardest(plan, j) ? " \\*" : "") + " | ";
    }
    out += std::string(m.changed ? "yes" : "") + " | " + MdEscape(Provenance(plan, m)) + " |\n";
    while (next < plan.smoothing.size() && plan.smoothing[next].after == static_cast<int>(j)) {
      const Suggestion& s = plan.smoothing[next++];
      for (const auto& ins : s.moves) {
        out += std::string("| + | ") + (tokens ? "" : ins.hand + " | ") + "*insert: " +
               MdEscape(ins.description.empty() ? ins.symbol : ins.description) + "* | " +
               (estimates ? " | " : "") + "smoothing | " + MdEscape(s.CostNote()) + " |\n";
      }
    }
  }
  if (estimates && plan.profile->hardest_first >= 0) {
    out += "\nDifficulty: the move's estimate (0 to 1, how likely climbers flag it as a crux); "
           "\\* the hardest stretch, " +
           MdEscape(HardestText(plan)) + ".\n";
  }
  out += "\n## Parameters\n\n";
  for (const auto& l : ParameterLines(plan.variation.params)) out += "- " + MdEscape(l) + "\n";
  if (!plan.smoothing_model.empty()) {
    out += std::string("- smoothing (") + SmoothingMethodName(plan.setter.smooth_method) +
           ") with " + MdEscape(plan.smoothing_model) + "\n";
  }
  out += std::string("\nReproduce: `strangebeta vary ") + (tokens ? "--tokens FILE... " : "") +
         ReproduceOptions(plan.variation.params, plan.setter) + (tokens ? "`\n" : " ROUTES...`\n");
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

// A JSON number; non-finite values (never produced by the engine) as null.
std::string JsonNumber(double v) { return std::isfinite(v) ? FormatNumber(v) : "null"; }

void AppendNotes(std::string* out, const chaos::VariedMove& m) {
  *out += ", \"notes\": [";
  for (size_t k = 0; k < m.notes.size(); ++k) {
    if (k) *out += ", ";
    AppendJsonString(out, m.notes[k]);
  }
  *out += "]}";
}

void AppendMoves(std::string* out, const RoutePlan& plan) {
  const chaos::Variation& v = plan.variation;
  const bool estimates = HasEstimates(plan);
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
    *out += m.crux ? ", \"crux\": true" : ", \"crux\": false";
    *out += ", \"difficulty\": " + (estimates ? JsonNumber(plan.profile->difficulty[j]) : "null");
    AppendNotes(out, m);
  }
  *out += v.moves.empty() ? "]" : "\n  ]";
}

// Token plans: positions instead of moves (no hand, crux or difficulty).
void AppendPositions(std::string* out, const chaos::Variation& v) {
  *out += "[";
  for (size_t j = 0; j < v.moves.size(); ++j) {
    const auto& m = v.moves[j];
    *out += j ? ",\n    {\"token\": " : "\n    {\"token\": ";
    AppendJsonString(out, m.text);
    if (m.source) {
      *out += ", \"source\": {\"sequence\": " + std::to_string(m.source->route) +
              ", \"position\": " + std::to_string(m.source->move) + "}";
    } else {
      *out += ", \"source\": null";
    }
    *out += m.changed ? ", \"changed\": true" : ", \"changed\": false";
    AppendNotes(out, m);
  }
  *out += v.moves.empty() ? "]" : "\n  ]";
}

void AppendSmoothing(std::string* out, const RoutePlan& plan) {
  *out += "{\"model\": ";
  AppendJsonString(out, plan.smoothing_model);
  *out += ", \"method\": \"" + std::string(SmoothingMethodName(plan.setter.smooth_method)) + "\"";
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
            ", \"bits_saved\": " + JsonNumber(s.bits_saved()) + ", \"method\": \"" +
            SmoothingMethodName(s.method) + "\", \"direct_seen\": " +
            (s.direct_seen ? "true" : "false") + ", \"note\": ";
    AppendJsonString(out, s.CostNote());
    *out += "}";
  }
  *out += "]}";
}

std::string JsonTriple(const chaos::State& s) {
  return "[" + JsonNumber(s[0]) + ", " + JsonNumber(s[1]) + ", " + JsonNumber(s[2]) + "]";
}

// A string, or null when empty.
void AppendStringOrNull(std::string* out, const std::string& s) {
  if (s.empty()) {
    *out += "null";
  } else {
    AppendJsonString(out, s);
  }
}

void AppendSearch(std::string* out, const RoutePlan& plan) {
  if (!plan.search) {
    *out += "null";
    return;
  }
  const SearchReport& r = *plan.search;
  *out += "{\"requested_ic\": " + JsonTriple(r.requested_ic) +
          ", \"used_ic\": " + JsonTriple(r.used_ic) + ", \"distance\": " + JsonNumber(r.distance) +
          ", \"offset\": [" + std::to_string(r.offset[0]) + ", " + std::to_string(r.offset[1]) +
          ", " + std::to_string(r.offset[2]) + "], \"evaluated\": " + std::to_string(r.evaluated) +
          ", \"hands_swapped\": " + std::to_string(r.hands_swapped) + ", \"constraints\": [";
  for (size_t i = 0; i < r.constraints.size(); ++i) {
    const chaos::ConstraintOutcome& c = r.constraints[i];
    *out += i ? ", {\"name\": \"" : "{\"name\": \"";
    *out += std::string(chaos::ConstraintName(c.constraint)) + "\", \"held\": " +
            (c.held ? "true" : "false") + ", \"detail\": ";
    AppendJsonString(out, c.detail);
    *out += "}";
  }
  *out += "]}";
}

void AppendWarnings(std::string* out, const RoutePlan& plan) {
  if (!plan.warnings) {
    *out += "null";
    return;
  }
  *out += "[";
  const auto& ws = plan.warnings->warnings;
  for (size_t i = 0; i < ws.size(); ++i) {
    *out += i ? ", {\"kind\": \"" : "{\"kind\": \"";
    *out += std::string(WarningKindName(ws[i].kind)) + "\", \"first\": " +
            std::to_string(ws[i].first) + ", \"last\": " + std::to_string(ws[i].last) +
            ", \"count\": " + std::to_string(ws[i].count) + ", \"message\": ";
    AppendJsonString(out, ws[i].message);
    *out += "}";
  }
  *out += "]";
}

void AppendSummary(std::string* out, const RoutePlan& plan) {
  if (!plan.warnings) {
    *out += "null";
    return;
  }
  const ChangeSummary& c = plan.warnings->summary;
  *out += "{\"moves\": " + std::to_string(c.moves) + ", \"new_moves\": " + std::to_string(c.new_moves) + ", \"changed\": " + std::to_string(c.changed) +
          ", \"text_changed\": " + std::to_string(c.text_changed) +
          ", \"displacement\": " + std::to_string(c.displacement) +
          ", \"change\": " + JsonNumber(c.change) + ", \"farthest\": " + std::to_string(c.farthest) +
          ", \"message\": ";
  AppendJsonString(out, c.message);
  *out += "}";
}

void AppendProfile(std::string* out, const RoutePlan& plan) {
  if (!plan.profile) {
    *out += "null";
    return;
  }
  const DifficultyProfile& p = *plan.profile;
  *out += "{\"cruxes\": [";
  bool first = true;
  for (size_t j = 0; j < p.crux.size(); ++j) {
    if (!p.crux[j]) continue;
    *out += (first ? "" : ", ") + std::to_string(j);
    first = false;
  }
  *out += "], \"estimated\": ";
  *out += HasEstimates(plan) ? "true" : "false";
  *out += ", \"hardest_stretch\": ";
  if (p.hardest_first >= 0) {
    *out += "{\"first\": " + std::to_string(p.hardest_first) +
            ", \"last\": " + std::to_string(p.hardest_last) +
            ", \"mean\": " + JsonNumber(p.hardest_mean) + "}";
  } else {
    *out += "null";
  }
  *out += "}";
}

void AppendGrades(std::string* out, const RoutePlan& plan) {
  if (!plan.grades) {
    *out += "null";
    return;
  }
  const PlanGrades& g = *plan.grades;
  *out += "{\"discipline\": ";
  AppendStringOrNull(out, g.discipline);
  *out += ", \"scale\": ";
  AppendStringOrNull(out, g.scale);
  *out += ", \"estimate\": ";
  AppendStringOrNull(out, g.estimate);
  *out += ", \"low\": ";
  AppendStringOrNull(out, g.low);
  *out += ", \"high\": ";
  AppendStringOrNull(out, g.high);
  *out += ", \"level\": " + JsonNumber(g.level) + ", \"note\": ";
  AppendStringOrNull(out, g.note);
  *out += "}";
}

}  // namespace

std::string RenderMovesJson(const RoutePlan& plan) {
  std::string out;
  if (plan.tokens()) {
    AppendPositions(&out, plan.variation);
  } else {
    AppendMoves(&out, plan);
  }
  return out;
}

std::string RenderJson(const RoutePlan& plan) {
  // Written directly rather than through a document tree: one line per move
  // and per trajectory point keeps million-move plans fast and readable.
  const auto& v = plan.variation;
  const bool tokens = plan.tokens();
  std::string out;
  out.reserve(1024 + v.moves.size() * 170);
  out += std::string("{\n  \"kind\": \"") + (tokens ? "tokens" : "routes") + "\",\n";
  out += "  \"parameters\": " + ParametersJson(v.params, plan.setter) + ",\n  \"inputs\": [";
  for (size_t i = 0; i < v.inputs.size(); ++i) {
    out += i ? ", {\"name\": " : "{\"name\": ";
    AppendJsonString(&out, v.inputs[i].name);
    out += std::string(tokens ? ", \"positions\": " : ", \"moves\": ") +
           std::to_string(v.inputs[i].route.moves.size());
    if (!tokens) {
      out += ", \"grade\": ";
      const bool graded = plan.grades && i < plan.grades->inputs.size();
      AppendStringOrNull(&out, graded ? plan.grades->inputs[i] : std::string());
    }
    out += "}";
  }
  out += tokens ? "],\n  \"positions\": " : "],\n  \"moves\": ";
  out += RenderMovesJson(plan);
  out += ",\n  \"grades\": ";
  AppendGrades(&out, plan);
  out += ",\n  \"search\": ";
  AppendSearch(&out, plan);
  out += ",\n  \"warnings\": ";
  AppendWarnings(&out, plan);
  out += ",\n  \"summary\": ";
  AppendSummary(&out, plan);
  out += ",\n  \"profile\": ";
  AppendProfile(&out, plan);
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
    if (s.contains("method")) {
      if (!s["method"].is_string()) return false;
      auto m = ParseSmoothingMethod(s["method"].get<std::string>());
      if (!m.ok()) return false;
      sug.method = *m;
    }
    if (s.contains("direct_seen")) {
      if (!s["direct_seen"].is_boolean()) return false;
      sug.direct_seen = s["direct_seen"].get<bool>();
    }
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

std::string RenderTrajectorySvg(const RoutePlan& plan) { return TrajectorySvg(plan, {}); }

std::string TrajectorySvg(const RoutePlan& plan, const TrajectoryWords& words) {
  std::string out;
  const double w = 640, h = 480;
  cairo_surface_t* surface = cairo_svg_surface_create_for_stream(AppendToString, &out, w, h);
  cairo_svg_surface_restrict_to_version(surface, CAIRO_SVG_VERSION_1_1);
  cairo_svg_surface_set_document_unit(surface, CAIRO_SVG_UNIT_PX);
  cairo_t* cr = cairo_create(surface);
  DrawTrajectory(cr, plan, w, h, words);
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
