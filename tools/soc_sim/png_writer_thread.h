// Writes PNG files on a thread of its own, so that encoding a frame does not
// hold up the simulation (on this machine it costs about as much as
// simulating a frame of a simple scene). Files are the same as if written
// in line, and written whole or not at all (tools/common/output_file.h); the
// first error is kept and reported by finish(), and failed() tells the
// simulation at once, so that a full disk stops the run instead of letting
// it simulate frames nobody can keep.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace tessera {

class PngWriterThread {
 public:
  PngWriterThread();
  ~PngWriterThread();  // finishes the queue

  // Queues an RGBA8 image; blocks while `max_queued` images wait, to bound memory.
  void write(std::string path, unsigned width, unsigned height, std::vector<uint8_t> rgba);
  // Waits until every queued image is written; returns the first error ("" if none).
  std::string finish();
  unsigned written() const;
  // A write has failed (finish() says which and why).
  bool failed() const { return m_failed.load(); }

 private:
  struct Job {
    std::string path;
    unsigned width, height;
    std::vector<uint8_t> rgba;
  };
  void run();

  static constexpr size_t MAX_QUEUED = 8;
  mutable std::mutex m_mutex;
  std::condition_variable m_changed;
  std::deque<Job> m_jobs;
  bool m_busy = false;
  bool m_stop = false;
  unsigned m_written = 0;
  std::string m_error;
  std::atomic<bool> m_failed{false};
  std::thread m_thread;
};

}  // namespace tessera
