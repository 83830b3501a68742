#pragma once
// An identity for "the same description" (a vehicle, a route): FNV-1a over its canonical text,
// 64 bits, printed as "fnv1a64:<16 hex digits>". Not a defence against anyone forging one.
#include <string>
#include <string_view>

namespace roadload {

std::string content_hash(std::string_view text);

}  // namespace roadload
