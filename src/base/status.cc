#include "base/status.h"

namespace sb {

std::string SourceLocation::ToString() const {
  std::string s = file;
  if (line > 0) {
    s += ":" + std::to_string(line);
    if (column > 0) s += ":" + std::to_string(column);
  }
  return s;
}

Status Status::InvalidInputAt(SourceLocation where, std::string reason) {
  std::string prefix = where.ToString() + ": ";
  Status s(Code::kInvalidInput, prefix + reason);
  s.reason_offset_ = prefix.size();
  s.location_ = std::move(where);
  return s;
}

std::string Status::reason() const { return message_.substr(reason_offset_); }

Status Status::WithPrefix(const std::string& prefix) const {
  if (ok()) return *this;
  if (!location_) return Status(code_, prefix + ": " + message_);
  // Keep "file:line:col: " first so the location still leads the message.
  Status s = *this;
  s.message_ = message_.substr(0, reason_offset_) + prefix + ": " + reason();
  return s;
}

}  // namespace sb
