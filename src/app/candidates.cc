#include "app/candidates.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <utility>

#include "app/variations.h"
#include "base/number.h"
#include "chaos/constraints.h"
#include "chaos/search.h"
#include "chaos/tokens.h"
#include "grades/scale.h"
#include "language/styles.h"
#include "language/symbols.h"
#include "markov/token_model.h"
#include "plan/smooth.h"

namespace sb::app {

namespace {

std::string Fixed(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, x);
  return buf;
}

// The whole band of a grade text read in discipline `d` (and the plan's
// scale when it has one); nullopt when it cannot be read.
std::optional<int> BandOf(const std::string& text, grades::Discipline d,
                          std::optional<grades::Scale> scale) {
  grades::GradeContext ctx;
  ctx.discipline = d;
  auto g = grades::ParseGrade(text, ctx);
  if (!g.ok() && scale) {
    ctx.scale = scale;
    g = grades::ParseGrade(text, ctx);
  }
  if (!g.ok()) {
    // "6B/6B+": the first of a split band.
    const size_t slash = text.find('/');
    if (slash == std::string::npos || slash == 0) return std::nullopt;
    return BandOf(text.substr(0, slash), d, scale);
  }
  return grades::Band(grades::Difficulty(*g, d));
}

// The levels' IC centres (NoveltyCentre).
constexpr double kCloseFactor = 1.0 / 3.0;
constexpr double kCloseStep = 0.5;  // of the ring step: the close level's rings are tighter
constexpr double kNewFactor = 3.0;
constexpr int kNewSkip = 100;

// A reason, in English and as a message (CandidateScore::why).
void Say(CandidateScore* s, Message m) {
  s->reasons.push_back(m.English());
  s->why.push_back(std::move(m));
}

// "novelty close: close to its inputs", ... as one message each.
Message NoveltyReason(Novelty n) {
  switch (n) {
    case Novelty::kClose: return Msg("novelty close: close to its inputs");
    case Novelty::kMix: return Msg("novelty mix: a mix of its inputs and new moves");
    case Novelty::kNew: break;
  }
  return Msg("novelty new: mostly new");
}


// The IC picker's reach around a level's centre, in grid steps (3 units at
// the default spacing of 0.1: the reference IC is inside the close level's
// scan, the mix level's covers 0 to 5 units from it): 2,821 ICs per level.
constexpr int kPickRadius = 30;
// At most this many variations made per level's scan (nearest the centre
// first): about 0.1 s.
constexpr int kMaxPickVaried = 4000;

// The IC picker (issue 33; the paper's section 7: "finds candidate ICs,
// given a desired amount of change or effect"). A scan of the grid around a
// level's centre with the setter's constraints (chaos::IcEvaluator, the IC
// search's own evaluation), and for each IC meeting them the variation it
// gives (chaos::Vary at that IC, exactly what the IC search returns when it
// starts there) with its share of new moves, warnings and filter.
struct ScanPoint {
  chaos::State ic{};
  int skip = 0;
  long order = 0;        // nearest first within its level's scan, levels in order
  int new_moves = 0, moves = 0;
  bool kept = false;     // the gallery's filter (RejectedByFilter, kMinNewMoves, same as input)
  bool swapped = false;  // hands swapped (the IC meets all but alternate-hands)
  int warnings = 0;
};
struct PickerScan {
  long scanned = 0;      // ICs evaluated
  long meeting = 0;      // of them, meeting the setter's constraints (hands swapped or not)
  long swapped = 0;      // of those, the ones meeting them once hands are swapped
  std::vector<ScanPoint> points;  // distinct move sequences, nearest first
  // The mappings (and whether hands were swapped) already made: the moves
  // are a function of them, so an IC repeating one is not varied again.
  std::set<std::pair<std::vector<int>, bool>> mappings;
};

// Scans `centre`'s grid (the request's spacing and plane, kPickRadius steps)
// and appends its distinct variations (not already in `seen`) to `*out`:
// at each IC meeting every constraint, the variation there; at each IC
// meeting all but alternate-hands, the variation there with hands swapped
// (chaos::AlternateHands, as the IC search does; the gallery builds a picked
// IC with a search of radius 0, so exactly this variation is made, whether
// or not another IC further away alternates by itself). Stops once `enough`
// in-band (`level`) kept points without warnings were found. Errors: the
// request's (CheckRequestForInputs, InputFacts, the evaluator's).
Status ScanLevel(const std::vector<chaos::InputRoute>& inputs_in, const chaos::VaryParams& centre,
                 const SettingRequest& setting, Novelty level, int enough,
                 std::set<std::vector<std::pair<Hand, std::string>>>* seen, PickerScan* out) {
  std::vector<chaos::InputRoute> inputs = inputs_in;
  SB_RETURN_IF_ERROR(chaos::CheckInputKinds(inputs));
  if (setting.drop_inner_finishes) DropInnerFinishes(&inputs);
  if (setting.drop_inner_starts) DropInnerStarts(&inputs);
  SB_RETURN_IF_ERROR(CheckRequestForInputs(setting, inputs));
  std::vector<bool> is_match;
  SB_ASSIGN_OR_RETURN(chaos::MoveFacts facts,
                      InputFacts(inputs, setting.match_grammar, &is_match, nullptr));
  SB_ASSIGN_OR_RETURN(chaos::IcEvaluator ev, chaos::IcEvaluator::Make(inputs, centre, facts,
                                                                        setting.constraints,
                                                                        is_match));
  const uint32_t requested = ev.requested();
  const uint32_t alt = chaos::ConstraintBit(chaos::Constraint::kAlternateHands);
  chaos::SearchGrid grid = setting.grid;
  // The search's own reach when larger (the CLI's 100 steps): an IC the
  // search would find is one the picker sees.
  grid.radius = std::max(kPickRadius, setting.grid.radius);
  const std::vector<std::array<int, 3>> offsets = chaos::SearchOffsets(grid);
  std::vector<chaos::State> ics(offsets.size());
  for (size_t i = 0; i < offsets.size(); ++i) {
    ics[i] = centre.var_ic;
    for (int a = 0; a < 3; ++a) {
      if (offsets[i][a] != 0) ics[i][a] = centre.var_ic[a] + offsets[i][a] * grid.spacing;
    }
  }
  std::vector<uint32_t> fails(ics.size());
  const size_t n = static_cast<size_t>(ev.size());
  std::vector<int> k(ics.size() * n);
  ev.Evaluate(ics.data(), ics.size(), fails.data(), k.data());
  const long base = out->scanned;
  out->scanned += static_cast<long>(ics.size());
  // ICs meeting every constraint, and those failing alternate-hands only
  // (their hands swapped), nearest first.
  std::vector<size_t> use;
  for (size_t i = 0; i < ics.size(); ++i) {
    if (fails[i] == 0 || ((requested & alt) && (fails[i] & ~alt) == 0)) use.push_back(i);
    if (fails[i] != 0 && (requested & alt) && (fails[i] & ~alt) == 0) ++out->swapped;
  }
  out->meeting += static_cast<long>(use.size());
  int found = 0;
  int varied = 0;
  for (size_t i : use) {
    if (found >= enough) break;
    const bool swap = fails[i] != 0;
    if (!out->mappings.insert({std::vector<int>(k.begin() + i * n, k.begin() + (i + 1) * n), swap})
             .second) {
      continue;
    }
    if (++varied > kMaxPickVaried) break;
    chaos::VaryParams p = centre;
    p.var_ic = ics[i];
    auto v = chaos::Vary(inputs, p, is_match);
    if (!v.ok()) continue;
    int same_hand_at = -1;
    if (swap) {
      chaos::AlternateHands(&v->moves, setting.constraints.keep_start,
                            setting.constraints.keep_finish, &same_hand_at);
      // A kept end whose hand was swapped is not held: rejected, as the
      // search reports it.
      if (same_hand_at < 0 && !v->moves.empty() &&
          ((setting.constraints.keep_start && !v->moves.front().notes.empty() &&
            std::find(v->moves.front().notes.begin(), v->moves.front().notes.end(),
                      "(hand swapped)") != v->moves.front().notes.end()) ||
           (setting.constraints.keep_finish &&
            std::find(v->moves.back().notes.begin(), v->moves.back().notes.end(),
                      "(hand swapped)") != v->moves.back().notes.end()))) {
        continue;
      }
    }
    std::vector<std::pair<Hand, std::string>> key;
    for (const chaos::VariedMove& m : v->moves) key.push_back({m.hand, m.text});
    if (!seen->insert(key).second) continue;
    const plan::PlanWarnings w = plan::Warn(*v, facts);
    const MoveChange change = plan::NewMoveCount(v->moves, v->inputs);
    ScanPoint pt;
    pt.ic = ics[i];
    pt.skip = centre.skip;
    pt.order = base + static_cast<long>(i);
    pt.new_moves = change.new_moves;
    pt.moves = change.moves;
    pt.warnings = static_cast<int>(w.warnings.size());
    pt.swapped = swap;
    pt.kept = change.same_as.empty() && change.new_moves >= kMinNewMoves &&
              !RejectedByFilter(w, nullptr, swap && same_hand_at > 0);
    if (pt.kept && pt.warnings == 0 && NoveltyOf(pt.new_moves, pt.moves) == level) ++found;
    out->points.push_back(std::move(pt));
  }
  return Status::Ok();
}

// How far a share of new moves is from a level's band, in moves (0 inside).
int MovesOutside(int new_moves, int moves, Novelty level) {
  // close: 3·new < moves; mix: moves <= 3·new <= 2·moves; new: 3·new > 2·moves.
  int lo = 0, hi = moves;
  if (level == Novelty::kClose) hi = (moves - 1) / 3;
  if (level == Novelty::kMix) { lo = (moves + 2) / 3; hi = (2 * moves) / 3; }
  if (level == Novelty::kNew) lo = (2 * moves) / 3 + 1;
  return new_moves < lo ? lo - new_moves : new_moves > hi ? new_moves - hi : 0;
}

// A warning's kind ("start-mid-route: move 4 ...") in a setter's words, as
// what a route "has".
Message WarningWords(std::string_view warning) {
  const std::string_view kind = warning.substr(0, warning.find(':'));
  if (kind == "start-mid-route") return Msg("a start hold mid-route");
  if (kind == "finish-mid-route") return Msg("a finish hold mid-route");
  if (kind == "repeated-move") return Msg("a move repeated");
  if (kind == "same-hand") return Msg("the same hand twice in a row");
  if (kind == "no-finish") return Msg("no finish");
  if (kind == "early-crux") return Msg("the crux too early");
  return std::string(kind);
}

// Why the level asked is not met without a warning, in a setter's words
// (MakeGallery's `said`): no variation within the setter's rules (kept by
// the filter) lands in the level, with the nearest share reached (the most
// changed for `new`, the least for `close`) among the scanned and made
// variations; or every one there has a warning, named.
Message NoveltyMissed(Novelty level, const std::vector<Candidate>& out,
                      const std::vector<ScanPoint>& points) {
  const Candidate& best = out.front();
  const Message level_words = Word(NoveltyWords(level));
  std::vector<std::pair<int, int>> kept;  // new moves, moves
  for (const ScanPoint& pt : points) {
    if (pt.kept && pt.moves > 0) kept.push_back({pt.new_moves, pt.moves});
  }
  bool met = false;
  for (const Candidate& c : out) {
    if (c.score.rejected || c.score.moves <= 0) continue;
    kept.push_back({c.score.new_moves, c.score.moves});
    met = met || c.score.novelty == level;
  }
  const Message shown = MsgN("{1} of {2} move changed", "{1} of {2} moves changed",
                             best.score.moves, {std::to_string(best.score.new_moves),
                                                std::to_string(best.score.moves)});
  if (met) {
    // Every kept candidate in the level has a warning: the one they share,
    // else the best's.
    std::string common = best.score.warnings.empty() ? "" : best.score.warnings.front();
    const std::string kind = common.substr(0, common.find(':'));
    bool all = !kind.empty();
    for (const Candidate& c : out) {
      if (c.score.rejected || c.score.novelty != level) continue;
      bool has = false;
      for (const std::string& w : c.score.warnings) has = has || w.rfind(kind + ":", 0) == 0;
      all = all && has;
    }
    if (all) {
      return Msg("The variations of these routes that are {1} all have {2}; the best of them is "
                 "shown ({3}): check it at the wall, or ask for another novelty",
                 {level_words, WarningWords(common), shown});
    }
    return Msg("The variations of these routes that are {1} all carry a warning; the best of them "
               "is shown ({2}, with {3}): check it at the wall, or ask for another novelty",
               {level_words, shown, WarningWords(common)});
  }
  if (kept.empty()) {
    return Msg("No variation of these routes passes the setter's rules: each is rejected; the "
               "best of them is shown ({1})", {shown});
  }
  // The nearest share to the level's band: the most changed for new, the
  // least for close, the nearest to the band for mix.
  auto share_less = [](const std::pair<int, int>& a, const std::pair<int, int>& b) {
    return static_cast<long>(a.first) * b.second < static_cast<long>(b.first) * a.second;
  };
  if (level == Novelty::kNew) {
    const auto m = *std::max_element(kept.begin(), kept.end(), share_less);
    return Msg("No variation of these routes changes more than two thirds of the moves within "
               "the setter's rules (the most changed: {1} of {2}); showing the best of the "
               "others instead ({3})",
               {std::to_string(m.first), std::to_string(m.second), shown});
  }
  if (level == Novelty::kClose) {
    const auto m = *std::min_element(kept.begin(), kept.end(), share_less);
    return Msg("No variation of these routes changes less than a third of the moves within "
               "the setter's rules (the least changed: {1} of {2}); showing the best of the "
               "others instead ({3})",
               {std::to_string(m.first), std::to_string(m.second), shown});
  }
  const auto lo = *std::min_element(kept.begin(), kept.end(), share_less);
  const auto hi = *std::max_element(kept.begin(), kept.end(), share_less);
  return Msg("No variation of these routes changes between a third and two thirds of the moves "
             "within the setter's rules (from {1} of {2} to {3} of {4}); showing the best of "
             "the others instead ({5})",
             {std::to_string(lo.first), std::to_string(lo.second), std::to_string(hi.first),
              std::to_string(hi.second), shown});
}

}  // namespace

Status CandidateSlot::Validate() const {
  if (!style.empty() && !language::IsStyleName(style)) {
    return Status::InvalidInput("style: unknown style \"" + style +
                                "\" (the names are listed in docs/setting.md)");
  }
  if (!band_to.empty() && band.empty()) {
    return Status::InvalidInput("band_to: given without band");
  }
  return Status::Ok();
}

MoveChange ChangeAgainstInputs(const std::vector<chaos::VariedMove>& moves,
                               const std::vector<chaos::InputRoute>& inputs) {
  return plan::NewMoveCount(moves, inputs);
}

const char* NoveltyName(Novelty n) {
  switch (n) {
    case Novelty::kClose: return "close";
    case Novelty::kMix: return "mix";
    case Novelty::kNew: return "new";
  }
  return "mix";
}

const char* NoveltyWords(Novelty n) {
  switch (n) {
    case Novelty::kClose: return "close to its inputs";
    case Novelty::kMix: return "a mix of its inputs and new moves";
    case Novelty::kNew: return "mostly new";
  }
  return "";
}

Result<Novelty> ParseNovelty(std::string_view text) {
  std::string t(text);
  for (char& c : t) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (Novelty n : {Novelty::kClose, Novelty::kMix, Novelty::kNew}) {
    if (t == NoveltyName(n)) return n;
  }
  return Status::InvalidInput("novelty: \"" + std::string(text) +
                              "\" is not a level (close, mix or new)");
}

Novelty NoveltyOf(int new_moves, int moves) {
  if (moves <= 0 || 3 * new_moves < moves) return Novelty::kClose;
  if (3 * new_moves <= 2 * moves) return Novelty::kMix;
  return Novelty::kNew;
}

chaos::VaryParams NoveltyCentre(const chaos::VaryParams& params, Novelty n) {
  chaos::VaryParams p = params;
  for (int k = 0; k < 3; ++k) {
    const double d = params.var_ic[k] - params.ref_ic[k];
    if (n == Novelty::kClose) p.var_ic[k] = params.ref_ic[k] + d * kCloseFactor;
    if (n == Novelty::kNew) p.var_ic[k] = params.ref_ic[k] + d * kNewFactor;
  }
  if (n == Novelty::kNew) p.skip = std::max(params.skip, kNewSkip);
  return p;
}

bool RejectedByFilter(const plan::PlanWarnings& warnings, std::vector<std::string>* why,
                      bool excuse_one_hand_pair, std::vector<Message>* said) {
  int finish = 0, moves = 0, hands = 0, pairs = 0;
  for (const plan::Warning& w : warnings.warnings) {
    finish += w.kind == plan::WarningKind::kFinishMidRoute;
    moves += w.kind == plan::WarningKind::kRepeatedMove;
    hands += w.kind == plan::WarningKind::kSameHand;
    pairs += w.kind == plan::WarningKind::kSameHand && w.count == 2;
  }
  // The one same-hand pair the kept ends' parity demands (and no other run).
  if (excuse_one_hand_pair && hands == 1 && pairs == 1) hands = 0;
  std::vector<Message> m;
  if (finish) {
    m.push_back(MsgN("rejected: a finish move before the end ({1} move)",
                     "rejected: a finish move before the end ({1} moves)", finish,
                     {std::to_string(finish)}));
  }
  if (moves) {
    m.push_back(MsgN("rejected: a move repeated more often in a row than in its inputs ({1} run)",
                     "rejected: a move repeated more often in a row than in its inputs ({1} runs)",
                     moves, {std::to_string(moves)}));
  }
  if (hands) {
    m.push_back(MsgN("rejected: one hand more often in a row than in its inputs ({1} run)",
                     "rejected: one hand more often in a row than in its inputs ({1} runs)", hands,
                     {std::to_string(hands)}));
  }
  for (Message& x : m) {
    if (why) why->push_back(x.English());
    if (said) said->push_back(std::move(x));
  }
  return finish + moves + hands > 0;
}

struct CandidateScorer::Impl {
  CandidateSlot slot;
  language::MoveLanguage styles;   // the project's grammar (style reading)
  language::MoveLanguage symbols;  // the model's own reading of moves
  // Read once per process and shared (plan::CachedModel): immutable.
  std::shared_ptr<const markov::TokenModel> model;
  int symbol_set = 0;  // 0..3 (k1..k4)
  Impl(CandidateSlot s, language::MoveLanguage st, language::MoveLanguage sy,
       std::shared_ptr<const markov::TokenModel> m, int set)
      : slot(std::move(s)),
        styles(std::move(st)),
        symbols(std::move(sy)),
        model(std::move(m)),
        symbol_set(set) {}
};

CandidateScorer::CandidateScorer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CandidateScorer::CandidateScorer(CandidateScorer&&) noexcept = default;
CandidateScorer& CandidateScorer::operator=(CandidateScorer&&) noexcept = default;
CandidateScorer::~CandidateScorer() = default;

Result<CandidateScorer> CandidateScorer::Make(const CandidateSlot& slot, const std::string& model) {
  SB_RETURN_IF_ERROR(slot.Validate());
  std::string path = model == "default" ? plan::DefaultModelPath() : model;
  if (path.empty()) return Status::NotFound("the bundled Markov model (data/models/default.sbm) was not found");
  SB_ASSIGN_OR_RETURN(std::shared_ptr<const markov::TokenModel> m, plan::CachedModel(path));
  SB_ASSIGN_OR_RETURN(plan::SymbolSource src, plan::CheckSmoothingModel(*m, path));
  SB_ASSIGN_OR_RETURN(language::MoveLanguage sy, plan::LoadSymbolLanguage(src));
  SB_ASSIGN_OR_RETURN(language::MoveLanguage st, language::MoveLanguage::LoadDefault());
  const int set = src.symbol_set[1] - '1';
  return CandidateScorer(
      std::make_unique<Impl>(slot, std::move(st), std::move(sy), std::move(m), set));
}

double CandidateScorer::BitsPerMove(const std::vector<std::string>& moves) {
  if (moves.empty()) return 0.0;
  std::vector<std::string> tokens;
  for (const std::string& m : moves) {
    tokens.push_back(impl_->symbols.Read(m).symbols.k[impl_->symbol_set]);
  }
  auto ids = impl_->model->Encode(tokens);
  if (!ids.ok()) return 0.0;  // a vocabulary model encodes every token
  return impl_->model->model().LogLoss(*ids) / static_cast<double>(moves.size());
}

CandidateScore CandidateScorer::Score(const plan::RoutePlan& p) {
  CandidateScore s;
  const plan::PlanWarnings w = p.warnings ? *p.warnings : plan::Warn(p.variation);
  const CandidateSlot& slot = impl_->slot;

  // The filter. Alternate-hands is not held only where the kept ends' hands
  // demand one same-hand pair (chaos::SearchVariation): that pair is said,
  // not rejected; any other hand run longer than the inputs' still is.
  bool parity_pair = false;
  if (p.search) {
    for (const chaos::ConstraintOutcome& o : p.search->constraints) {
      parity_pair |= o.constraint == chaos::Constraint::kAlternateHands && !o.held;
    }
  }
  s.rejected = RejectedByFilter(w, &s.reasons, parity_pair, &s.why);
  // A constraint asked and not held (a kept start or finish whose hand was
  // swapped): not what the setter asked for.
  if (p.search) {
    for (const chaos::ConstraintOutcome& o : p.search->constraints) {
      if (o.held) continue;
      if (o.constraint == chaos::Constraint::kAlternateHands) {
        Say(&s, Msg("one same-hand pair allowed: {1}", {o.detail}));
        continue;
      }
      s.rejected = true;
      Say(&s, Msg("rejected: {1} not held ({2})",
                  {std::string(chaos::ConstraintName(o.constraint)), o.detail}));
    }
  }

  // Change against the inputs: one rule (ChangeAgainstInputs, kMinNewMoves).
  const MoveChange change = ChangeAgainstInputs(p.variation.moves, p.variation.inputs);
  s.new_moves = change.new_moves;
  s.moves = change.moves;
  s.novelty = NoveltyOf(change.new_moves, change.moves);
  const std::vector<Message> counts = {std::to_string(change.new_moves),
                                        std::to_string(change.moves),
                                        std::to_string(kMinNewMoves)};
  if (!change.same_as.empty()) {
    s.rejected = true;
    Say(&s, Msg("rejected: same as input {1}", {change.same_as}));
  } else if (change.new_moves < kMinNewMoves) {
    s.rejected = true;
    Say(&s, MsgN("rejected: {1} of {2} move new against its inputs (at least {3} asked; the "
                 "inputs one after the other make one)",
                 "rejected: {1} of {2} moves new against its inputs (at least {3} asked; the "
                 "inputs one after the other make one)",
                 change.moves, counts));
  } else {
    Say(&s, MsgN("{1} of {2} move new against its inputs", "{1} of {2} moves new against its inputs",
                 change.moves, counts));
    Say(&s, NoveltyReason(s.novelty));
  }

  // Warnings.
  const int nw = static_cast<int>(w.warnings.size());
  for (const plan::Warning& x : w.warnings) {
    s.warnings.push_back(std::string(plan::WarningKindName(x.kind)) + ": " + x.message);
  }
  s.warnings_part = kScoreNoWarnings / (1.0 + nw);
  if (nw == 0) {
    Say(&s, Msg("no warnings"));
  } else {
    std::string kinds;
    std::set<std::string> seen;
    for (const plan::Warning& x : w.warnings) {
      if (seen.insert(plan::WarningKindName(x.kind)).second) {
        kinds += (kinds.empty() ? "" : ", ") + std::string(plan::WarningKindName(x.kind));
      }
    }
    Say(&s, MsgN("{1} warning ({2})", "{1} warnings ({2})", nw, {std::to_string(nw), kinds}));
  }

  // The predicted grade (issue 33): the inputs' grades weighted by the moves
  // taken from each.
  if (p.grades) s.estimated_band = p.grades->estimate;
  if (p.grades && !p.grades->discipline.empty()) {
    auto d = grades::ParseDiscipline(p.grades->discipline);
    auto sc = grades::ParseScale(p.grades->scale);
    if (d.ok() && sc.ok()) {
      std::vector<InputGradeBasis> basis = slot.input_grades;
      if (basis.size() != p.variation.inputs.size()) {
        basis.clear();
        for (const chaos::InputRoute& in : p.variation.inputs) {
          basis.push_back(SetterGradeBasis(in, *d));
        }
      }
      s.predicted = PredictGrade(p.variation, basis, *d, *sc);
    }
  }
  // The grade against the band: the predicted one, else the estimate.
  const std::string graded = s.predicted.known ? s.predicted.grade : s.estimated_band;
  const bool predicted = s.predicted.known;
  if (slot.band.empty()) {
    s.grade_part = kScoreGrade;
    if (graded.empty()) {
      Say(&s, Msg("any grade (no band asked)"));
    } else {
      Say(&s, Msg("any grade (no band asked): {1}",
                  {predicted ? Msg("predicted {1}", {graded}) : Msg("estimated {1}", {graded})}));
    }
  } else if (!p.grades || graded.empty() || p.grades->discipline.empty()) {
    const Message note = !s.predicted.note.empty() ? s.predicted.note_said
                         : p.grades                ? Message(p.grades->note)
                                                   : Message();
    if (note.empty()) {
      Say(&s, Msg("no grade prediction"));
    } else {
      Say(&s, Msg("no grade prediction: {1}", {note}));
    }
  } else {
    auto d = grades::ParseDiscipline(p.grades->discipline);
    std::optional<grades::Scale> scale;
    if (auto sc = grades::ParseScale(p.grades->scale); sc.ok()) scale = *sc;
    std::optional<int> est = s.predicted.known ? std::optional<int>(s.predicted.band)
                             : d.ok()          ? BandOf(graded, *d, scale)
                                               : std::nullopt;
    std::optional<int> lo = d.ok() ? BandOf(slot.band, *d, scale) : std::nullopt;
    std::optional<int> hi =
        d.ok() ? (slot.band_to.empty() ? lo : BandOf(slot.band_to, *d, scale)) : std::nullopt;
    const std::string band = slot.band + (slot.band_to.empty() ? "" : "-" + slot.band_to);
    if (!est || !lo || !hi) {
      Say(&s, predicted ? Msg("predicted {1}, not comparable with band {2}", {graded, band})
                        : Msg("estimated {1}, not comparable with band {2}", {graded, band}));
    } else {
      if (*hi < *lo) std::swap(*lo, *hi);
      const int off = *est < *lo ? *lo - *est : *est > *hi ? *est - *hi : 0;
      s.grade_part = off == 0 ? kScoreGrade : off == 1 ? kScoreGrade / 2 : 0.0;
      const std::vector<Message> a = {graded, std::to_string(off), band};
      if (off == 0) {
        Say(&s, predicted ? Msg("predicted {1} inside band {2}", {graded, band})
                          : Msg("estimated {1} inside band {2}", {graded, band}));
      } else {
        Say(&s, predicted ? MsgN("predicted {1} {2} band outside band {3}",
                                 "predicted {1} {2} bands outside band {3}", off, a)
                          : MsgN("estimated {1} {2} band outside band {3}",
                                 "estimated {1} {2} bands outside band {3}", off, a));
      }
    }
  }

  // The styles its moves have, in words (the style reading).
  {
    std::map<std::string, int> count;
    for (const chaos::VariedMove& m : p.variation.moves) {
      for (const std::string& st : language::ReadStyle(impl_->styles, m.text).All()) {
        if (st != "unparsed" && st != "match") ++count[st];
      }
    }
    std::vector<std::pair<int, std::string>> order;
    for (const auto& [st, n] : count) order.push_back({-n, st});
    std::sort(order.begin(), order.end());
    std::vector<Message> words;
    for (size_t k = 0; k < order.size() && k < 3; ++k) {
      const int n = -order[k].first;
      words.push_back(k == 0 ? MsgN("{1} ({2} move)", "{1} ({2} moves)", n,
                                    {Word(order[k].second), std::to_string(n)})
                             : List({Word(order[k].second), " (" + std::to_string(n) + ")"}, ""));
    }
    s.style_said = List(std::move(words), ", ");
    s.style_words = s.style_said.English();
  }

  // The slot's style.
  if (slot.style.empty()) {
    s.style_part = kScoreStyle;
    Say(&s, Msg("any style (no style asked)"));
  } else {
    for (const chaos::VariedMove& m : p.variation.moves) {
      const std::vector<std::string> all = language::ReadStyle(impl_->styles, m.text).All();
      s.style_moves += std::find(all.begin(), all.end(), slot.style) != all.end();
    }
    s.style_part = s.style_moves > 0 ? kScoreStyle : 0.0;
    Say(&s, s.style_moves > 0 ? MsgN("{1} on {2} move", "{1} on {2} moves", s.style_moves,
                                     {Word(slot.style), std::to_string(s.style_moves)})
                              : Msg("no {1} move", {Word(slot.style)}));
  }

  // Smoothness: bits per move against the inputs' own.
  std::vector<std::string> texts;
  for (const chaos::VariedMove& m : p.variation.moves) texts.push_back(m.text);
  s.bits_per_move = BitsPerMove(texts);
  double in_bits = 0.0;
  size_t in_moves = 0;
  for (const chaos::InputRoute& in : p.variation.inputs) {
    std::vector<std::string> t;
    for (const Move& m : in.route.moves) t.push_back(m.text);
    in_bits += BitsPerMove(t) * static_cast<double>(t.size());
    in_moves += t.size();
  }
  s.input_bits_per_move = in_moves ? in_bits / static_cast<double>(in_moves) : 0.0;
  const double extra = std::max(0.0, s.bits_per_move - s.input_bits_per_move);
  s.smooth_part = kScoreSmooth * std::exp2(-extra);
  Say(&s, Msg("smoothness {1} bits per move (inputs {2})",
              {Decimal(Fixed(s.bits_per_move, 2)), Decimal(Fixed(s.input_bits_per_move, 2))}));

  s.score = s.warnings_part + s.grade_part + s.style_part + s.smooth_part;
  return s;
}

void RankCandidates(std::vector<Candidate>* c) {
  std::stable_sort(c->begin(), c->end(), [](const Candidate& a, const Candidate& b) {
    if (a.score.rejected != b.score.rejected) return !a.score.rejected;
    if (a.score.in_novelty != b.score.in_novelty) return a.score.in_novelty;
    const bool aw = a.score.warnings.empty(), bw = b.score.warnings.empty();
    if (aw != bw) return aw;
    if (a.score.score != b.score.score) return a.score.score > b.score.score;
    return a.index < b.index;
  });
}

Result<std::vector<Candidate>> MakeGallery(const std::vector<chaos::InputRoute>& inputs,
                                           const chaos::VaryParams& params,
                                           const SettingRequest& setting,
                                           const CandidateSlot& slot,
                                           const GalleryOptions& options,
                                           std::string* note, Message* said) {
  if (note) note->clear();
  if (said) *said = Message();
  std::string own_note;
  if (said && !note) note = &own_note;
  if (options.rings < 0 || options.rings > kMaxGalleryRings) {
    return Status::InvalidInput("rings: between 0 and " + std::to_string(kMaxGalleryRings));
  }
  if (!(options.ring_step > 0.0) || !std::isfinite(options.ring_step)) {
    return Status::InvalidInput("ring_step: a positive number");
  }
  SB_ASSIGN_OR_RETURN(CandidateScorer scorer, CandidateScorer::Make(slot, options.model));
  static constexpr int kDirs[8][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1},
                                      {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  std::vector<Candidate> out;
  // Two ICs giving the same moves are one candidate (the first kept).
  std::set<std::vector<std::pair<Hand, std::string>>> made;
  Status first_error;
  SmoothingRequest no_smoothing;
  // The level asked first, then the others, nearest first (mix before the
  // far end).
  std::vector<Novelty> order = {options.novelty};
  if (options.novelty == Novelty::kMix) order.insert(order.end(), {Novelty::kClose, Novelty::kNew});
  if (options.novelty == Novelty::kClose) order.insert(order.end(), {Novelty::kMix, Novelty::kNew});
  if (options.novelty == Novelty::kNew) order.insert(order.end(), {Novelty::kMix, Novelty::kClose});
  if (options.max_levels < 1 || options.max_levels > 3) {
    return Status::InvalidInput("max_levels: between 1 and 3");
  }
  const size_t levels = std::min(order.size(), static_cast<size_t>(options.max_levels));
  const int want = 1 + 8 * options.rings;
  auto clean_in_level = [&](const ScanPoint& pt) {
    return pt.kept && pt.warnings == 0 && NoveltyOf(pt.new_moves, pt.moves) == options.novelty;
  };
  // The IC picker (with the setter's constraints asked): the level's grid
  // scanned for ICs whose variation lands in the level without a warning;
  // while none does, the other levels' grids too (no plan is built for a
  // scan: the gallery builds `want` plans whatever the levels scanned).
  PickerScan scan;
  size_t scanned_levels = 0;
  bool picker = setting.Search();
  if (picker) {
    std::set<std::vector<std::pair<Hand, std::string>>> seen;
    for (size_t level = 0; level < levels; ++level) {
      if (level > 0 && std::any_of(scan.points.begin(), scan.points.end(), clean_in_level)) break;
      Status st = ScanLevel(inputs, NoveltyCentre(params, order[level]), setting, options.novelty,
                            want, &seen, &scan);
      if (!st.ok()) {
        picker = false;  // BuildPlan below says why
        break;
      }
      ++scanned_levels;
    }
  }
  struct Start {
    chaos::State ic;
    int skip;
    int radius;  // the search's reach from `ic` (0: the IC picker's point, made as scanned)
  };
  std::vector<Start> starts;
  if (picker) {
    // In the level without a warning, then in it with warnings, then the
    // nearest to its band, then the rest; hands alternating by themselves
    // before hands swapped, then nearest their level's centre.
    std::vector<const ScanPoint*> pts;
    for (const ScanPoint& pt : scan.points) pts.push_back(&pt);
    auto tier = [&](const ScanPoint& pt) {
      const bool in = NoveltyOf(pt.new_moves, pt.moves) == options.novelty;
      return !pt.kept ? 3 : in && pt.warnings == 0 ? 0 : in ? 1 : 2;
    };
    std::stable_sort(pts.begin(), pts.end(), [&](const ScanPoint* a, const ScanPoint* b) {
      const int ta = tier(*a), tb = tier(*b);
      if (ta != tb) return ta < tb;
      if (ta == 2) {
        const int oa = MovesOutside(a->new_moves, a->moves, options.novelty);
        const int ob = MovesOutside(b->new_moves, b->moves, options.novelty);
        if (oa != ob) return oa < ob;
        if (a->warnings != b->warnings) return a->warnings < b->warnings;
      }
      if (a->swapped != b->swapped) return !a->swapped;
      return a->order < b->order;
    });
    for (const ScanPoint* pt : pts) {
      if (static_cast<int>(starts.size()) >= want) break;
      starts.push_back({pt->ic, pt->skip, 0});
    }
  }
  // The level's rings fill what the picker did not (and are the gallery
  // without a search).
  {
    const chaos::VaryParams centre = NoveltyCentre(params, options.novelty);
    std::vector<chaos::State> ics = {centre.var_ic};
    const double step =
        options.ring_step * (options.novelty == Novelty::kClose ? kCloseStep : 1.0);
    for (int r = 1; r <= options.rings; ++r) {
      for (const auto& d : kDirs) {
        chaos::State ic = centre.var_ic;
        ic[0] += d[0] * r * step;
        ic[1] += d[1] * r * step;
        ics.push_back(ic);
      }
    }
    for (size_t i = 0; i < ics.size() && static_cast<int>(starts.size()) < want; ++i) {
      starts.push_back({ics[i], centre.skip, setting.grid.radius});
    }
  }
  int index = 0;
  for (const Start& st : starts) {
    chaos::VaryParams p = params;
    p.var_ic = st.ic;
    p.skip = st.skip;
    SettingRequest at = setting;
    at.grid.radius = st.radius;
    SmoothingOutcome outcome;
    Result<plan::RoutePlan> plan = BuildPlan(inputs, p, at, no_smoothing, &outcome);
    if (!plan.ok()) {
      if (first_error.ok()) first_error = plan.status();
      ++index;
      continue;
    }
    std::vector<std::pair<Hand, std::string>> key;
    for (const chaos::VariedMove& m : plan->variation.moves) key.push_back({m.hand, m.text});
    if (!made.insert(std::move(key)).second) {
      ++index;
      continue;
    }
    Candidate c;
    c.score = scorer.Score(*plan);
    c.score.in_novelty = c.score.novelty == options.novelty;
    c.plan = std::move(plan).value();
    c.searched_from = st.ic;
    c.skip = p.skip;
    c.search_radius = st.radius;
    c.index = index++;
    out.push_back(std::move(c));
  }
  auto met = [&] {
    return std::any_of(out.begin(), out.end(), [&](const Candidate& c) {
      return !c.score.rejected && c.score.novelty == options.novelty;
    });
  };
  if (out.empty()) return first_error;
  RankCandidates(&out);
  const Candidate& best = out.front();
  if (note && (!met() || !best.score.warnings.empty())) {
    const Message why = NoveltyMissed(options.novelty, out, scan.points);
    if (said) *said = why;
    // Why the level asked is not met without a warning, in words a setter
    // can act on.
    int in_level = 0;
    std::string rejected_why;
    for (const Candidate& c : out) {
      if (c.score.novelty != options.novelty) continue;
      ++in_level;
      for (const std::string& r : c.score.reasons) {
        if (rejected_why.empty() && r.rfind("rejected:", 0) == 0) rejected_why = r.substr(10);
      }
    }
    const std::string level = std::string(NoveltyWords(options.novelty)) + " (novelty " +
                              NoveltyName(options.novelty) + ")";
    // What the IC picker saw, checkable: how many ICs it scanned, how many
    // met the constraints, and the share of new moves the kept variations
    // reach.
    std::string seen;
    if (picker) {
      int kept = 0, lo = -1, hi = -1, in_band = 0, clean = 0, moves = 0;
      for (const ScanPoint& pt : scan.points) {
        if (!pt.kept) continue;
        ++kept;
        moves = std::max(moves, pt.moves);
        lo = lo < 0 ? pt.new_moves : std::min(lo, pt.new_moves);
        hi = std::max(hi, pt.new_moves);
        const bool in = NoveltyOf(pt.new_moves, pt.moves) == options.novelty;
        in_band += in;
        clean += in && pt.warnings == 0;
      }
      seen = "the IC picker scanned " + std::to_string(scan.scanned) + " ICs (" +
             std::to_string(std::max(kPickRadius, setting.grid.radius)) +
             " grid steps around the centre of " +
             (scanned_levels == 1 ? std::string("the level asked")
                                  : std::to_string(scanned_levels) + " novelty levels") +
             "): " + std::to_string(scan.meeting) + " meet the setter's constraints" +
             (scan.swapped ? " (" + std::to_string(scan.swapped) + " of them once hands are swapped)"
                           : std::string()) +
             ", giving " + std::to_string(scan.points.size()) + " different variations, " +
             std::to_string(kept) + " of them pass the filter" +
             (kept ? " with " + std::to_string(lo) + " to " + std::to_string(hi) + " of " +
                         std::to_string(moves) + " moves new"
                   : std::string()) +
             (in_band ? "; " + std::to_string(in_band) + " of those are " +
                            NoveltyWords(options.novelty) + ", " +
                            (clean ? std::to_string(clean) + " without a warning"
                                   : std::string("each with a warning"))
                      : "; none is " + std::string(NoveltyWords(options.novelty)));
    }
    if (met()) {
      *note = "every candidate " + level + " carries a warning (" + best.score.warnings.front() +
              "): check it at the wall, or try another novelty or other inputs" +
              (seen.empty() ? "" : " (" + seen + ")");
    } else {
      *note = "no candidate " + level + " passes the filter: " +
              (!seen.empty() ? seen
               : in_level == 0
                   ? "none of the " + std::to_string(out.size()) +
                         " candidates made lands there with these inputs"
                   : std::to_string(in_level) + " land there but are rejected (" + rejected_why +
                         ")") +
              "; the best shown is " + NoveltyWords(best.score.novelty) + " (" +
              std::to_string(best.score.new_moves) + " of " + std::to_string(best.score.moves) +
              " moves new): try novelty " + NoveltyName(best.score.novelty) + " or other inputs";
    }
    // The setter's sentence first, the picker's figures after it.
    *note = why.English() + ". Details: " + *note;
  }
  return out;
}

int GalleryPlanCount(const GalleryOptions& options) {
  // Issue 33: the other levels are scanned by the IC picker, not built: a
  // gallery builds one plan per IC it shows, whatever the levels scanned.
  return 1 + 8 * options.rings;
}

Result<GalleryChoice> ChooseFromGallery(const std::vector<chaos::InputRoute>& inputs,
                                        chaos::VaryParams* params,
                                        SettingRequest* setting,
                                        const CandidateSlot& slot,
                                        const GalleryOptions& options) {
  GalleryChoice out;
  SB_ASSIGN_OR_RETURN(out.candidates,
                      MakeGallery(inputs, *params, *setting, slot, options, &out.note,
                                  &out.note_said));
  out.count = static_cast<int>(out.candidates.size());
  for (const Candidate& c : out.candidates) out.kept += c.score.rejected ? 0 : 1;
  params->var_ic = out.candidates.front().searched_from;
  params->skip = out.candidates.front().skip;
  setting->grid.radius = out.candidates.front().search_radius;
  return out;
}

void ApplySetterPreset(chaos::VaryParams* params, SettingRequest* request, bool keep_max_repeat) {
  request->constraints.keep_start = true;
  request->constraints.keep_finish = true;
  request->constraints.alternate_hands = true;
  request->drop_inner_finishes = true;
  request->drop_inner_starts = true;
  if (!keep_max_repeat) params->mapping.max_repeat = kSetterMaxRepeat;
}

std::string GalleryReport(const std::vector<Candidate>& candidates) {
  std::string s;
  int rank = 0;
  for (const Candidate& c : candidates) {
    const chaos::State& ic = c.plan.variation.params.var_ic;
    s += std::to_string(++rank) + ". IC (" + FormatDouble(ic[0]) + ", " + FormatDouble(ic[1]) +
         ", " + FormatDouble(ic[2]) + ") score " + Fixed(c.score.score, 1) +
         (c.score.rejected ? " REJECTED" : "") + ": ";
    for (size_t i = 0; i < c.score.reasons.size(); ++i) {
      s += (i ? "; " : "") + c.score.reasons[i];
    }
    s += "\n";
  }
  return s;
}

}  // namespace sb::app
