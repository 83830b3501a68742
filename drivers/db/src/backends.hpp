#pragma once
// The two implementations behind open_database().
#include <memory>
#include <string>

#include "roadload/db/database.hpp"

namespace roadload::db {

std::unique_ptr<Database> open_sqlite(const std::string& path, Open mode);
std::unique_ptr<Database> open_postgres(const std::string& url);

}  // namespace roadload::db
