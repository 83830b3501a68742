#pragma once
// What the core DBC's tests share: the database loaded once, hex payloads, and SPNs looked up and
// decoded with the PGN they must live in.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "roadload/j1939/database.hpp"
#include "roadload/j1939/dbc.hpp"
#include "roadload/j1939/signal.hpp"

namespace roadload::j1939::core_dbc_test {

using roadload::j1939::ByteOrder;
using roadload::j1939::Database;
using roadload::j1939::MessageDef;
using roadload::j1939::SignalDef;
using roadload::j1939::SignalReading;
using roadload::j1939::SignalState;

inline constexpr double kExact = 1e-9;  // for factors such as 0.05 or 0.4 that binary floating point rounds

inline const std::string kCorePath = std::string(ROADLOAD_CONFIG_DIR "/j1939-core.dbc");

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The database is built once; every test only reads it.
inline const Database& core() {
  static const Database db = [] {
    Database d;
    const std::string text = read_file(kCorePath);
    EXPECT_FALSE(text.empty()) << "cannot read " << kCorePath;
    const auto err = roadload::j1939::load_dbc(d, text, kCorePath);
    EXPECT_FALSE(err.has_value()) << (err ? err->to_string() : std::string());
    return d;
  }();
  return db;
}

// "607D844A1400F084" -> {0x60, 0x7D, ...}, the data part of a candump line.
inline std::vector<std::uint8_t> bytes(const std::string& hex) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    out.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  }
  return out;
}

// Looks the SPN up, checks it lives in the expected PGN and decodes it from `payload`.
inline SignalReading spn(std::uint32_t number, roadload::j1939::Pgn expected_pgn, const std::vector<std::uint8_t>& payload) {
  const MessageDef* msg = nullptr;
  const SignalDef* sig = core().find_spn(number, &msg);
  EXPECT_NE(sig, nullptr) << "SPN " << number << " is not in the core DBC";
  if (sig == nullptr) return SignalReading{};
  EXPECT_NE(msg, nullptr);
  if (msg != nullptr) {
    EXPECT_EQ(msg->pgn, expected_pgn) << "SPN " << number;
  }
  return roadload::j1939::decode(*sig, payload);
}

inline double value(std::uint32_t number, roadload::j1939::Pgn pgn, const std::vector<std::uint8_t>& payload) {
  const SignalReading r = spn(number, pgn, payload);
  EXPECT_EQ(r.state, SignalState::valid) << "SPN " << number << " raw " << r.raw;
  return r.get().value_or(-99999.0);
}

inline constexpr roadload::j1939::Pgn kEEC1 = 61444, kEEC2 = 61443, kEEC3 = 65247, kEC1 = 65251, kCCVS1 = 65265, kLFE1 = 65266,
                                      kETC1 = 61442, kETC2 = 61445, kAMB = 65269, kVD = 65248, kVDHR = 65217, kVP1 = 65267,
                                      kFD1 = 65213, kEBC1 = 61441, kDM1 = 65226, kERC1 = 61440, kEBC2 = 65215, kHOURS = 65253,
                                      kLFC = 65257, kET1 = 65262;

}  // namespace roadload::j1939::core_dbc_test
