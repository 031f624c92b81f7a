// The setter's workflow (issues 13, 15, 16; docs/setting.md) as a service for
// the CLI and the web app: a variation made under the setter's constraints
// (IC search), with the facts of its input moves (crux flags, difficulty
// estimates), its warnings, difficulty profile and grades.
//
//   app::SettingRequest req;                 // plan::SetterOptions; the CLI:
//   req.constraints.keep_start = true;       // cli::ResolveSettingOptions
//   auto out = app::VaryWithSetting(std::move(inputs), vary_params, req);
//   // out->variation (the plan's), out->search (IC used, distance, constraints),
//   // out->warnings, out->facts (crux flags and estimates per input move)
//
// Plans are made by app::BuildPlan (app/variations.h), which calls these and
// fills every annotation of plan::RoutePlan.
#ifndef SB_APP_SETTING_H_
#define SB_APP_SETTING_H_

#include <cstdint>
#include <optional>
#include <vector>

#include "base/status.h"
#include "chaos/constraints.h"
#include "chaos/search.h"
#include "chaos/variation.h"
#include "grades/scale.h"
#include "language/symbols.h"
#include "plan/plan.h"
#include "plan/warnings.h"

namespace sb::app {

// What the setter asks for: constraints, search grid, match rule, smoothing
// method (plan/plan.h). Its JSON form is plan::ParametersJson /
// plan::SetterOptionsFromJson, the one codec of these fields.
using SettingRequest = plan::SetterOptions;

// Budgets of one server request's IC search (POST /api/variations), checked
// before the search starts; the CLI has only the engine's limits
// (chaos::SearchGrid::Validate).
//
// The reach: the CLI's default radius, 100 grid steps (10 units at the
// default spacing: twice the half-width of the paper's figure-4 landscape).
inline constexpr int kMaxRequestSearchRadius = 100;
// The work: candidate ICs (the grid's bounding box, an upper bound of the
// ICs visited) times the trajectory steps of each (skip + moves). The
// default search of a 30-move variation (201^2 ICs x 30 steps = 1.2 M) takes
// about 0.1 s on this project's 2-core machine; 12 M steps (about a second of
// CPU in the worst case, when no IC qualifies) keeps one request from holding
// a core for longer, e.g. a 100-step transient or 300 moves at the default
// radius, or a 2,000-move variation at radius 30.
inline constexpr uint64_t kMaxRequestSearchSteps = 12'000'000;

// The budget check of a search for a variation of `moves` moves with
// `params`: kInvalidInput naming the field ("search_radius: ...") when the
// radius or the work is over the budgets above. OK when no search is asked.
Status CheckRequestSearchBudget(const SettingRequest& request, const chaos::VaryParams& params,
                                int moves);

// kInvalidInput when `request` asks what `inputs` cannot give: for token
// sequences (chaos/tokens.h) alternate-hands (no hands), a crux window (no
// cruxes) and the grammar's match rule (no moves). Errors name the option as
// a field ("alternate_hands: ..."); callers prefix or rename. Pure.
Status CheckRequestForInputs(const SettingRequest& request,
                             const std::vector<chaos::InputRoute>& inputs);

// A variation made with the setter's request. Value type.
struct SettingOutcome {
  chaos::Variation variation;
  // Set when a constraint was asked for (the IC search ran); its `variation`
  // member is moved into `variation` above.
  std::optional<chaos::SearchResult> search;
  plan::PlanWarnings warnings;
  chaos::MoveFacts facts;  // crux flags (Move::crux) and difficulty estimates per input move
};

// The input moves' facts: crux flags from Move::crux; estimates from the
// bundled difficulty model (empty when it is missing, and for token
// sequences); into `is_match` the grammar's match flags when `match_grammar`
// (else it is emptied). `lang` (may be null: loaded when needed) reads the
// moves. Errors: the grammar cannot be loaded (kNotFound), or the model file
// is damaged. Thread-safe when `lang` is null or owned by the caller's thread.
Result<chaos::MoveFacts> InputFacts(const std::vector<chaos::InputRoute>& inputs,
                                    bool match_grammar, std::vector<bool>* is_match,
                                    language::MoveLanguage* lang = nullptr);

// Removes from every input but the last the finish moves that end it
// (plan::IsFinishMoveText: "jug finish", "top out", "match finish"...) and
// a match on the finish hold after them (plan::IsMatchOnlyText: "dyno to
// finishing jug" then "match"), keeping at least one move of each input; token sequences are left alone.
// Returns the number of moves removed. VaryWithSetting calls it when the
// request asks drop_inner_finishes. Pure.
int DropInnerFinishes(std::vector<chaos::InputRoute>* inputs);

// Removes the start move (the first) of every input but the first, keeping
// at least one move of each, and counts it in InputRoute::first_move so
// reports keep the route file's numbering: joined routes otherwise carry an
// inner route's start (two hands on a start hold) into the middle of the
// variation (issue 22, the "start-mid-route" warning). Where the input before
// ends with the hand the input now starts with, the input's hands are
// mirrored (L <-> R), so the join alternates as the inputs do. Token sequences are
// left alone. Returns the number of moves removed. VaryWithSetting calls it
// when the request asks drop_inner_starts. Pure.
int DropInnerStarts(std::vector<chaos::InputRoute>* inputs);

// Varies `inputs` with the setter's request: with no constraint asked,
// exactly chaos::Vary (with the match rule); otherwise
// chaos::SearchVariation from params.var_ic. Warnings are computed either
// way. Errors: those of CheckRequestForInputs (kInvalidInput), InputFacts,
// Vary and SearchVariation (kNotFound naming the constraint that could not be
// met). Deterministic; thread-safe as InputFacts.
Result<SettingOutcome> VaryWithSetting(std::vector<chaos::InputRoute> inputs,
                                       const chaos::VaryParams& params,
                                       const SettingRequest& request,
                                       language::MoveLanguage* lang = nullptr);

// The grades of a plan of routes (issue 15): each input's grade as typed, and
// the variation's estimated grade from its moves with the bundled estimator
// (data/models/grades.sbg, loaded once per process) in the discipline of the
// inputs (their type: or grade: lines; the first input's when they differ,
// noted) and the scale of the first input graded in it. Where no estimate
// can be made, `note` says why (no discipline, no estimator). `profile`
// gives the per-move estimates an estimator trained with them needs. Never
// fails; deterministic. Not thread-safe for one `lang`.
plan::PlanGrades GradesOf(const chaos::Variation& variation,
                          const plan::DifficultyProfile& profile, language::MoveLanguage& lang);

// The bundled grade estimator's mean (on `d`'s axis) for the moves of
// `route`, with per-move difficulty estimates `difficulty` (empty: the
// bundled difficulty model's, when the estimator needs them). nullopt when
// the estimator, its model of `d` or the moves cannot be had (issue 33: the
// moves model's part of a predicted grade, app/grade_prediction.h). Not
// thread-safe for one `lang`.
std::optional<double> EstimatedGradeMean(const Route& route, std::vector<double> difficulty,
                                         grades::Discipline d, language::MoveLanguage& lang);

}  // namespace sb::app

#endif  // SB_APP_SETTING_H_
