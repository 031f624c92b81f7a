// The messages of the static scripts (web/*.js) by script, for the JSON block
// the pages render (web/script_messages.h). Each array lists its script's
// tr('...') messages as N_() ids: the catalog check (tests/i18n_check.py)
// fails when a script's tr() message is missing here, and extracts these ids
// into po/*.po. A script that translates a message it does not spell out
// (tr(r.action)) has its possible values listed here by hand.
#include "web/script_messages.h"

#include <nlohmann/json.hpp>

#include "web/i18n.h"

namespace sb::web {

namespace {

// A count's message of a script (trn('{1} route', '{1} routes', n, ...)).
struct PluralMessage {
  const char* one;
  const char* many;
};
// Marks a plural message for extraction (xgettext keyword NN_:1,2).
#define NN_(one, many) PluralMessage{one, many}

// web/app.js
const char* const kAppJs[] = {
    N_("error {1}"),
    N_("Variation IC"),
    N_("Reference IC"),
    N_("Max repeat"),
    N_("Skip"),
    N_("Step"),
    N_("System parameters"),
    N_("Mask"),
    N_("System"),
    N_("Integrator"),
    N_("Mapping"),
    N_("Preset"),
    N_("Routes"),
    N_("Visibility"),
    N_("Keep start"),
    N_("Keep finish"),
    N_("Crux window"),
    N_("Alternate hands"),
    N_("Match moves"),
    N_("Target effect"),
    N_("Target change"),
    N_("Smoothing method"),
    N_("No variation IC within {1} grid steps of your variation IC meets every constraint: \"{2}\" could not be met. Try a wider crux window, fewer constraints or another variation IC."),
    N_("Sign-up failed"),
    N_("Account made; please log in."),
    N_("Log-in failed"),
    N_("in the wall's scale \"{1}\""),
    N_("left hand"),
    N_("right hand"),
    N_("crux"),
    N_("not understood as a move"),
    N_("style: {1}"),
    N_("unknown word \"{1}\": did you mean \"{2}\"?"),
    N_("not a move: start with L or R"),
    N_("metadata"),
    N_("moves follow"),
    N_("comment"),
    N_("description"),
    N_("line {1}: {2}"),
    N_("line {1} of the moves: {2}"),
    N_("not saved: see the text"),
    N_("not saved: see the field \"{1}\""),
    N_("Someone else saved this route first (now revision {1}, state {2})."),
    N_("Their changes are now in the form: {1}."),
    N_("Yours are kept: {1}."),
    N_("Changed by both, yours kept (theirs below): {1}."),
    N_("Their text is below. Save again to save the form as it is now."),
    N_("name"),
    N_("grade"),
    N_("hold colour"),
    N_("wall"),
    N_("circuit"),
    N_("state"),
    N_("date"),
    N_("notes"),
    N_("moves"),
    N_("who can see it"),
    N_("other header lines"),
    N_("not saved: changed meanwhile"),
    N_("Delete this route?"),
    N_("Move up"),
    N_("Move down"),
    N_("Remove"),
    N_("Variation of the chosen routes"),
    N_("Variation of {1}"),
    N_("Variation of {1} and {2}"),
    N_("Variation of {1}, {2} and {3} more"),
    N_("private"),
    N_("Add"),
    N_("Add {1}"),
    N_("{1} of {2} moves change"),
    N_("{1} (mean distance)"),
    N_("warm = little variation, cold = much"),
    N_("{1} moves; axes {2} (right), {3} (up)"),
    N_("IC {1}: {2} of {3} moves change; change {4}"),
    N_("computing…"),
    N_("no map"),
    N_("Hover:"),
    N_("Chosen:"),
    N_("no candidates"),
    N_("{1} moves change, change {2}"),
    N_("Log in first to generate a variation."),
    N_("Choose at least one route."),
    N_("Generating…"),
    N_("You made this variation before from the same routes and parameters: here it is. Tick \"Make a new copy\" on the vary page for a second one."),
    N_("The setter's preset: the best of {1} candidates ({2} kept by the filter), score {3}: {4}."),
    N_("{1} imported"),
    N_("{1} imported into {2}"),
    N_("{1} imported as your own routes"),
    N_("Open {1}"),
    N_("Choose both files."),
    N_("Importing…"),
    N_("{1} routes imported, {2} notes"),
    N_("draft"),
    N_("planned"),
    N_("set"),
    N_("stripped"),
};

// web/climbers.js
const char* const kClimbersJs[] = {
    N_("error {1}"),
    N_("Thank you! Saved. You can change your answers any time."),
    N_("Save changes"),
    N_("Thank you! Your answers are saved."),
    N_("variation"),
    N_("instrument: choose a file"),
    N_("Accepted (reload to see the numbers)."),
    N_("Discarded."),
};

// web/gym_import.js
const char* const kGymImportJs[] = {
    N_("(none)"),
    N_("{1} new, {2} changed, {3} no longer in the list"),
    N_(": strip them?"),
    N_("({1} unchanged)"),
    N_("New sectors: {1}."),
    N_("Paste a list or choose a file."),
    N_("Reading…"),
    N_("{1} created, {2} updated, {3} stripped, {4} left as they were"),
    N_("new"),
    N_("changed"),
    N_("missing"),
    N_("same"),
    N_("error"),
};

// web/gyms.js
const char* const kGymsJs[] = {
    N_("Not done: someone changed these routes first. They are now: {1}. Reload the page to see them, then try again."),
    N_("none"),
    N_("Someone else saved this first (now revision {1}). It is now: {2}. Your changes are still here: save again to apply yours over theirs, or reload to take theirs."),
    N_("Failed ({1})"),
    N_("Drafts of others left as they are: {1}."),
    N_("Routes this page did not show, left as they are: {1}."),
    N_("Changed: {1}."),
};

// web/logbook.js
const char* const kLogbookJs[] = {
    N_("error {1}"),
    N_("Tap flash, send or attempt first."),
    N_("Tick updated: {1}"),
    N_("Ticked: {1}"),
    N_("(held for the setters to check)"),
    N_("80%: {1} to {2}"),
    N_("Accepted."),
    N_("Discarded."),
};

// web/setting_day.js
const char* const kSettingDayJs[] = {
    N_("Planned:"),
    N_("route {1}"),
    N_("card"),
    N_("tag"),
    N_("Failed ({1})"),
};

// The count messages of web/app.js and web/climbers.js (trn()).
const PluralMessage kAppJsPlurals[] = {
    NN_("{1} move", "{1} moves"),
    NN_("{1} route", "{1} routes"),
};
const PluralMessage kClimbersJsPlurals[] = {
    NN_("{1} route", "{1} routes"),
};

template <size_t N>
std::string Block(std::string_view lang, const char* const (&ids)[N]) {
  return ScriptMessages(lang, std::span<const char* const>(ids, N));
}

// The block of `ids` with the count messages `plurals` added, each as its
// forms for 1, for many (2) and for 0: ["{1} Route", "{1} Routen", "{1} Routen"]
// (the scripts' trn() picks by n; English, German and French differ only there).
template <size_t N, size_t P>
std::string Block(std::string_view lang, const char* const (&ids)[N],
                  const PluralMessage (&plurals)[P]) {
  std::string block = Block(lang, ids);
  if (block.empty()) return block;
  nlohmann::json forms = nlohmann::json::object();
  for (const PluralMessage& p : plurals) {
    forms[p.one] = {TrN(lang, p.one, p.many, 1), TrN(lang, p.one, p.many, 2),
                    TrN(lang, p.one, p.many, 0)};
  }
  std::string text = forms.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string safe;
  for (char c : text) safe += c == '<' ? std::string("\\u003c") : std::string(1, c);
  // Joined into the one object: `{...}` + `{...}` -> `{..., ...}`.
  const size_t close = block.rfind('}');
  if (close == std::string::npos || safe.size() <= 2) return block;
  const bool empty = block.find("{}") != std::string::npos && block.find("{}") + 1 == close;
  return block.substr(0, close) + (empty ? "" : ",") + safe.substr(1, safe.size() - 2) +
         block.substr(close);
}

}  // namespace

std::string AppScriptMessages(std::string_view lang) { return Block(lang, kAppJs, kAppJsPlurals); }
std::string ClimbersScriptMessages(std::string_view lang) {
  return Block(lang, kClimbersJs, kClimbersJsPlurals);
}
std::string ImportScriptMessages(std::string_view lang) { return Block(lang, kGymImportJs); }
std::string GymsScriptMessages(std::string_view lang) { return Block(lang, kGymsJs); }
std::string LogbookScriptMessages(std::string_view lang) { return Block(lang, kLogbookJs); }
std::string SettingDayScriptMessages(std::string_view lang) { return Block(lang, kSettingDayJs); }

}  // namespace sb::web
