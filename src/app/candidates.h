// Candidates for a setting day's slot (issue 22): the filter and the score a
// setter's gallery ranks variations by, and a gallery of variations made at
// several ICs near the one asked for (what `strangebeta vary --preset setter`
// prints the best of). How the score is made: docs/setting.md, "The setter's
// preset and the candidate score".
//
//   app::CandidateSlot slot{"V3", "V5", "crimp"};
//   auto scorer = app::CandidateScorer::Make(slot);      // grammar + Markov model
//   app::CandidateScore s = scorer->Score(plan);         // plan from app::BuildPlan
//   s.rejected, s.score, s.reasons
//
//   auto gallery = app::MakeGallery(inputs, params, request, slot, {});
//   (*gallery)[0]: the best candidate (plan, score, the IC it was searched from)
#ifndef SB_APP_CANDIDATES_H_
#define SB_APP_CANDIDATES_H_

#include <memory>
#include <string_view>
#include <string>
#include <vector>

#include "app/grade_prediction.h"
#include "app/message.h"
#include "app/setting.h"
#include "base/status.h"
#include "chaos/variation.h"
#include "plan/plan.h"
#include "plan/warnings.h"

namespace sb::app {

// What a slot asks of its candidates. Empty fields ask nothing.
struct CandidateSlot {
  // The grade band as the gym writes it on its tags ("V3", "6B+", "5.10a"),
  // read in the candidates' discipline; `band_to` (optional) makes it a
  // range band..band_to of whole bands (docs/grades.md, "Difficulty and
  // bands").
  std::string band;
  std::string band_to;
  // A style name (language/styles.h, docs/setting.md "Style names").
  std::string style;
  // Issue 33: the grades of the gallery's inputs the predicted grade rests
  // on (app/grade_prediction.h), one per input in order: a setting day's
  // ascent grades where the gym has ticks. Empty: each input's setter's
  // grade (its grade: line).
  std::vector<InputGradeBasis> input_grades;
  // kInvalidInput naming the field: an unknown style, band_to without band.
  // Grades are read when scoring (they need the candidates' discipline).
  Status Validate() const;
};

// The weights of the score's parts, out of 100 (docs/setting.md). No
// warning at all earns the first in full (each warning shrinks it:
// weight / (1 + warnings)); the predicted grade (else the estimated one)
// inside the band the second
// (one band off: half); the slot's style on at least one move the third;
// smoothness the fourth (in full when the candidate's bits per move under
// the Markov model are at most its inputs', halved for each bit more).
inline constexpr double kScoreNoWarnings = 30.0;
inline constexpr double kScoreGrade = 30.0;
inline constexpr double kScoreStyle = 20.0;
inline constexpr double kScoreSmooth = 20.0;

// The filter of a gallery: a candidate is rejected when its plan warns of a
// finish or top-out move at the start or mid-route (finish-mid-route), or a
// run of one move or one hand longer than its inputs have (repeated-move,
// same-hand; plan::Warn). With `excuse_one_hand_pair` (keep-start,
// keep-finish and alternate-hands asked and the ends' hands of different
// parity: chaos::AlternateHands leaves one same-hand pair), a single
// same-hand warning of two moves is not a rejection (it stays a warning).
// Appends to `why` one phrase per reason (and to `said` the same as
// messages, for the pages' languages). Pure.
bool RejectedByFilter(const plan::PlanWarnings& warnings, std::vector<std::string>* why,
                      bool excuse_one_hand_pair = false, std::vector<Message>* said = nullptr);

// "A variation a setter could set" changes its inputs (issue 22). A move of
// a candidate is new when it does not follow its predecessor in any input
// (the first move: when no input starts with it); moves compare by hand and
// text. A candidate whose moves equal one input's is rejected ("same as
// input NAME"), and so is one with fewer than kMinNewMoves new moves: the
// inputs one after the other (their ends dropped or kept) make one new move,
// where the second input begins, so a candidate must change more than that.
inline constexpr int kMinNewMoves = 2;

// How much `moves` change `inputs` (the rule above; plan::NewMoveCount, the
// one change count plans, galleries and setting days show). Pure.
using MoveChange = plan::MoveChange;
MoveChange ChangeAgainstInputs(const std::vector<chaos::VariedMove>& moves,
                               const std::vector<chaos::InputRoute>& inputs);

// Novelty the setter chooses (issue 33), the paper's effect/change picker in
// three words: the share of a candidate's moves new against its inputs
// (ChangeAgainstInputs) is below a third at `close`, a third to two thirds
// at `mix` (the default), above two thirds at `new`.
enum class Novelty { kClose, kMix, kNew };
// "close", "mix", "new".
const char* NoveltyName(Novelty n);
// A setter's words: "close to its inputs", "a mix of its inputs and new
// moves", "mostly new".
const char* NoveltyWords(Novelty n);
// Reads a level name (case-blind); kInvalidInput "novelty: ..." naming the
// three otherwise. Pure.
Result<Novelty> ParseNovelty(std::string_view text);
// The level a share of new_moves of moves falls in (no moves: close). Pure.
Novelty NoveltyOf(int new_moves, int moves);

// A candidate's score and why. Value type.
struct CandidateScore {
  // By RejectedByFilter, by too little change (kMinNewMoves), or a
  // constraint of its search not held (but
  // alternate-hands, whose one same-hand pair the kept ends demand: a
  // reason, and that pair's same-hand warning excused by the filter).
  bool rejected = false;
  double score = 0.0;                 // 0..100, the sum of the parts below
  double warnings_part = 0.0, grade_part = 0.0, style_part = 0.0, smooth_part = 0.0;
  std::vector<std::string> reasons;   // words, one per part (and the filter's)
  // The same reasons as messages (reasons[i] == why[i].English()), which the
  // pages translate by id (issue 32).
  std::vector<Message> why;
  std::vector<std::string> warnings;  // "kind: message", as the plan shows them
  std::string estimated_band;         // the plan's estimated grade ("" = none)
  // Issue 33: the grade predicted from its inputs' grades (what the grade
  // part scores when known; else the estimate above).
  PredictedGrade predicted;
  // The styles read from its moves, in words: "crimp (5 moves), sidepull
  // (3), dyno (1)"; the three most frequent ("" = none read).
  std::string style_words;
  Message style_said;                 // the same as a message (issue 32)
  int style_moves = 0;                // moves having the slot's style
  int new_moves = 0;                  // moves new against its inputs (MoveChange)
  int moves = 0;                      // its moves
  Novelty novelty = Novelty::kClose;  // the level its share of new moves falls in
  // The level asked of the gallery (GalleryOptions::novelty), set by
  // MakeGallery: whether this candidate is in it (ranked first when kept).
  bool in_novelty = true;
  double bits_per_move = 0.0;         // under the Markov model
  double input_bits_per_move = 0.0;   // the inputs' own, each route scored alone
};

// Scores plans for one slot. Holds the grammar and the Markov model: not
// thread-safe (make one per thread).
class CandidateScorer {
 public:
  // `model`: a Markov model file made from move symbols, or "default" (the
  // bundled data/models/default.sbm). Errors: the slot's (Validate), the
  // grammar or the model cannot be loaded or read moves (kNotFound,
  // kInvalidInput).
  static Result<CandidateScorer> Make(const CandidateSlot& slot,
                                      const std::string& model = "default");
  CandidateScorer(CandidateScorer&&) noexcept;
  CandidateScorer& operator=(CandidateScorer&&) noexcept;
  ~CandidateScorer();

  // The score of a plan made by app::BuildPlan (its warnings and grades are
  // read; a plan without warnings is scored from plan::Warn of its
  // variation). Deterministic.
  CandidateScore Score(const plan::RoutePlan& plan);

  // Bits per move of move texts under the model (-log2 P / moves); 0 for
  // none.
  double BitsPerMove(const std::vector<std::string>& moves);

 private:
  struct Impl;
  explicit CandidateScorer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// One candidate of a gallery.
struct Candidate {
  plan::RoutePlan plan;
  CandidateScore score;
  chaos::State searched_from{};  // the IC its search started at
  int skip = 0;                  // the transient it was made with (its level's)
  // The reach of the IC search it was made with, in grid steps: 0 for an
  // IC the picker chose (the variation scanned there, exactly), the
  // request's for the rings' ICs. app::BuildPlan from `searched_from` and
  // `skip` with this radius makes it again.
  int search_radius = 0;
  int index = 0;                 // its place in the order the ICs were tried
};

// Orders candidates: kept before rejected, then those in the novelty level
// asked (CandidateScore::in_novelty), then those without any warning, then
// higher score (smoothness, the slot's grade and style), then lower index.
// Stable and deterministic.
void RankCandidates(std::vector<Candidate>* candidates);

// How a gallery is made.
struct GalleryOptions {
  // How many candidates: 1 + 8·`rings` ICs (the ICs of the rings below, and
  // with a search the IC picker's, MakeGallery).
  int rings = 1;
  double ring_step = 1.0;
  std::string model = "default";  // for the smoothing part
  // The level asked. With the setter's constraints (a search), its ICs are
  // picked as the paper's IC picker does (section 7: ICs chosen for the
  // effect asked): the grid around the level's centre (NoveltyCentre) is
  // scanned with the constraints, and the ICs whose variation lands in the
  // level without a warning are taken, nearest the centre first; while none
  // does, the other levels' grids are scanned too (nearest level first), and
  // the ICs nearest the level's band are taken. What the picker did not fill
  // (and the whole gallery without a search): the level's centre and the 8
  // points of each ring at `ring_step`, 2·`ring_step`, ... (half that at
  // `close`; x-y plane, ring by ring, each ring from +x counter-clockwise).
  Novelty novelty = Novelty::kMix;
  // Levels whose grids the picker may scan, the level asked first (1..3).
  // A scan builds no plan (about 10 ms), so it is not charged.
  int max_levels = 3;
};
// Where a level's ICs are centred, the way the paper's picker moves away
// from the reference IC for more change: `mix` is the IC asked (the default
// preset's, 3 units from the reference), `close` the point a third of the way
// from the reference to it (a variation trajectory near the reference maps
// most moves onto themselves), `new` the IC asked pushed away from the
// reference to three times the distance, with a transient (skip) of 100
// steps (the "more" preset's) so the trajectories decorrelate. Pure.
chaos::VaryParams NoveltyCentre(const chaos::VaryParams& params, Novelty n);
// At most this many rings: 1 + 8·rings plans are built, each with its own
// IC search (about 0.1 s each on the project's 2-core machine).
inline constexpr int kMaxGalleryRings = 4;

// Builds a plan (app::BuildPlan with `setting`; at the picker's ICs with a
// search radius of 0, Candidate::search_radius) at each candidate IC, drops
// those whose IC search fails and duplicates (the same moves, hands
// included, from two ICs: the first kept), scores the rest for `slot` and
// ranks them (RankCandidates).
// Errors: bad options (kInvalidInput), the scorer's, and when no candidate
// could be made, the first candidate's error. Deterministic.
// `*note` (optional) says, in words, when the level asked could not be met
// without a warning and why ("" otherwise): with the IC picker, how many ICs
// it scanned, how many meet the constraints, and the share of new moves the
// variations passing the filter reach (so a setter sees the inputs cannot
// give the level, and a reader can check it with the same scan).
// `*said` (optional) says the same in a setter's words, translated by id
// (empty when the level is met): "No variation of these routes changes more
// than two thirds of the moves within the setter's rules (the most changed:
// 9 of 18); showing the best of the others instead (7 of 18 moves
// changed)", or "The variations of these routes that are mostly new all
// have a start hold mid-route; ...". `*note` begins with it.
Result<std::vector<Candidate>> MakeGallery(const std::vector<chaos::InputRoute>& inputs,
                                           const chaos::VaryParams& params,
                                           const SettingRequest& setting,
                                           const CandidateSlot& slot,
                                           const GalleryOptions& options,
                                           std::string* note = nullptr,
                                           Message* said = nullptr);

// The gallery's best, as the setter's preset uses it (`vary --preset setter`
// and the web's "preset": "setter": one step for both). Value type.
struct GalleryChoice {
  std::vector<Candidate> candidates;  // ranked (RankCandidates); the first is chosen
  int rank = 1;                       // the chosen one's rank (always the best)
  int count = 0;                      // candidates made (duplicates dropped)
  int kept = 0;                       // of them, kept by the filter
  std::string note;                   // MakeGallery's (the level not met, why)
  Message note_said;                  // the same in a setter's words (MakeGallery's `said`)
};
// The plans a gallery with `options` builds at most (its ICs: 1 + 8 per
// ring; the IC picker's scans of other levels build none), what a caller
// charges to a work budget before the work starts. Pure.
int GalleryPlanCount(const GalleryOptions& options);
// Makes the gallery (MakeGallery with `slot` and `options`) from `*params`
// and `*setting`, sets params->var_ic (and skip) to the IC the best
// candidate's search started at and setting->grid.radius to its search's
// reach (Candidate::search_radius), so app::BuildPlan with `*params` and
// `*setting` rebuilds that candidate and a stored variation with those
// parameters rebuilds the same. Errors: MakeGallery's. Deterministic.
Result<GalleryChoice> ChooseFromGallery(const std::vector<chaos::InputRoute>& inputs,
                                        chaos::VaryParams* params,
                                        SettingRequest* setting,
                                        const CandidateSlot& slot,
                                        const GalleryOptions& options);

// The setter's preset (`vary --preset setter`) on top of the default
// preset's parameters: keep-start, keep-finish and alternate-hands (hand
// swaps where no IC alternates, the setters' own fix) and drop-inner-finishes
// (no input's finish carried mid-route) and drop-inner-starts (no inner
// input's start move mid-route) on `request`, and the
// paper's max-repeat 1 (no source move twice in a row) on `params` unless
// `keep_max_repeat` (the caller gave one). Pure.
inline constexpr int kSetterMaxRepeat = 1;
void ApplySetterPreset(chaos::VaryParams* params, SettingRequest* request,
                       bool keep_max_repeat = false);

// The text a CLI prints after the best plan: one line per candidate, rank,
// IC, score, kept/rejected and the reasons. Pure.
std::string GalleryReport(const std::vector<Candidate>& candidates);

}  // namespace sb::app

#endif  // SB_APP_CANDIDATES_H_
