// Hold and tape colours as gyms write them (issue 32): the one colour table.
// Names in English, German and French ("yellow", "gelb", "jaune"; "grün" or
// "gruen"; "bleue"), a phrase whose last known colour word counts ("light
// blue", "bleu clair", "blue tape"), German compounds with hell/dunkel
// ("hellblau"), and CSS hex codes ("#36c", "#3366cc"). Anything else is no
// colour: the API refuses it with the nearest names (CheckColour), and a
// tag never prints it as an empty swatch.
//
//   sb::plan::ColourSwatch("Gelb")        -> Rgb{1.0, 0.87, 0.0}
//   sb::plan::ColourName("jaune")         -> "yellow"
//   sb::plan::ColourLabel("#ffdd00")      -> "yellow (#ffdd00)"
//   sb::plan::ColourSuggestions("gelbb")  -> {"gelb", ...}
#ifndef SB_PLAN_COLOUR_H_
#define SB_PLAN_COLOUR_H_

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"

namespace sb::plan {

// A colour swatch: RGB in [0, 1].
struct Rgb {
  double r = 0, g = 0, b = 0;
};

// The swatch of a colour as gyms write it (see above; case ignored, German
// and French letters included). nullopt for anything else. Pure.
std::optional<Rgb> ColourSwatch(const std::string& colour);
// The English name of a known colour ("gelb" -> "yellow"; a hex code: the
// nearest named colour), "" for an unknown one. Pure.
std::string ColourName(const std::string& colour);
// What a page or tag prints beside the swatch: the colour as written, and
// for a hex code the nearest name first ("yellow (#ffdd00)"). Pure.
std::string ColourLabel(const std::string& colour);
// The known names (every language) nearest to `text` by edit distance, at
// most `n`, nearest first (ties in the table's order). Pure.
std::vector<std::string> ColourSuggestions(std::string_view text, size_t n = 3);
// Ok for "" (no colour) and every known colour; else kInvalidInput
// `field: "gelbb" is not a colour name or #rgb/#rrggbb code (did you mean
// gelb, gelb?)`. Pure.
Status CheckColour(std::string_view field, const std::string& colour);
// Every name the table knows (English, German, French), for docs and forms.
const std::vector<std::string>& KnownColourNames();

}  // namespace sb::plan

#endif  // SB_PLAN_COLOUR_H_
