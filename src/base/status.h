// Error values used at every module boundary (leveldb style).
#ifndef SB_BASE_STATUS_H_
#define SB_BASE_STATUS_H_

#include <cassert>
#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace sb {

// Where in a source text an error is: file name (as the user gave it), line
// and column, both 1-based; 0 = not known. Value type.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;

  // "file:line:col", "file:line" (no column) or "file" (no line).
  std::string ToString() const;
  bool operator==(const SourceLocation&) const = default;
};

// Status is either OK or an error with a code and a one-line message.
// An input error can carry its source location as data (location()); its
// message() then reads "file:line:col: reason" (the compiler convention, so
// editors and users can jump to the spot) and reason() is the part after it.
// Value type; cheap to copy; thread-compatible. Never ignore one: the class is
// [[nodiscard]] and the build treats an ignored Status as an error.
class [[nodiscard]] Status {
 public:
  enum class Code {
    kOk = 0,
    kInvalidInput,       // the user's input is malformed (exit code 2 in the CLI)
    kNotFound,           // a named file, id or key does not exist (or is not visible)
    kIoError,            // the OS or the database refused a read or write
    kConflict,           // the operation clashes with stored state (e.g. a taken name)
    kPermission,         // the caller is known but may not do this
    kUnauthenticated,    // the caller must log in first, or gave wrong credentials
    kResourceExhausted,  // too many attempts or too much work; try again later
    kInternal,           // a bug: an invariant did not hold
  };

  Status() = default;
  static Status Ok() { return Status(); }
  static Status InvalidInput(std::string msg) { return Status(Code::kInvalidInput, std::move(msg)); }
  // An input error at `where`: message() = where.ToString() + ": " + reason.
  static Status InvalidInputAt(SourceLocation where, std::string reason);
  static Status NotFound(std::string msg) { return Status(Code::kNotFound, std::move(msg)); }
  static Status IoError(std::string msg) { return Status(Code::kIoError, std::move(msg)); }
  static Status Conflict(std::string msg) { return Status(Code::kConflict, std::move(msg)); }
  static Status Permission(std::string msg) { return Status(Code::kPermission, std::move(msg)); }
  static Status Unauthenticated(std::string msg) {
    return Status(Code::kUnauthenticated, std::move(msg));
  }
  static Status ResourceExhausted(std::string msg) {
    return Status(Code::kResourceExhausted, std::move(msg));
  }
  static Status Internal(std::string msg) { return Status(Code::kInternal, std::move(msg)); }

  bool ok() const { return code_ == Code::kOk; }
  Code code() const { return code_; }
  // The whole message, location included; empty when ok().
  const std::string& message() const { return message_; }
  // The message without the location prefix (= message() when not located).
  std::string reason() const;
  // The source location of an input error, when known.
  const std::optional<SourceLocation>& location() const { return location_; }
  // "ok" or the message; for logs and CLI output.
  std::string ToString() const { return ok() ? std::string("ok") : message_; }
  // The same error with "prefix: " in front of the message (the location is
  // kept; reason() gains the prefix too). OK stays OK.
  Status WithPrefix(const std::string& prefix) const;

 private:
  Status(Code code, std::string msg) : code_(code), message_(std::move(msg)) {}
  Code code_ = Code::kOk;
  std::string message_;
  std::optional<SourceLocation> location_;
  size_t reason_offset_ = 0;  // where the reason starts in message_
};

// Result<T> holds either a T or a non-OK Status. Access value() only when
// ok(). Building a Result from an OK Status is a programming error: it asserts
// in debug builds and turns into kInternal otherwise.
template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}  // NOLINT: implicit by design
  Result(Status status) : v_(std::move(status)) {  // NOLINT: must not be ok()
    assert(!std::get<Status>(v_).ok() && "Result built from an OK status");
    if (std::get<Status>(v_).ok()) v_ = Status::Internal("Result built from an OK status");
  }
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
  T&& operator*() && { return std::get<T>(std::move(v_)); }

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

#define SB_CONCAT_INNER_(a, b) a##b
#define SB_CONCAT_(a, b) SB_CONCAT_INNER_(a, b)
// `SB_ASSIGN_OR_RETURN(auto x, ExprGivingResult());` declares x from the
// Result's value, or returns its Status from the enclosing function.
#define SB_ASSIGN_OR_RETURN(lhs, expr) \
  SB_ASSIGN_OR_RETURN_IMPL_(SB_CONCAT_(sb_result_, __LINE__), lhs, expr)
#define SB_ASSIGN_OR_RETURN_IMPL_(tmp, lhs, expr) \
  auto tmp = (expr);                              \
  if (!tmp.ok()) return tmp.status();             \
  lhs = std::move(tmp).value()

#endif  // SB_BASE_STATUS_H_
