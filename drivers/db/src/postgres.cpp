// PostgreSQL through libpq's C interface: parameters go as text with the statement (no SQL is
// ever assembled from values), and numbers come back by their column's type.
#include <cstdio>

#include "backends.hpp"
#include "libpq.hpp"

namespace roadload::db {
namespace {

// Type OIDs of pg_type.h, stable since PostgreSQL 7.
constexpr Oid kInt8 = 20, kInt2 = 21, kInt4 = 23, kFloat4 = 700, kFloat8 = 701, kNumeric = 1700;

// `?` to `$1`, `$2`...: statements are written once for both databases. None holds a `?` in a
// string literal.
std::string numbered(std::string_view sql) {
  std::string out;
  int n = 0;
  for (char c : sql) {
    if (c == '?') out += "$" + std::to_string(++n);
    else out += c;
  }
  return out;
}

std::string as_text(const Value& v) {
  if (const auto* i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
  if (const auto* d = std::get_if<double>(&v)) {
    char b[32];
    std::snprintf(b, sizeof b, "%.17g", *d);
    return b;
  }
  return std::get<std::string>(v);
}

class Postgres final : public Database {
 public:
  explicit Postgres(const std::string& url) : pq_(libpq()), name_(redacted(url)) {
    conn_ = pq_.connectdb(url.c_str());
    if (pq_.status(conn_) != CONNECTION_OK) {
      const std::string why = pq_.error_message(conn_);
      pq_.finish(conn_);
      throw DatabaseError(name_ + ": cannot connect: " + why);
    }
    // "already exists, skipping" notices of an idempotent schema are not news.
    pq_.set_notice_processor(
        conn_, [](void*, const char*) {}, nullptr);
  }
  ~Postgres() override { pq_.finish(conn_); }

  Dialect dialect() const override { return Dialect::postgres; }
  const std::string& name() const override { return name_; }

  void script(std::string_view sql) override { check(pq_.exec(conn_, std::string(sql).c_str()), sql); }

  std::vector<Row> query(std::string_view sql, const std::vector<Value>& params) override {
    std::vector<std::string> texts(params.size());
    std::vector<const char*> values(params.size(), nullptr);
    for (std::size_t i = 0; i < params.size(); ++i) {
      if (std::holds_alternative<std::monostate>(params[i])) continue;
      texts[i] = as_text(params[i]);
      values[i] = texts[i].c_str();
    }
    PGresult* r = pq_.exec_params(conn_, numbered(sql).c_str(), static_cast<int>(params.size()), nullptr, values.data(), nullptr,
                                  nullptr, 0);
    const auto rows = read(r, sql);
    pq_.clear(r);
    return rows;
  }

  void begin() override { script("BEGIN"); }
  void commit() override { script("COMMIT"); }
  void rollback() override { script("ROLLBACK"); }

 private:
  void check(PGresult* r, std::string_view sql) {
    const auto status = pq_.result_status(r);
    if (status == PGRES_COMMAND_OK || status == PGRES_TUPLES_OK) {
      pq_.clear(r);
      return;
    }
    const std::string why = pq_.result_error_message(r);
    pq_.clear(r);
    throw DatabaseError(name_ + ": " + why + " in: " + std::string(sql.substr(0, sql.find('\n', 1))));
  }

  std::vector<Row> read(PGresult* r, std::string_view sql) {
    const auto status = pq_.result_status(r);
    if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) {
      const std::string why = pq_.result_error_message(r);
      pq_.clear(r);
      throw DatabaseError(name_ + ": " + why + " in: " + std::string(sql.substr(0, sql.find('\n', 1))));
    }
    std::vector<Row> rows(static_cast<std::size_t>(pq_.ntuples(r)));
    for (int i = 0; i < pq_.ntuples(r); ++i) {
      for (int c = 0; c < pq_.nfields(r); ++c) rows[i].push_back(field(r, i, c));
    }
    return rows;
  }

  Value field(PGresult* r, int row, int column) const {
    if (pq_.getisnull(r, row, column)) return std::monostate{};
    const std::string s = pq_.getvalue(r, row, column);
    switch (pq_.ftype(r, column)) {
      case kInt2:
      case kInt4:
      case kInt8: return static_cast<std::int64_t>(std::stoll(s));
      case kFloat4:
      case kFloat8:
      case kNumeric: return std::stod(s);
      default: return s;
    }
  }

  const Libpq& pq_;
  std::string name_;
  PGconn* conn_ = nullptr;
};

}  // namespace

std::unique_ptr<Database> open_postgres(const std::string& url) { return std::make_unique<Postgres>(url); }

}  // namespace roadload::db
