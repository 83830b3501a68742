#pragma once
// Fuzz target bodies, shared by the libFuzzer binaries and by the regression test that replays
// every corpus and crasher file in ordinary builds.
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace roadload::fuzz {

void candump_line(const std::uint8_t* data, std::size_t size);
void dbc(const std::uint8_t* data, std::size_t size);
void json(const std::uint8_t* data, std::size_t size);
void metadata(const std::uint8_t* data, std::size_t size);
void recording(const std::uint8_t* data, std::size_t size);
void transport(const std::uint8_t* data, std::size_t size);
void vehicle(const std::uint8_t* data, std::size_t size);
void route(const std::uint8_t* data, std::size_t size);
void geo_line(const std::uint8_t* data, std::size_t size);
void daemon_config(const std::uint8_t* data, std::size_t size);

struct Target {
  std::string_view name;
  void (*run)(const std::uint8_t*, std::size_t);
};

inline constexpr Target kTargets[] = {
    {"candump_line", candump_line}, {"dbc", dbc},         {"json", json},   {"metadata", metadata}, {"recording", recording},
    {"transport", transport},       {"vehicle", vehicle}, {"route", route}, {"geo_line", geo_line}, {"daemon_config", daemon_config},
};

}  // namespace roadload::fuzz
