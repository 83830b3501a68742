#pragma once
// A recording read on a second thread, a batch of records ahead of its one consumer: reading and
// parsing the text on one core and the consumer's work on the other take a decode of a CAN log
// from the sum of the two to the larger.
#include <array>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

#include "roadload/recording/candump.hpp"
#include "roadload/recording/reader.hpp"

namespace roadload::recording {

class ReadAhead {
 public:
  // Reads `reader` from a thread of its own until the end or destruction. The reader is not
  // touched by the caller meanwhile: its interfaces come from interfaces() below, and its errors
  // may be read once next() has returned null.
  explicit ReadAhead(RecordingReader& reader);
  ~ReadAhead();
  ReadAhead(const ReadAhead&) = delete;
  ReadAhead& operator=(const ReadAhead&) = delete;

  // The next record, valid until the next call; null at the end. Rethrows what the reading thread
  // threw.
  const Record* next();
  // The interface names of every record handed out so far.
  const InterfaceTable& interfaces() const { return interfaces_; }

 private:
  // Each hand-over may wake a thread, which costs tens of microseconds in a VM: the batches are
  // large (256 records a batch took a decode from 62 to 90 ms).
  static constexpr std::size_t kBatch = 1024;
  static constexpr std::size_t kBatches = 3;
  struct Batch {
    std::vector<Record> records = std::vector<Record>(kBatch);
    std::size_t size = 0;
    bool last = false;
    bool new_interfaces = false;  // `interfaces` holds a table grown since the previous batch
    InterfaceTable interfaces;
  };
  void read();
  bool fill(Batch& b, std::size_t& interfaces_seen);

  RecordingReader& reader_;
  std::array<Batch, kBatches> batches_;
  // Counters, not a lock: a hand-over with nobody waiting is two atomic operations.
  std::atomic<std::size_t> filled_{0};    // batches the reading thread has handed over
  std::atomic<std::size_t> released_{0};  // batches the consumer has finished with; kStop: stop
  static constexpr std::size_t kStop = std::size_t{1} << 62;
  std::exception_ptr failure_;  // set before the last batch is handed over
  // The consumer's side.
  Batch* current_ = nullptr;
  std::size_t at_ = 0;
  bool ended_ = false;
  InterfaceTable interfaces_;
  std::thread thread_;  // last: started once everything above exists
};

}  // namespace roadload::recording
