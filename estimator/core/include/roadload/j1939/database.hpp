#pragma once
// Message and signal definitions, looked up by PGN in constant time. Definitions are data loaded
// from DBC files; nothing about a particular PGN is compiled in.
#include <cstdint>
#include <string>
#include <vector>

#include "roadload/j1939/id.hpp"
#include "roadload/j1939/signal.hpp"

namespace roadload::j1939 {

struct MessageDef {
  Pgn pgn = 0;
  std::string name;
  std::uint32_t length = 8;         // bytes; above 8 the message travels by the transport protocol
  std::uint32_t cycle_time_ms = 0;  // GenMsgCycleTime when the DBC gives it
  std::vector<SignalDef> signals;
};

class Database {
 public:
  Database();

  // A later definition of the same PGN replaces the earlier one, so a user's DBC loaded after the
  // built-in set overrides it.
  void add(MessageDef message);
  const MessageDef* find(Pgn pgn) const;
  // Finds a signal by SPN; `message` (if given) receives the message that carries it.
  const SignalDef* find_spn(std::uint32_t spn, const MessageDef** message = nullptr) const;
  const MessageDef* find_name(const std::string& name) const;

  const std::vector<MessageDef>& messages() const { return messages_; }
  std::size_t size() const { return messages_.size(); }

 private:
  std::vector<MessageDef> messages_;
  std::vector<std::uint16_t> by_pgn_;  // 2^18 PGNs; 0 = unknown, else index + 1
};

}  // namespace roadload::j1939
