#include "store/sql.h"

#include <charconv>

#include "base/log.h"
#include "base/text.h"

namespace sb::store::sql {

const char* DialectName(Dialect d) { return d == Dialect::kSqlite ? "sqlite" : "postgresql"; }

const std::string& Rows::Text(size_t row, size_t col) const {
  static const std::string kEmpty;
  const std::optional<std::string>& cell = rows[row][col];
  return cell ? *cell : kEmpty;
}

int64_t Rows::Int(size_t row, size_t col) const { return OptInt(row, col).value_or(0); }

std::optional<int64_t> Rows::OptInt(size_t row, size_t col) const {
  const std::optional<std::string>& cell = rows[row][col];
  if (!cell) return std::nullopt;
  int64_t v = 0;
  auto [end, ec] = std::from_chars(cell->data(), cell->data() + cell->size(), v);
  if (ec != std::errc() || end != cell->data() + cell->size()) return 0;
  return v;
}

std::optional<double> Rows::OptDouble(size_t row, size_t col) const {
  const std::optional<std::string>& cell = rows[row][col];
  if (!cell) return std::nullopt;
  double v = 0;
  auto [end, ec] = std::from_chars(cell->data(), cell->data() + cell->size(), v);
  if (ec != std::errc() || end != cell->data() + cell->size()) return 0.0;
  return v;
}

std::string DoubleText(double v) {
  char buf[64];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, end) : std::string("0");
}

Status CheckText(const std::vector<Value>& params) {
  for (size_t i = 0; i < params.size(); ++i) {
    const std::string* t = std::get_if<std::string>(&params[i]);
    if (!t) continue;
    std::string where = "parameter " + std::to_string(i + 1) + ": ";
    if (size_t nul = t->find('\0'); nul != std::string::npos) {
      return Status::InvalidInput(where + "text with a NUL byte (byte " + std::to_string(nul) +
                                  ") cannot be stored");
    }
    if (size_t bad = FindInvalidUtf8(*t); bad != std::string::npos) {
      return Status::InvalidInput(where + "text is not valid UTF-8 (byte " + std::to_string(bad) +
                                  ")");
    }
  }
  return Status::Ok();
}

std::string RedactUrl(const std::string& url) {
  std::string out = url;
  size_t scheme = out.find("://");
  if (scheme != std::string::npos) {
    size_t start = scheme + 3;
    size_t end = out.find_first_of("/?", start);
    if (end == std::string::npos) end = out.size();
    size_t at = out.rfind('@', end);
    if (at != std::string::npos && at >= start) {
      size_t colon = out.find(':', start);
      if (colon != std::string::npos && colon < at) out.replace(colon + 1, at - colon - 1, "***");
    }
  }
  // A password given as a query parameter.
  for (size_t p = out.find("password="); p != std::string::npos;
       p = out.find("password=", p + 1)) {
    if (p > 0 && out[p - 1] != '?' && out[p - 1] != '&' && out[p - 1] != ' ') continue;
    size_t v = p + 9;
    size_t e = out.find_first_of("& ", v);
    if (e == std::string::npos) e = out.size();
    out.replace(v, e - v, "***");
  }
  return out;
}

// ---------------------------------------------------------------------------

Result<std::unique_ptr<Pool>> Pool::Create(Factory factory, int size,
                                           std::chrono::milliseconds wait) {
  std::unique_ptr<Pool> pool(new Pool(std::move(factory), size < 1 ? 1 : size, wait));
  SB_ASSIGN_OR_RETURN(std::unique_ptr<Connection> first, pool->factory_());
  pool->dialect_ = first->dialect();
  pool->idle_.push_back(std::move(first));
  pool->open_ = 1;
  return pool;
}

namespace {

// The connection of a Pool::RunAtomically call, as its body's store calls
// see it: statements go to the pinned connection; a store call's own
// transaction is a savepoint of the outer one.
class NestedConnection final : public Connection {
 public:
  explicit NestedConnection(Connection* outer) : outer_(outer) {}
  Dialect dialect() const override { return outer_->dialect(); }
  Result<Rows> Query(std::string_view sql, const std::vector<Value>& params,
                     Violation* violated) override {
    // PostgreSQL ends a transaction at its first failed statement; a store
    // call that handles a failure (a unique violation read as kConflict)
    // must keep the outer transaction usable, as autocommit would.
    if (depth_ > 0 || outer_->dialect() != Dialect::kPostgres) {
      return outer_->Query(sql, params, violated);
    }
    SB_RETURN_IF_ERROR(outer_->Exec("SAVEPOINT sb_stmt"));
    Result<Rows> r = outer_->Query(sql, params, violated);
    SB_RETURN_IF_ERROR(outer_->Exec(r.ok() ? "RELEASE SAVEPOINT sb_stmt"
                                           : "ROLLBACK TO SAVEPOINT sb_stmt; "
                                             "RELEASE SAVEPOINT sb_stmt"));
    return r;
  }
  Status Exec(std::string_view script) override { return outer_->Exec(script); }
  Status Begin() override {
    SB_RETURN_IF_ERROR(outer_->Exec("SAVEPOINT sb_nested_" + std::to_string(depth_ + 1)));
    ++depth_;
    return Status::Ok();
  }
  Status Commit() override {
    if (depth_ == 0) return Status::Internal("commit outside a transaction");
    Status st = outer_->Exec("RELEASE SAVEPOINT sb_nested_" + std::to_string(depth_));
    if (st.ok()) --depth_;
    return st;
  }
  void Rollback() override {
    if (depth_ == 0) return;
    const std::string sp = "sb_nested_" + std::to_string(depth_);
    Status st = outer_->Exec("ROLLBACK TO SAVEPOINT " + sp + "; RELEASE SAVEPOINT " + sp);
    if (!st.ok()) LogError("rollback to savepoint: " + st.message());
    --depth_;
  }
  Status LockKeys(const std::vector<std::string>& keys) override {
    return outer_->LockKeys(keys);
  }
  Result<int> SchemaVersion() override { return outer_->SchemaVersion(); }
  Status SetSchemaVersion(int version) override { return outer_->SetSchemaVersion(version); }
  Status BeforeMigrations() override { return outer_->BeforeMigrations(); }
  Status CheckMigration() override { return outer_->CheckMigration(); }
  Status AfterMigrations() override { return outer_->AfterMigrations(); }
  Result<int64_t> NextId(const std::string& table) override { return outer_->NextId(table); }
  Status SetNextId(const std::string& table, int64_t next) override {
    return outer_->SetNextId(table, next);
  }
  bool broken() const override { return outer_->broken(); }

 private:
  Connection* outer_;
  int depth_ = 0;
};

// The pinned connection of the calling thread's RunAtomically, per pool.
struct Pinned {
  const Pool* pool = nullptr;
  NestedConnection* conn = nullptr;
};
thread_local Pinned t_pinned;

}  // namespace

Status Pool::RunAtomically(const std::function<Status()>& body) {
  if (t_pinned.pool == this) return body();
  SB_ASSIGN_OR_RETURN(Lease lease, Acquire());
  NestedConnection nested(&*lease);
  SB_RETURN_IF_ERROR(lease->Begin());
  const Pinned saved = t_pinned;
  t_pinned = {this, &nested};
  Status st = body();
  t_pinned = saved;
  if (st.ok()) st = lease->Commit();
  if (!st.ok()) lease->Rollback();
  return st;
}

Result<Pool::Lease> Pool::Acquire() {
  if (t_pinned.pool == this) return Lease(t_pinned.conn);
  std::unique_lock<std::mutex> lock(mu_);
  const auto deadline = std::chrono::steady_clock::now() + wait_;
  for (;;) {
    while (!idle_.empty()) {
      std::unique_ptr<Connection> c = std::move(idle_.back());
      idle_.pop_back();
      if (!c->broken()) return Lease(this, std::move(c));
      --open_;  // dropped; a fresh one may be opened below
    }
    if (open_ < size_) {
      ++open_;
      lock.unlock();
      Result<std::unique_ptr<Connection>> c = factory_();
      if (c.ok()) return Lease(this, std::move(c).value());
      lock.lock();
      --open_;
      freed_.notify_one();
      return c.status();
    }
    if (freed_.wait_until(lock, deadline) == std::cv_status::timeout && idle_.empty() &&
        open_ >= size_) {
      return Status::IoError("all " + std::to_string(size_) +
                             " database connections stayed busy for " +
                             std::to_string(wait_.count()) + " ms");
    }
  }
}

void Pool::Release(std::unique_ptr<Connection> conn) {
  std::lock_guard<std::mutex> lock(mu_);
  if (conn->broken()) {
    --open_;
  } else {
    idle_.push_back(std::move(conn));
  }
  freed_.notify_one();
}

}  // namespace sb::store::sql
