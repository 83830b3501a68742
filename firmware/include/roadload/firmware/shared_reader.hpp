#pragma once
// Devices read in turn by one thread, each once a round and without waiting: eight accelerometers
// on threads of their own woke a gateway 1,333 times a second for FIFO reads of a few hundred bytes
// (docs/roadloadd.md has the CPU it saves). The price: a read that blocks (a hung
// SPI transfer, a part being started again) holds up every part's round, and a round late by more
// than the slack under the kernel's data-ready queue makes a part resync its clock.
#include <atomic>
#include <string_view>
#include <thread>
#include <vector>

#include "roadload/firmware/channel.hpp"
#include "roadload/firmware/thread_name.hpp"

namespace roadload::firmware {

// `Member`: a Channel.
template <typename Member>
class SharedReader {
 public:
  SharedReader() = default;
  ~SharedReader() { join(); }
  SharedReader(const SharedReader&) = delete;
  SharedReader& operator=(const SharedReader&) = delete;

  // The channels must outlive join(); `period` bounds how long a device's data waits in it.
  // `role` names the thread (name_this_thread).
  void start(std::string_view role, std::vector<Member*> channels, Nanoseconds period, const std::atomic<bool>& stop,
             bool feed_estimator, io::WaitClock& clock) {
    members_ = std::move(channels);
    live_.assign(members_.size(), true);
    for (Member* c : members_) c->begin(feed_estimator, clock);
    thread_ = std::thread([this, role, period, &stop, &clock] {
      name_this_thread(role);
      run(period, stop, clock);
    });
  }
  void join() {
    if (thread_.joinable()) thread_.join();
  }

 private:
  void run(Nanoseconds period, const std::atomic<bool>& stop, io::WaitClock& clock) {
    while (!stop.load(std::memory_order_relaxed)) {
      const CaptureTime round = clock.now();
      bool any = false;
      for (std::size_t i = 0; i < members_.size(); ++i) {
        if (!live_[i]) continue;
        live_[i] = members_[i]->read_once(stop, clock, Nanoseconds{0});
        // One that ended is finished now, as its own thread would have: the merge stops waiting for it.
        if (!live_[i]) members_[i]->finish(stop, clock);
        any = any || live_[i];
      }
      if (!any) break;
      clock.sleep_until(round + period, period);
    }
    for (std::size_t i = 0; i < members_.size(); ++i) {
      if (live_[i]) members_[i]->finish(stop, clock);
    }
  }

  std::vector<Member*> members_;
  std::vector<bool> live_;
  std::thread thread_;
};

}  // namespace roadload::firmware
