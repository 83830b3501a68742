#pragma once
// One small interface over the two databases a fleet's results go into: SQLite, a single file and
// no server (the default), and PostgreSQL with PostGIS, shared by many writers. Statements are
// written once with `?` placeholders; each backend binds them its own way. Errors are exceptions
// naming the database and the statement: a fleet's ingest stops at the first and rolls back.
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace roadload::db {

using Value = std::variant<std::monostate, std::int64_t, double, std::string>;
using Row = std::vector<Value>;

enum class Dialect { sqlite, postgres };

class DatabaseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Database {
 public:
  virtual ~Database() = default;
  virtual Dialect dialect() const = 0;
  // Where it is, for messages: the SQLite file or the PostgreSQL URL without its password.
  virtual const std::string& name() const = 0;
  // Statements without parameters, several separated by ';' (schema, migrations).
  virtual void script(std::string_view sql) = 0;
  // One statement; its rows, every column as the type the database holds it in.
  virtual std::vector<Row> query(std::string_view sql, const std::vector<Value>& params = {}) = 0;
  void execute(std::string_view sql, const std::vector<Value>& params = {}) { query(sql, params); }
  virtual void begin() = 0;
  virtual void commit() = 0;
  virtual void rollback() = 0;
};

enum class Open { create, existing };

// `url`: postgresql://... or postgres://... (libpq's connection URI), sqlite:///path or a plain
// path (SQLite: created with Open::create; with Open::existing a missing file is an error, not an
// empty database). Throws DatabaseError when it cannot connect or open.
std::unique_ptr<Database> open_database(const std::string& url, Open mode = Open::create);

// The URL as it may be printed: the password replaced by "***".
std::string redacted(const std::string& url);

// A transaction that rolls back unless committed: an ingest that throws leaves nothing half done.
class Transaction {
 public:
  explicit Transaction(Database& db) : db_(db) { db_.begin(); }
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  ~Transaction() {
    if (!done_) try {
        db_.rollback();
      } catch (const DatabaseError&) {
        // The connection is already gone; the server rolled back for us.
      }
  }
  void commit() {
    db_.commit();
    done_ = true;
  }

 private:
  Database& db_;
  bool done_ = false;
};

// Value accessors for rows read back: a NULL reads as nothing, an integer column as a double
// where a number is wanted (PostgreSQL and SQLite disagree on which numeric type they return).
std::optional<double> number(const Value& v);
std::string text(const Value& v);

}  // namespace roadload::db
