// Error values used at every module boundary (leveldb style).
#ifndef SB_BASE_STATUS_H_
#define SB_BASE_STATUS_H_

#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace sb {

// Status is either OK or an error with a code and a one-line message.
// Messages for input errors follow the compiler convention
// "file:line:col: reason" so editors and users can jump to the spot.
// Value type; cheap to copy; thread-compatible.
class Status {
 public:
  enum class Code {
    kOk = 0,
    kInvalidInput,  // the user's input is malformed (exit code 2 in the CLI)
    kNotFound,      // a named file, id or key does not exist
    kIoError,       // the OS refused a read or write
    kConflict,      // the operation clashes with stored state (e.g. a taken name)
    kPermission,    // the caller may not do this
    kInternal,      // a bug: an invariant did not hold
  };

  Status() = default;
  static Status Ok() { return Status(); }
  static Status InvalidInput(std::string msg) { return Status(Code::kInvalidInput, std::move(msg)); }
  static Status NotFound(std::string msg) { return Status(Code::kNotFound, std::move(msg)); }
  static Status IoError(std::string msg) { return Status(Code::kIoError, std::move(msg)); }
  static Status Conflict(std::string msg) { return Status(Code::kConflict, std::move(msg)); }
  static Status Permission(std::string msg) { return Status(Code::kPermission, std::move(msg)); }
  static Status Internal(std::string msg) { return Status(Code::kInternal, std::move(msg)); }

  bool ok() const { return code_ == Code::kOk; }
  Code code() const { return code_; }
  // The message without a code prefix; empty when ok().
  const std::string& message() const { return message_; }
  // "ok" or the message; for logs and CLI output.
  std::string ToString() const { return ok() ? std::string("ok") : message_; }

 private:
  Status(Code code, std::string msg) : code_(code), message_(std::move(msg)) {}
  Code code_ = Code::kOk;
  std::string message_;
};

// Result<T> holds either a T or a non-OK Status. Access value() only when ok().
template <typename T>
class Result {
 public:
  Result(T value) : v_(std::move(value)) {}           // NOLINT: implicit by design
  Result(Status status) : v_(std::move(status)) {}    // NOLINT: must not be ok()
  bool ok() const { return std::holds_alternative<T>(v_); }
  const Status& status() const {
    static const Status kOk;
    return ok() ? kOk : std::get<Status>(v_);
  }
  T& value() & { return std::get<T>(v_); }
  const T& value() const& { return std::get<T>(v_); }
  T&& value() && { return std::get<T>(std::move(v_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

 private:
  std::variant<T, Status> v_;
};

}  // namespace sb

// Returns early from the enclosing function when `expr` yields a non-OK Status.
#define SB_RETURN_IF_ERROR(expr)              \
  do {                                        \
    ::sb::Status sb_status_ = (expr);         \
    if (!sb_status_.ok()) return sb_status_;  \
  } while (0)

#endif  // SB_BASE_STATUS_H_
