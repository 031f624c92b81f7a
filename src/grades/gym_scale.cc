#include "grades/gym_scale.h"

#include <cmath>

#include "base/text.h"

namespace sb::grades {

std::optional<size_t> GymScale::Find(std::string_view text) const {
  const std::string_view t = Trim(text);
  for (size_t i = 0; i < labels.size(); ++i) {
    if (EqualsIgnoreCase(labels[i].label, t)) return i;
  }
  return std::nullopt;
}

Result<double> GymScale::Read(std::string_view text, std::string_view field) const {
  if (std::optional<size_t> i = Find(text)) return labels[*i].value();
  return Status::InvalidInput(std::string(field) + ": \"" + std::string(Trim(text)) +
                              "\" is not a grade of the scale \"" + name + "\" (it accepts " +
                              Accepts() + ")");
}

std::string GymScale::Format(double value) const {
  std::string best;
  double best_d = INFINITY;
  for (const GymLabel& l : labels) {
    const double d = value < l.lo ? l.lo - value : value > l.hi ? value - l.hi : 0;
    if (d < best_d) {
      best_d = d;
      best = l.label;
    }
  }
  return best;
}

std::string GymScale::Accepts() const {
  std::string out;
  for (const GymLabel& l : labels) out += (out.empty() ? "" : ", ") + l.label;
  return out;
}

Result<GymScale> MakeGymScale(std::string_view name, const std::vector<LabelSpec>& labels) {
  GymScale s;
  s.name = std::string(Trim(name));
  if (s.name.empty() || s.name.size() > kMaxGymScaleNameBytes ||
      FindInvalidUtf8(s.name) != std::string::npos) {
    return Status::InvalidInput("name: 1-" + std::to_string(kMaxGymScaleNameBytes) +
                                " bytes of text");
  }
  if (BuiltInScale(s.name)) {
    return Status::InvalidInput("name: \"" + s.name + "\" is a built-in scale");
  }
  if (labels.empty() || labels.size() > kMaxGymScaleLabels) {
    return Status::InvalidInput("labels: 1 to " + std::to_string(kMaxGymScaleLabels) + " labels");
  }
  std::optional<Discipline> disc;
  for (size_t i = 0; i < labels.size(); ++i) {
    const std::string at = "labels[" + std::to_string(i) + "]";
    GymLabel l;
    l.label = std::string(Trim(labels[i].label));
    if (l.label.empty() || l.label.size() > kMaxGymLabelBytes ||
        FindInvalidUtf8(l.label) != std::string::npos) {
      return Status::InvalidInput(at + ".label: 1-" + std::to_string(kMaxGymLabelBytes) +
                                  " bytes of text");
    }
    if (s.Find(l.label)) return Status::InvalidInput(at + ".label: \"" + l.label + "\" twice");
    l.from = std::string(Trim(labels[i].from));
    l.to = std::string(Trim(labels[i].to));
    double ends[2];
    const std::string* texts[2] = {&l.from, &l.to};
    const char* names[2] = {"from", "to"};
    for (int k = 0; k < 2; ++k) {
      const std::string field = at + "." + names[k];
      // Letter grades read by case without a discipline: "6a" French, "6A" Font.
      Result<Grade> g = ParseGrade(*texts[k], {disc, std::nullopt}, field);
      if (!g.ok()) return g.status();
      if (!disc) disc = g->discipline();
      if (g->discipline() != *disc) {
        return Status::InvalidInput(field + ": \"" + *texts[k] + "\" is a " +
                                    DisciplineName(g->discipline()) +
                                    " grade; this scale's grades are " + DisciplineName(*disc));
      }
      ends[k] = g->value;
    }
    l.lo = ends[0];
    l.hi = ends[1];
    if (l.lo > l.hi) {
      return Status::InvalidInput(at + ": from (" + l.from + ") is harder than to (" + l.to + ")");
    }
    if (!s.labels.empty()) {
      const GymLabel& prev = s.labels.back();
      if (l.lo < prev.hi) {
        return Status::InvalidInput(at + ": " + l.from + ".." + l.to + " overlaps or precedes labels[" +
                                    std::to_string(i - 1) + "] (" + prev.from + ".." + prev.to +
                                    "): labels ascend without overlapping");
      }
    }
    s.labels.push_back(std::move(l));
  }
  s.discipline = *disc;
  return s;
}

std::optional<Scale> BuiltInScale(std::string_view name) {
  for (Scale s : {Scale::kV, Scale::kFont, Scale::kYds, Scale::kFrench, Scale::kUiaa}) {
    if (EqualsIgnoreCase(Trim(name), BuiltInScaleName(s))) return s;
  }
  return std::nullopt;
}

const char* BuiltInScaleName(Scale s) {
  switch (s) {
    case Scale::kYds: return "YDS";
    case Scale::kV: return "V";
    case Scale::kFont: return "Font";
    case Scale::kFrench: return "French";
    case Scale::kUiaa: return "UIAA";
  }
  return "V";
}

}  // namespace sb::grades
