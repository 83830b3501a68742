#pragma once
// libpq, loaded when the first PostgreSQL database is opened rather than linked: it brings some
// twenty libraries (TLS, Kerberos, LDAP) that every roadload command would otherwise map and
// relocate at start, most of a decode's fixed cost, and 0.3 s of each command's start under
// User-Mode Linux, where page faults are dear. The headers give the types and the signatures.
#include <libpq-fe.h>

namespace roadload::db {

struct Libpq {
  decltype(&PQconnectdb) connectdb;
  decltype(&PQstatus) status;
  decltype(&PQerrorMessage) error_message;
  decltype(&PQfinish) finish;
  decltype(&PQsetNoticeProcessor) set_notice_processor;
  decltype(&PQexec) exec;
  decltype(&PQexecParams) exec_params;
  decltype(&PQclear) clear;
  decltype(&PQresultStatus) result_status;
  decltype(&PQresultErrorMessage) result_error_message;
  decltype(&PQntuples) ntuples;
  decltype(&PQnfields) nfields;
  decltype(&PQgetisnull) getisnull;
  decltype(&PQgetvalue) getvalue;
  decltype(&PQftype) ftype;
};

// The library's functions, loaded once; throws DatabaseError naming what could not be loaded.
const Libpq& libpq();

}  // namespace roadload::db
