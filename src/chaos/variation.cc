#include "chaos/variation.h"

#include <cctype>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "base/number.h"
#include "base/text.h"
#include "chaos/tokens.h"

namespace sb::chaos {

Result<VaryParams> VaryParams::Preset(std::string_view name) {
  VaryParams p;
  std::string l = ToLower(name);
  if (l == "default") return p;
  if (l == "more") {
    p.preset = "more";
    p.var_ic = {-16.0, -13.5, 52.0};
    p.skip = 100;
    return p;
  }
  return Status::InvalidInput("unknown preset \"" + std::string(name) + "\" (default or more)");
}

Status VaryParams::Validate() const {
  if (!std::isfinite(step) || step <= 0.0) {
    return Status::InvalidInput("step: must be a positive number");
  }
  if (skip < 0 || skip > kMaxSkip) {
    return Status::InvalidInput("skip: must be between 0 and " + std::to_string(kMaxSkip));
  }
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(ref_ic[i])) return Status::InvalidInput("ref-ic: must be finite numbers");
    if (!std::isfinite(var_ic[i])) return Status::InvalidInput("var-ic: must be finite numbers");
    if (!std::isfinite(system.params[i])) {
      return Status::InvalidInput("params: must be finite numbers");
    }
  }
  // Mask 0 is degenerate (every point ties, so every move maps to the first)
  // but reproduces the original site's "000" variations; the CLI refuses it.
  if (mapping.mask > 7) return Status::InvalidInput("mask: must be a subset of x, y, z");
  if (mapping.max_repeat < 0 || mapping.max_repeat > kMaxRepeat) {
    return Status::InvalidInput("max-repeat: must be between 0 and " + std::to_string(kMaxRepeat));
  }
  return Status::Ok();
}

// ---------------------------------------------------------------------------
// Parameter codecs.

namespace {

using nlohmann::json;

Status FieldError(const std::string& field, const std::string& what) {
  return Status::InvalidInput(field + ": " + what);
}

Status GetTriple(const json& j, const char* field, std::array<double, 3>* out) {
  if (!j.contains(field)) return Status::Ok();
  const json& v = j.at(field);
  if (v.is_string()) {
    if (!ParseTriple(v.get<std::string>(), out)) {
      return FieldError(field, "expected three numbers x,y,z");
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
  // Unsigned values above INT64_MAX read as negative: out of range either way.
  int64_t x = v.get<int64_t>();
  if (x < lo || x > hi) {
    return FieldError(field, "must be between " + std::to_string(lo) + " and " +
                                 std::to_string(hi));
  }
  *out = static_cast<int>(x);
  return Status::Ok();
}

}  // namespace

std::string ParamsToJson(const VaryParams& p) {
  json j;
  j["preset"] = p.preset;
  j["system"] = SystemKindName(p.system.kind);
  j["params"] = p.system.params;
  j["integrator"] = IntegratorKindName(p.integrator);
  j["step"] = p.step;
  j["ref_ic"] = p.ref_ic;
  j["var_ic"] = p.var_ic;
  j["skip"] = p.skip;
  j["mapping"] = MappingKindName(p.mapping.kind);
  j["mask"] = MaskString(p.mapping.mask);
  j["dabby_direction"] = DabbyDirectionName(p.mapping.dabby_direction);
  j["max_repeat"] = p.mapping.max_repeat;
  return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

Result<VaryParams> ParamsFromJson(std::string_view json_text) {
  json j = json::parse(json_text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return Status::InvalidInput("parameters: malformed JSON");
  if (!j.is_object()) return Status::InvalidInput("parameters: expected an object");
  VaryParams p;
  if (j.contains("preset")) {
    if (!j["preset"].is_string()) return FieldError("preset", "expected a string");
    auto pr = VaryParams::Preset(j["preset"].get<std::string>());
    if (!pr.ok()) return FieldError("preset", pr.status().message());
    p = *pr;
  }
  SB_RETURN_IF_ERROR(GetEnum(j, "system", ParseSystemKind, &p.system.kind));
  if (j.contains("system") && !j.contains("params")) p.system.params = DefaultParams(p.system.kind);
  SB_RETURN_IF_ERROR(GetTriple(j, "params", &p.system.params));
  SB_RETURN_IF_ERROR(GetEnum(j, "integrator", ParseIntegratorKind, &p.integrator));
  if (j.contains("step")) {
    if (!j["step"].is_number()) return FieldError("step", "expected a number");
    p.step = j["step"].get<double>();
  }
  SB_RETURN_IF_ERROR(GetTriple(j, "ref_ic", &p.ref_ic));
  SB_RETURN_IF_ERROR(GetTriple(j, "var_ic", &p.var_ic));
  SB_RETURN_IF_ERROR(GetInt(j, "skip", 0, kMaxSkip, &p.skip));
  SB_RETURN_IF_ERROR(GetEnum(j, "mapping", ParseMappingKind, &p.mapping.kind));
  SB_RETURN_IF_ERROR(GetEnum(j, "mask", ParseMask, &p.mapping.mask));
  SB_RETURN_IF_ERROR(
      GetEnum(j, "dabby_direction", ParseDabbyDirection, &p.mapping.dabby_direction));
  SB_RETURN_IF_ERROR(GetInt(j, "max_repeat", 0, kMaxRepeat, &p.mapping.max_repeat));
  SB_RETURN_IF_ERROR(p.Validate());
  return p;
}

namespace {
const char* const kIcColumns[6] = {"rx", "ry", "rz", "vx", "vy", "vz"};
}  // namespace

Result<VaryParams> ParamsFromSiteColumns(const std::map<std::string, std::string>& columns,
                                         const SourceLocation& where,
                                         std::vector<std::string>* notes) {
  auto get = [&](const char* k) -> std::string {
    auto it = columns.find(k);
    return it == columns.end() ? std::string() : std::string(Trim(it->second));
  };
  auto bad = [&](const char* column, const std::string& what) {
    return Status::InvalidInputAt(where, std::string(column) + ": " + what);
  };
  VaryParams p;
  p.integrator = IntegratorKind::kRkf45;
  p.mapping.kind = ToLower(get("nna")) == "d" ? MappingKind::kDabby : MappingKind::kEuclidean;
  if (std::string mask = get("dim_mask"); !mask.empty()) {
    Result<DimMask> m = ParseMask(mask);
    if (m.ok()) {
      p.mapping.mask = *m;
    } else if (notes) {
      notes->push_back("dim_mask \"" + mask + "\" ignored: " + m.status().message());
    }
  }
  if (std::string v = get("max_repeat"); !v.empty()) {
    // The site wrote -1 for "off" in a few rows.
    if (v == "-1") v = "0";
    if (!ParseInt(v, &p.mapping.max_repeat) || p.mapping.max_repeat < 0 ||
        p.mapping.max_repeat > kMaxRepeat) {
      return bad("max_repeat", "expected a whole number 0.." + std::to_string(kMaxRepeat) +
                                   ", got \"" + v.substr(0, 20) + "\"");
    }
  }
  if (std::string v = get("transient"); !v.empty()) {
    if (!ParseInt(v, &p.skip) || p.skip < 0 || p.skip > kMaxSkip) {
      return bad("transient", "expected a whole number 0.." + std::to_string(kMaxSkip) +
                                  ", got \"" + v.substr(0, 20) + "\"");
    }
  }
  for (int k = 0; k < 6; ++k) {
    std::string v = get(kIcColumns[k]);
    if (v.empty()) continue;
    double d = 0;
    if (!ParseDouble(v, &d)) {
      return bad(kIcColumns[k], "not a finite number: \"" + v.substr(0, 20) + "\"");
    }
    (k < 3 ? p.ref_ic : p.var_ic)[k % 3] = d;
  }
  if (Status s = p.Validate(); !s.ok()) return Status::InvalidInputAt(where, s.message());
  return p;
}

std::map<std::string, std::string> SiteColumnsFromParams(const VaryParams& p) {
  std::map<std::string, std::string> c;
  c["nna"] = p.mapping.kind == MappingKind::kDabby ? "D" : "B";
  c["dim_mask"] = MaskString(p.mapping.mask);
  c["max_repeat"] = std::to_string(p.mapping.max_repeat);
  c["prec_trunc"] = "0";
  c["transient"] = std::to_string(p.skip);
  for (int k = 0; k < 6; ++k) c[kIcColumns[k]] = FormatDouble((k < 3 ? p.ref_ic : p.var_ic)[k % 3]);
  return c;
}

std::vector<VariedMove> PrepareMoves(const std::vector<InputRoute>& inputs) {
  return PrepareMoves(inputs, {});
}

std::vector<VariedMove> PrepareMoves(const std::vector<InputRoute>& inputs,
                                     const std::vector<bool>& is_match) {
  size_t total = 0;
  for (const InputRoute& in : inputs) total += in.route.moves.size();
  const bool by_flag = !is_match.empty() && is_match.size() == total;
  std::vector<VariedMove> out;
  for (size_t r = 0; r < inputs.size(); ++r) {
    const auto& moves = inputs[r].route.moves;
    // The latest (already substituted) text of each hand within this route.
    std::optional<std::string> last[2];
    for (size_t m = 0; m < moves.size(); ++m) {
      VariedMove v;
      v.hand = moves[m].hand;
      v.text = moves[m].text;
      v.source = SourceRef{static_cast<int>(r), static_cast<int>(m)};
      v.crux = moves[m].crux;
      int h = v.hand == Hand::kLeft ? 0 : 1;
      bool match = !inputs[r].tokens && (by_flag ? is_match[out.size()] : IsMatchText(v.text));
      if (match && last[1 - h]) {
        v.text = *last[1 - h];
        v.notes.push_back("(match?)");
      }
      last[h] = v.text;
      out.push_back(std::move(v));
    }
  }
  return out;
}

namespace {

// Text with case and punctuation ignored: lower-case letters and digits,
// single spaces between words.
std::string NormalizeForRepeat(std::string_view text) {
  std::string out;
  bool space = false;
  for (char c : text) {
    unsigned char u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || u >= 0x80) {
      if (space && !out.empty()) out += ' ';
      space = false;
      out += static_cast<char>(std::tolower(u));
    } else if (std::isspace(u)) {
      space = true;
    }
  }
  return out;
}

}  // namespace

std::vector<int> RepeatClasses(const std::vector<VariedMove>& moves, bool exact) {
  std::map<std::string, int> ids;
  std::vector<int> out;
  out.reserve(moves.size());
  for (const VariedMove& m : moves) {
    auto [it, inserted] =
        ids.emplace(exact ? m.text : NormalizeForRepeat(m.text), static_cast<int>(ids.size()));
    out.push_back(it->second);
  }
  return out;
}

Result<Variation> Vary(std::vector<InputRoute> inputs, const VaryParams& params) {
  return Vary(std::move(inputs), params, {});
}

Result<Variation> Vary(std::vector<InputRoute> inputs, const VaryParams& params,
                       const std::vector<bool>& is_match) {
  SB_RETURN_IF_ERROR(params.Validate());
  SB_RETURN_IF_ERROR(CheckInputKinds(inputs));
  std::vector<VariedMove> prepared = PrepareMoves(inputs, is_match);
  if (prepared.empty()) return Status::InvalidInput("no moves to vary");
  if (!is_match.empty() && is_match.size() != prepared.size()) {
    return Status::InvalidInput("match flags: one per input move expected");
  }
  const int n = static_cast<int>(prepared.size());

  Variation v;
  v.params = params;
  auto integrate_reference = [&] {
    v.reference = Trajectory(params.system, params.integrator, params.step, params.ref_ic,
                             params.skip, n);
  };
  if (static_cast<long>(n) + params.skip >= 65536) {  // long: integrate both at once
    std::thread t(integrate_reference);
    v.variation = Trajectory(params.system, params.integrator, params.step, params.var_ic,
                             params.skip, n);
    t.join();
  } else {
    integrate_reference();
    v.variation = Trajectory(params.system, params.integrator, params.step, params.var_ic,
                             params.skip, n);
  }
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) {
      if (!std::isfinite(v.reference[i][d]) || !std::isfinite(v.variation[i][d])) {
        return Status::InvalidInput(
            "the trajectory diverged (non-finite state); choose a smaller step, other "
            "parameters or initial conditions");
      }
    }
  }

  std::vector<int> move_class;
  if (params.mapping.max_repeat > 0) move_class = RepeatClasses(prepared, AreTokens(inputs));
  v.mapping = MapTrajectory(v.reference, v.variation, params.mapping, move_class);

  v.moves.reserve(n);
  for (int j = 0; j < n; ++j) {
    int k = v.mapping[j];
    if (k < 0) {
      VariedMove blank;
      blank.hand = prepared[j].hand;
      blank.changed = true;
      blank.notes.push_back("(blank: fill in)");
      v.moves.push_back(std::move(blank));
      continue;
    }
    VariedMove m = prepared[k];
    m.changed = k != j;
    v.moves.push_back(std::move(m));
  }
  v.inputs = std::move(inputs);
  return v;
}

}  // namespace sb::chaos
