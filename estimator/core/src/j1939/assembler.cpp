#include "roadload/j1939/assembler.hpp"

namespace roadload::j1939 {

std::optional<Message> MessageAssembler::push(const CanFrame& frame) {
  if (frame.kind != CanFrameKind::extended) return std::nullopt;
  const Id id = parse_id(frame.id);
  const Pgn pgn = id.pgn();
  if (is_transport_pgn(pgn)) {
    const auto done = tp_.push(frame);
    if (!done) return std::nullopt;
    return Message{done->t, done->pgn, done->sa, done->da, done->priority, done->iface, true, done->data};
  }
  return Message{frame.t, pgn, id.sa, id.da(), id.priority, frame.iface, false, frame.payload()};
}

}  // namespace roadload::j1939
