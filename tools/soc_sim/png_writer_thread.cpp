#include "png_writer_thread.h"

#include <exception>

#include "png_writer.h"

namespace tessera {

PngWriterThread::PngWriterThread() : m_thread([this] { run(); }) {}

PngWriterThread::~PngWriterThread() {
  finish();
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_stop = true;
  }
  m_changed.notify_all();
  m_thread.join();
}

void PngWriterThread::write(std::string path, unsigned width, unsigned height, std::vector<uint8_t> rgba) {
  std::unique_lock<std::mutex> lock(m_mutex);
  m_changed.wait(lock, [this] { return m_jobs.size() < MAX_QUEUED; });
  m_jobs.push_back({std::move(path), width, height, std::move(rgba)});
  m_changed.notify_all();
}

std::string PngWriterThread::finish() {
  std::unique_lock<std::mutex> lock(m_mutex);
  m_changed.wait(lock, [this] { return m_jobs.empty() && !m_busy; });
  return m_error;
}

unsigned PngWriterThread::written() const {
  std::lock_guard<std::mutex> lock(m_mutex);
  return m_written;
}

void PngWriterThread::run() {
  std::unique_lock<std::mutex> lock(m_mutex);
  for (;;) {
    m_changed.wait(lock, [this] { return m_stop || !m_jobs.empty(); });
    if (m_jobs.empty()) return;
    Job job = std::move(m_jobs.front());
    m_jobs.pop_front();
    m_busy = true;
    m_changed.notify_all();
    lock.unlock();
    std::string error;
    try {
      write_png(job.path, job.width, job.height, job.rgba);
    } catch (const std::exception& e) {
      error = e.what();
    }
    lock.lock();
    m_busy = false;
    if (error.empty())
      ++m_written;
    else if (m_error.empty()) {
      m_error = error;
      m_failed.store(true);
    }
    m_changed.notify_all();
  }
}

}  // namespace tessera
