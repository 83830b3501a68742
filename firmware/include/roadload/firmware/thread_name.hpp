#pragma once
// roadloadd's threads by name, as `top -H`, `ps -L` and perf show them: "rl-can0", "rl-accel",
// "rl-writer". The kernel keeps 15 characters; a longer name is cut.
#include <string_view>

namespace roadload::firmware {

// Names the calling thread "rl-<role>".
void name_this_thread(std::string_view role);

}  // namespace roadload::firmware
