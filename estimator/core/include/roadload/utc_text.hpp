#pragma once
// UTC as people and logs read it, "2026-11-22T05:40:12Z": the status line's stamp, the drive's date
// in its results. Calendar arithmetic only (std::chrono), no clock read and no C library state.
#include <cstdint>
#include <string>

namespace roadload {

// ISO 8601 to the second for ns since 1970-01-01 UTC (leap seconds aside, as POSIX time).
std::string utc_text(std::int64_t utc_ns);

}  // namespace roadload
