// parallelRows: runs body(first_row, end_row) over [0, rows) split into contiguous bands, one
// per hardware thread. Bands are disjoint, so a body that writes only its own rows needs no lock.
// An exception thrown in any band (out of memory, say) is rethrown in the caller once every band
// has finished, instead of terminating the process from a worker thread.
#pragma once

#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

namespace glarecam {

inline unsigned defaultThreadCount() { return std::max(1u, std::thread::hardware_concurrency()); }

template <typename Body>
void parallelRows(int rows, unsigned threads, Body&& body) {
  threads = std::clamp(threads, 1u, static_cast<unsigned>(std::max(rows, 1)));
  if (threads == 1) {
    body(0, rows);
    return;
  }
  auto band = [&](unsigned i) {
    return static_cast<int>(static_cast<long long>(rows) * i / threads);
  };
  std::vector<std::exception_ptr> errors(threads);
  auto run = [&](unsigned i) {
    try {
      body(band(i), band(i + 1));
    } catch (...) {
      errors[i] = std::current_exception();
    }
  };
  {
    std::vector<std::jthread> workers;
    workers.reserve(threads - 1);
    for (unsigned i = 1; i < threads; ++i) workers.emplace_back(run, i);
    run(0);
  }  // joins every worker
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
}

}  // namespace glarecam
