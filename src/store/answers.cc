// The stored form of questionnaire answers (store.h, EncodeAnswers), shared
// by every backend.
#include <string>

#include "base/number.h"
#include "store/store.h"

namespace sb::store {

std::string EncodeAnswers(const Answers& answers) {
  std::string out = "[";
  for (size_t i = 0; i < answers.size(); ++i) {
    if (i) out += ',';
    out += answers[i] ? std::to_string(*answers[i]) : "null";
  }
  return out + "]";
}

Result<Answers> DecodeAnswers(const std::string& text) {
  auto bad = [&] { return Status::InvalidInput("stored answers are malformed: " + text); };
  if (text.size() < 2 || text.front() != '[' || text.back() != ']') return bad();
  Answers out;
  std::string_view body(text.data() + 1, text.size() - 2);
  if (body.empty()) return out;
  size_t start = 0;
  while (true) {
    size_t comma = body.find(',', start);
    std::string_view part = body.substr(
        start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    if (part == "null") {
      out.push_back(std::nullopt);
    } else {
      int v = 0;
      if (!ParseInt(part, &v)) return bad();
      out.push_back(v);
    }
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace sb::store
