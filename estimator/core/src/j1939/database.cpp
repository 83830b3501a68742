#include "roadload/j1939/database.hpp"

namespace roadload::j1939 {

namespace {
constexpr std::size_t kPgnSpace = std::size_t{1} << 18;
}

Database::Database() : by_pgn_(kPgnSpace, 0) {}

void Database::add(MessageDef message) {
  const Pgn pgn = message.pgn & (kPgnSpace - 1);
  if (by_pgn_[pgn] != 0) {
    messages_[by_pgn_[pgn] - 1u] = std::move(message);
    return;
  }
  messages_.push_back(std::move(message));
  by_pgn_[pgn] = static_cast<std::uint16_t>(messages_.size());
}

const MessageDef* Database::find(Pgn pgn) const {
  if (pgn >= kPgnSpace) return nullptr;
  const std::uint16_t i = by_pgn_[pgn];
  return i == 0 ? nullptr : &messages_[i - 1u];
}

const SignalDef* Database::find_spn(std::uint32_t spn, const MessageDef** message) const {
  for (const MessageDef& m : messages_) {
    for (const SignalDef& s : m.signals) {
      if (s.spn != spn) continue;
      if (message != nullptr) *message = &m;
      return &s;
    }
  }
  return nullptr;
}

const MessageDef* Database::find_name(const std::string& name) const {
  for (const MessageDef& m : messages_) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

}  // namespace roadload::j1939
