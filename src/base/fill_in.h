// Placeholders of a message pattern filled in: the one rule that the app's
// messages (app/message.h), the card's translated lines (plan/card.cc) and the
// pages' Fmt (web/i18n.h) share.
#ifndef SB_BASE_FILL_IN_H_
#define SB_BASE_FILL_IN_H_

#include <string>
#include <string_view>
#include <vector>

namespace sb {

// `pattern` with each "{1}".."{9}" replaced by args[0]..args[8]; a placeholder
// past the end of `args` stays as written, any other text is copied. Pure.
inline std::string FillIn(std::string_view pattern, const std::vector<std::string>& args) {
  std::string out;
  out.reserve(pattern.size());
  for (size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] == '{' && i + 2 < pattern.size() && pattern[i + 1] >= '1' &&
        pattern[i + 1] <= '9' && pattern[i + 2] == '}') {
      const size_t k = static_cast<size_t>(pattern[i + 1] - '1');
      if (k < args.size()) {
        out += args[k];
      } else {
        out += pattern.substr(i, 3);
      }
      i += 2;
      continue;
    }
    out += pattern[i];
  }
  return out;
}

}  // namespace sb

#endif  // SB_BASE_FILL_IN_H_
