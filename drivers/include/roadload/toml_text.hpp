#pragma once
// TOML text as roadload reads it: UTF-8 is welcome inside strings and comments (a vehicle file's
// "m²"), never outside them, where TOML allows none and Debian's toml++ 3.3 reaches undefined
// behaviour classifying it (found by the vehicle, route and daemon-config fuzzers).
#include <optional>
#include <string>
#include <string_view>

namespace roadload {

// `s` as a TOML basic string: in quotes, with quotes, backslashes and the control characters TOML
// forbids (all below 0x20 but tab, and 0x7F) escaped. Every writer of roadload's TOML files uses it.
std::string toml_quoted(std::string_view s);

}  // namespace roadload

namespace roadload::detail {

// The line of the first byte above 0x7F outside every string and comment; nullopt when none.
std::optional<long> non_ascii_outside_strings(std::string_view text);

}  // namespace roadload::detail
