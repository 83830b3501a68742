#pragma once
// `roadload collect`: analysed drives (analyze's or roadloadd's results folders) into the fleet
// database. A drive is keyed by its logger run (recording_id), so ingesting it again changes
// nothing, and its results analysed again replace its rows in one transaction.
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "roadload/parse_error.hpp"

namespace roadload::fleet {

struct CollectSummary {
  int drives_added = 0;
  int drives_unchanged = 0;  // the same results were already there
  int drives_replaced = 0;   // the drive was there with other results (analysed again)
  int sections_added = 0;
  int section_results = 0;  // rows written
  int schema_from = 0;      // the schema version found (0: a new database)
};

// A results folder that cannot be read or is not one: its file, line and field.
class ResultsError : public std::runtime_error {
 public:
  explicit ResultsError(ParseError e) : std::runtime_error(e.to_string()), error(std::move(e)) {}
  ParseError error;
};

// Throws db::DatabaseError on the database's side and ResultsError for a results folder; a drive that fails leaves no row behind.
// `progress` (when set) is called after each drive with the count done.
CollectSummary collect(const std::vector<std::string>& result_dirs, const std::string& db_url,
                       const std::function<void(std::size_t done)>& progress = {});

}  // namespace roadload::fleet
