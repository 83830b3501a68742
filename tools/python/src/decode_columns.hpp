#pragma once
// A recording's decoded J1939 signals as columns, one row per signal of each message the
// definitions know: what `roadload decode` prints, one message a line, laid out for a data frame.
#include <cstdint>
#include <string>
#include <vector>

namespace roadload::python {

struct DecodedColumns {
  std::vector<std::int64_t> t_ns;  // the capture clock's stamp, as decode prints it in seconds
  std::vector<std::int32_t> iface;
  std::vector<std::uint8_t> sa;
  std::vector<std::uint32_t> pgn;
  std::vector<std::int32_t> message;  // into message_names
  std::vector<std::int32_t> signal;   // into signal_names and signal_units
  std::vector<double> value;          // NaN unless the state is valid
  std::vector<std::int32_t> state;    // into state_names
  std::vector<std::string> iface_names, message_names, signal_names, signal_units, state_names;
};

// The built-in definitions and `dbcs` over them; only `pgns` when not empty. Returns `roadload
// decode`'s exit status (65 when lines were malformed: the rest is decoded, each named through
// cli::say()).
int decode_columns(const std::vector<std::string>& inputs, const std::vector<std::string>& dbcs,
                   const std::vector<std::uint32_t>& pgns, DecodedColumns& out);

}  // namespace roadload::python
