#include "app/limits.h"

#include <string>

namespace sb::app {

namespace {

std::string TooLong(const std::string& field, size_t max, size_t has) {
  return field + ": at most " + std::to_string(max) + " characters (this one has " +
         std::to_string(has) + ")";
}

}  // namespace

size_t Utf8Chars(std::string_view s) {
  size_t n = 0;
  for (unsigned char c : s) n += (c & 0xC0) != 0x80;
  return n;
}

Status CheckRouteLimits(const Route& route, const RouteLimits& limits, std::string_view file) {
  if (route.moves.size() > static_cast<size_t>(limits.max_moves)) {
    return Status::InvalidInput("moves: at most " + std::to_string(limits.max_moves) +
                                " per route (this one has " + std::to_string(route.moves.size()) +
                                ")");
  }
  size_t description = 0;
  int meta_lines = 0;
  for (const HeaderLine& h : route.header) {
    if (h.key.empty()) {
      description += Utf8Chars(h.value) + 1;
      continue;
    }
    ++meta_lines;
    size_t n = Utf8Chars(h.value);
    bool name = h.key == "name";
    size_t max = name ? limits.max_name_chars : limits.max_meta_chars;
    if (n > max) return Status::InvalidInput(TooLong(h.key.substr(0, 40), max, n));
  }
  if (meta_lines > limits.max_meta_lines) {
    return Status::InvalidInput("metadata: at most " + std::to_string(limits.max_meta_lines) +
                                " lines (this one has " + std::to_string(meta_lines) + ")");
  }
  if (description > 0) --description;  // no newline after the last line
  if (description > limits.max_description_chars) {
    return Status::InvalidInput(
        TooLong("description", limits.max_description_chars, description));
  }
  for (size_t i = 0; i < route.moves.size(); ++i) {
    const Move& m = route.moves[i];
    size_t n = Utf8Chars(m.text);
    if (n <= limits.max_move_chars) continue;
    std::string reason = TooLong("move " + std::to_string(i + 1), limits.max_move_chars, n);
    if (!file.empty() && m.line > 0) {
      return Status::InvalidInputAt({std::string(file), m.line, 1}, reason);
    }
    return Status::InvalidInput(reason);
  }
  return Status::Ok();
}

}  // namespace sb::app
