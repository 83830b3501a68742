// SQLite: the embedded default. Several Dask workers may write one file at once, so each waits
// for the others' transactions (busy timeout) and takes the write lock when it begins, not at its
// first write, where two readers upgrading at once would deadlock.
#include <sqlite3.h>

#include "backends.hpp"

namespace roadload::db {
namespace {

class Sqlite final : public Database {
 public:
  Sqlite(const std::string& path, Open mode) : name_(path) {
    const int flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_FULLMUTEX | (mode == Open::create ? SQLITE_OPEN_CREATE : 0);
    if (sqlite3_open_v2(path.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
      const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
      sqlite3_close(db_);
      throw DatabaseError(path + ": cannot open the SQLite database: " + why);
    }
    sqlite3_busy_timeout(db_, 120'000);
    script("PRAGMA foreign_keys = ON; PRAGMA journal_mode = WAL;");
  }
  ~Sqlite() override { sqlite3_close(db_); }

  Dialect dialect() const override { return Dialect::sqlite; }
  const std::string& name() const override { return name_; }

  void script(std::string_view sql) override {
    char* error = nullptr;
    const std::string text(sql);
    if (sqlite3_exec(db_, text.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
      const std::string why = error ? error : sqlite3_errmsg(db_);
      sqlite3_free(error);
      throw DatabaseError(name_ + ": " + why + " in: " + first_line(sql));
    }
  }

  std::vector<Row> query(std::string_view sql, const std::vector<Value>& params) override {
    sqlite3_stmt* stmt = nullptr;
    if (sqlite3_prepare_v2(db_, sql.data(), static_cast<int>(sql.size()), &stmt, nullptr) != SQLITE_OK) fail(sql);
    std::vector<Row> rows;
    try {
      bind(stmt, params, sql);
      for (int rc = sqlite3_step(stmt); rc != SQLITE_DONE; rc = sqlite3_step(stmt)) {
        if (rc != SQLITE_ROW) fail(sql);
        rows.push_back(row(stmt));
      }
    } catch (...) {
      sqlite3_finalize(stmt);
      throw;
    }
    sqlite3_finalize(stmt);
    return rows;
  }

  void begin() override { script("BEGIN IMMEDIATE"); }
  void commit() override { script("COMMIT"); }
  void rollback() override { script("ROLLBACK"); }

 private:
  static std::string first_line(std::string_view sql) {
    const auto start = sql.find_first_not_of(" \n");
    if (start == std::string_view::npos) return {};
    return std::string(sql.substr(start, sql.find('\n', start) - start));
  }
  [[noreturn]] void fail(std::string_view sql) const {
    throw DatabaseError(name_ + ": " + sqlite3_errmsg(db_) + " in: " + first_line(sql));
  }

  void bind(sqlite3_stmt* stmt, const std::vector<Value>& params, std::string_view sql) const {
    for (std::size_t i = 0; i < params.size(); ++i) {
      const int at = static_cast<int>(i) + 1;
      int rc = SQLITE_OK;
      if (const auto* n = std::get_if<std::int64_t>(&params[i])) rc = sqlite3_bind_int64(stmt, at, *n);
      else if (const auto* d = std::get_if<double>(&params[i])) rc = sqlite3_bind_double(stmt, at, *d);
      else if (const auto* s = std::get_if<std::string>(&params[i]))
        rc = sqlite3_bind_text(stmt, at, s->data(), static_cast<int>(s->size()), SQLITE_TRANSIENT);
      else rc = sqlite3_bind_null(stmt, at);
      if (rc != SQLITE_OK) fail(sql);
    }
  }

  static Row row(sqlite3_stmt* stmt) {
    Row r;
    for (int c = 0; c < sqlite3_column_count(stmt); ++c) {
      switch (sqlite3_column_type(stmt, c)) {
        case SQLITE_INTEGER: r.emplace_back(static_cast<std::int64_t>(sqlite3_column_int64(stmt, c))); break;
        case SQLITE_FLOAT: r.emplace_back(sqlite3_column_double(stmt, c)); break;
        case SQLITE_NULL: r.emplace_back(std::monostate{}); break;
        default: {
          const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(stmt, c));
          r.emplace_back(std::string(p, static_cast<std::size_t>(sqlite3_column_bytes(stmt, c))));
        }
      }
    }
    return r;
  }

  std::string name_;
  sqlite3* db_ = nullptr;
};

}  // namespace

std::unique_ptr<Database> open_sqlite(const std::string& path, Open mode) { return std::make_unique<Sqlite>(path, mode); }

}  // namespace roadload::db
