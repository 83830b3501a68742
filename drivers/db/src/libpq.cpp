#include "libpq.hpp"

#include <dlfcn.h>

#include <string>
#include <type_traits>

#include "roadload/db/database.hpp"

namespace roadload::db {
namespace {

// libpq's soname since PostgreSQL 8.0; Debian's libpq5.
constexpr const char* kLibrary = "libpq.so.5";

Libpq load() {
  void* lib = dlopen(kLibrary, RTLD_NOW | RTLD_LOCAL);
  if (lib == nullptr) throw DatabaseError(std::string("PostgreSQL needs ") + kLibrary + " (Debian: libpq5): " + dlerror());
  Libpq l{};
  const auto get = [&](auto& fn, const char* name) {
    void* symbol = dlsym(lib, name);
    if (symbol == nullptr) throw DatabaseError(std::string(kLibrary) + " has no " + name);
    fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(symbol);
  };
  get(l.connectdb, "PQconnectdb");
  get(l.status, "PQstatus");
  get(l.error_message, "PQerrorMessage");
  get(l.finish, "PQfinish");
  get(l.set_notice_processor, "PQsetNoticeProcessor");
  get(l.exec, "PQexec");
  get(l.exec_params, "PQexecParams");
  get(l.clear, "PQclear");
  get(l.result_status, "PQresultStatus");
  get(l.result_error_message, "PQresultErrorMessage");
  get(l.ntuples, "PQntuples");
  get(l.nfields, "PQnfields");
  get(l.getisnull, "PQgetisnull");
  get(l.getvalue, "PQgetvalue");
  get(l.ftype, "PQftype");
  return l;
}

}  // namespace

// A failed load throws out of the static's initialisation, so the next database tries again.
const Libpq& libpq() {
  static const Libpq loaded = load();
  return loaded;
}

}  // namespace roadload::db
