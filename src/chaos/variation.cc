#include "chaos/variation.h"

#include <cctype>
#include <cmath>
#include <map>
#include <thread>

#include "base/text.h"

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
  if (skip < 0) return Status::InvalidInput("skip: must be >= 0");
  if (skip > 100000000) return Status::InvalidInput("skip: must be <= 100000000");
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
  if (mapping.max_repeat < 0) return Status::InvalidInput("max-repeat: must be >= 0");
  return Status::Ok();
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
      int h = v.hand == Hand::kLeft ? 0 : 1;
      bool match = by_flag ? is_match[out.size()] : IsMatchText(v.text);
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

std::vector<int> RepeatClasses(const std::vector<VariedMove>& moves) {
  std::map<std::string, int> ids;
  std::vector<int> out;
  out.reserve(moves.size());
  for (const VariedMove& m : moves) {
    auto [it, inserted] = ids.emplace(NormalizeForRepeat(m.text), static_cast<int>(ids.size()));
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
  if (params.mapping.max_repeat > 0) move_class = RepeatClasses(prepared);
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
