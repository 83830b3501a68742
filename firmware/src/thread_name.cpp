#include "roadload/firmware/thread_name.hpp"

#include <pthread.h>

#include <algorithm>
#include <array>

namespace roadload::firmware {

void name_this_thread(std::string_view role) {
  constexpr std::string_view kPrefix = "rl-";
  std::array<char, 16> name{};  // the kernel's TASK_COMM_LEN, its NUL included
  const auto end = std::copy(kPrefix.begin(), kPrefix.end(), name.begin());
  std::copy_n(role.begin(), std::min(role.size(), name.size() - 1 - kPrefix.size()), end);
  // A name is a convenience for whoever watches the process: failing to set it changes nothing.
  (void)pthread_setname_np(pthread_self(), name.data());
}

}  // namespace roadload::firmware
