// parallelRows: runs body(first_row, end_row) over [0, rows) split into contiguous bands, one
// per hardware thread. Bands are disjoint, so a body that writes only its own rows needs no lock.
#pragma once

#include <algorithm>
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
  std::vector<std::jthread> workers;
  workers.reserve(threads - 1);
  auto band = [&](unsigned i) {
    return static_cast<int>(static_cast<long long>(rows) * i / threads);
  };
  for (unsigned i = 1; i < threads; ++i) {
    workers.emplace_back([&, i] { body(band(i), band(i + 1)); });
  }
  body(0, band(1));
}

}  // namespace glarecam
