#include "roadload/utc_text.hpp"

#include <chrono>
#include <cstdio>

namespace roadload {

std::string utc_text(std::int64_t utc_ns) {
  using namespace std::chrono;
  const sys_seconds t{floor<seconds>(nanoseconds{utc_ns})};
  const sys_days day = floor<days>(t);
  const year_month_day ymd{day};
  const hh_mm_ss<seconds> hms{t - day};
  char text[40];
  std::snprintf(text, sizeof text, "%04d-%02u-%02uT%02lld:%02lld:%02lldZ", static_cast<int>(ymd.year()),
                static_cast<unsigned>(ymd.month()), static_cast<unsigned>(ymd.day()), static_cast<long long>(hms.hours().count()),
                static_cast<long long>(hms.minutes().count()), static_cast<long long>(hms.seconds().count()));
  return text;
}

}  // namespace roadload
