#include "roadload/db/database.hpp"

#include <charconv>

#include "backends.hpp"

namespace roadload::db {

std::unique_ptr<Database> open_database(const std::string& url, Open mode) {
  if (url.starts_with("postgresql://") || url.starts_with("postgres://")) return open_postgres(url);
  if (url.starts_with("sqlite://")) return open_sqlite(url.substr(std::string_view("sqlite://").size()), mode);
  if (url.find("://") != std::string::npos)
    throw DatabaseError(url + ": not a database URL (postgresql://..., sqlite:///path or a file path)");
  return open_sqlite(url, mode);
}

std::string redacted(const std::string& url) {
  const auto scheme = url.find("://");
  const auto at = url.find('@');
  if (scheme == std::string::npos || at == std::string::npos) return url;
  const auto colon = url.find(':', scheme + 3);
  if (colon == std::string::npos || colon > at) return url;
  return url.substr(0, colon + 1) + "***" + url.substr(at);
}

std::optional<double> number(const Value& v) {
  if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* s = std::get_if<std::string>(&v)) {
    double x = 0;
    const auto [end, ec] = std::from_chars(s->data(), s->data() + s->size(), x);
    if (ec == std::errc() && end == s->data() + s->size()) return x;
  }
  return std::nullopt;
}

std::string text(const Value& v) {
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  if (const auto* i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
  if (const auto* d = std::get_if<double>(&v)) return std::to_string(*d);
  return {};
}

}  // namespace roadload::db
