#include "app/discipline_targets.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "gym/rules.h"
#include "language/styles.h"
#include "store/target_store.h"

namespace sb::app {

namespace {

std::string StyleKind(const std::string& style) {
  const auto& holds = language::HoldStyleNames();
  if (std::find(holds.begin(), holds.end(), style) != holds.end()) return "hold";
  if (style == language::kUnparsedStyle) return "unparsed";
  return "movement";
}

bool IsTargetDiscipline(const std::string& d) {
  for (const char* name : kTargetDisciplines) {
    if (d == name) return true;
  }
  return false;
}

}  // namespace

Status DisciplineTargets::Validate() const {
  if (!IsTargetDiscipline(discipline)) {
    return Status::InvalidInput("discipline: expected \"bouldering\" or \"roped\"");
  }
  return WallTargets{grades, styles}.Validate(discipline);
}

std::vector<DisciplineDashboard> DisciplineDashboards(
    const std::vector<WallDashboard>& walls, const std::vector<DisciplineTargets>& targets) {
  std::vector<DisciplineDashboard> out;
  for (const char* name : kTargetDisciplines) {
    const DisciplineTargets* target = nullptr;
    for (const DisciplineTargets& t : targets) {
      if (t.discipline == name) target = &t;
    }
    DisciplineDashboard d;
    d.discipline = name;
    if (target) d.targets_revision = target->revision;
    std::map<std::string, BandRow> bands;
    std::map<std::string, double> style_moves;  // moves having the style
    for (const WallDashboard& w : walls) {
      if (w.wall.discipline != name) continue;
      ++d.walls;
      if (d.scale.empty()) d.scale = w.scale;
      d.on_wall += w.on_wall;
      d.ungraded += w.ungraded;
      d.moves += w.moves;
      for (const BandRow& b : w.bands) {
        if (b.current == 0) continue;
        auto [it, added] = bands.try_emplace(b.band, BandRow{b.band, b.value, 0, std::nullopt});
        it->second.current += b.current;
      }
      for (const StyleRow& s : w.styles) style_moves[s.style] += s.share * w.moves;
    }
    if (d.walls == 0 && (target == nullptr || (target->grades.empty() && target->styles.empty()))) {
      continue;
    }
    if (target) {
      for (const auto& [text, count] : target->grades) {
        Result<BandRow> b = BandOfText(text, name, d.scale, "grades." + text);
        if (!b.ok()) continue;  // stored targets were validated; a scale change may orphan one
        auto [it, added] = bands.try_emplace(b->band, BandRow{b->band, b->value, 0, std::nullopt});
        it->second.target = it->second.target.value_or(0) + count;
      }
    }
    for (auto& [band, row] : bands) d.bands.push_back(row);
    std::sort(d.bands.begin(), d.bands.end(), [](const BandRow& a, const BandRow& b) {
      return std::tie(a.value, a.band) < std::tie(b.value, b.band);
    });
    std::map<std::string, StyleRow> styles;
    for (const auto& [style, n] : style_moves) {
      StyleRow& s = styles[style];
      s.style = style;
      s.kind = StyleKind(style);
      s.share = d.moves > 0 ? n / d.moves : 0;
    }
    if (target) {
      for (const auto& [style, share] : target->styles) {
        StyleRow& s = styles[style];
        s.style = style;
        s.kind = StyleKind(style);
        s.reference = share;
        s.targeted = true;
      }
    }
    std::vector<StyleRow> targeted;
    for (auto& [style, row] : styles) {
      d.styles.push_back(row);
      if (row.targeted) targeted.push_back(row);
    }
    d.gaps = GradeGaps(d.bands);
    for (Gap& g : StyleGaps(targeted)) d.gaps.push_back(std::move(g));
    // The walls' words, the discipline named in place of "wall NAME".
    for (std::string& line : GapWords(name, d.gaps)) {
      const std::string wall_prefix = std::string("wall ") + name + ": ";
      if (line.rfind(wall_prefix, 0) == 0) line = line.substr(5);
      d.gap_words.push_back(std::move(line));
    }
    out.push_back(std::move(d));
  }
  return out;
}

Result<std::vector<DisciplineTargets>> Dashboard::GymDisciplineTargets(const Viewer& v,
                                                                     int64_t gym) {
  SB_ASSIGN_OR_RETURN(Gym g, gyms_.Get(v, gym));
  (void)g;
  std::vector<DisciplineTargets> out;
  if (!targets_) return out;
  SB_ASSIGN_OR_RETURN(std::vector<store::DisciplineTargetRecord> rows,
                      targets_->DisciplineTargets(gym));
  SB_ASSIGN_OR_RETURN(int64_t revision, targets_->DisciplineTargetsRevision(gym));
  for (const char* name : kTargetDisciplines) {
    DisciplineTargets t;
    t.discipline = name;
    t.revision = revision;
    for (const store::DisciplineTargetRecord& r : rows) {
      if (r.discipline != name) continue;
      if (r.kind == "grade") t.grades[r.name] = static_cast<int>(std::lround(r.value));
      if (r.kind == "style") t.styles[r.name] = r.value;
    }
    out.push_back(std::move(t));
  }
  return out;
}

Status Dashboard::SetDisciplineTargets(const Viewer& v, int64_t gym, const DisciplineTargets& t) {
  if (!v.logged_in()) return Status::Unauthenticated("log in first");
  SB_ASSIGN_OR_RETURN(Gym g, gyms_.Get(v, gym));
  if (!gym::IsHead(g.role)) return Status::Permission("only the gym's head setters may set targets");
  SB_RETURN_IF_ERROR(t.Validate());
  if (!targets_) return Status::Internal("the store keeps no targets");
  // Bands in the discipline's scale: that of its first wall with one.
  std::string scale;
  SB_ASSIGN_OR_RETURN(std::vector<Wall> walls, gyms_.Walls(v, gym));
  for (const Wall& w : walls) {
    if (w.discipline != t.discipline) continue;
    SB_ASSIGN_OR_RETURN(scale, WallScale(v, w));
    if (!scale.empty()) break;
  }
  SB_ASSIGN_OR_RETURN(auto bands, TargetBands(t.grades, t.discipline, scale));
  std::vector<store::DisciplineTargetRecord> rows;
  for (const auto& [band, count] : bands) {
    rows.push_back({gym, t.discipline, "grade", band, static_cast<double>(count)});
  }
  for (const auto& [style, share] : t.styles) {
    rows.push_back({gym, t.discipline, "style", style, share});
  }
  return targets_->SetDisciplineTargets(gym, t.discipline, rows, t.revision);
}

}  // namespace sb::app
