#include "decode_columns.hpp"

#include <algorithm>
#include <limits>
#include <map>

#include "files.hpp"
#include "roadload/j1939/assembler.hpp"
#include "roadload/j1939/database.hpp"
#include "roadload/recording/reader.hpp"

namespace roadload::python {
namespace {

// Each name once, its rows holding its index: a frame of millions of rows keeps a few dozen strings.
template <typename Key>
struct Codes {
  std::map<Key, std::int32_t> index;
  std::int32_t of(const Key& key, std::vector<std::string>& names, const std::string& name) {
    const auto [it, added] = index.emplace(key, static_cast<std::int32_t>(names.size()));
    if (added) names.push_back(name);
    return it->second;
  }
};

struct Appender {
  DecodedColumns& out;
  const recording::InterfaceTable& ifaces;
  Codes<std::uint8_t> iface;
  Codes<const j1939::MessageDef*> message;
  Codes<const j1939::SignalDef*> signal;

  void add(const j1939::Message& m, const j1939::MessageDef& def) {
    const std::int32_t iface_code = iface.of(m.iface, out.iface_names, std::string(ifaces.name(m.iface)));
    const std::int32_t message_code = message.of(&def, out.message_names, def.name);
    for (const j1939::SignalDef& s : def.signals) {
      const j1939::SignalReading r = j1939::decode(s, m.data);
      if (r.state == j1939::SignalState::missing) continue;
      const std::size_t units = out.signal_names.size();
      out.signal.push_back(signal.of(&s, out.signal_names, s.name));
      if (out.signal_names.size() > units) out.signal_units.push_back(s.unit);
      out.t_ns.push_back(to_ns(m.t));
      out.iface.push_back(iface_code);
      out.sa.push_back(m.sa);
      out.pgn.push_back(m.pgn);
      out.message.push_back(message_code);
      out.value.push_back(r.state == j1939::SignalState::valid ? r.value : std::numeric_limits<double>::quiet_NaN());
      out.state.push_back(static_cast<std::int32_t>(r.state));
    }
  }
};

}  // namespace

int decode_columns(const std::vector<std::string>& inputs, const std::vector<std::string>& dbcs,
                   const std::vector<std::uint32_t>& pgns, DecodedColumns& out) {
  for (auto s : {j1939::SignalState::valid, j1939::SignalState::parameter_specific, j1939::SignalState::reserved,
                 j1939::SignalState::error, j1939::SignalState::not_available, j1939::SignalState::missing})
    out.state_names.emplace_back(j1939::to_string(s));
  j1939::Database db;
  if (auto rc = cli::load_definitions("decode", dbcs, db)) return *rc;
  auto drive = cli::one_drive("decode", inputs);
  if (const int* rc = std::get_if<int>(&drive)) return *rc;
  // The CAN log only: decode's signals are all there, and the accelerometers' streams would cost
  // most of the read.
  auto rec = recording::RecordingReader::open_drive(std::get<std::vector<std::string>>(drive), recording::kCanStream);
  if (!rec) {
    cli::say("decode", rec.error().to_string());
    return cli::kExitNoInput;
  }
  j1939::MessageAssembler assembler;
  Appender append{out, rec.value().interfaces(), {}, {}, {}};
  while (const recording::Record* r = rec.value().next()) {
    const auto* frame = std::get_if<CanFrame>(r);
    if (frame == nullptr) continue;
    const auto m = assembler.push(*frame);
    if (!m || (!pgns.empty() && std::find(pgns.begin(), pgns.end(), m->pgn) == pgns.end())) continue;
    if (const j1939::MessageDef* def = db.find(m->pgn)) append.add(*m, *def);
  }
  cli::tell_errors("decode", inputs.front(), rec.value().errors());
  return rec.value().errors().count() > 0 ? cli::kExitDataErr : cli::kExitOk;
}

}  // namespace roadload::python
