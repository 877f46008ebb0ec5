// A fake of the part of libgpiod 1.6's C API that rig/gpio/gpiod_rig_io.cpp uses, over a
// simulated kernel: chips at /dev paths with labels and named lines, lines held by other users,
// forced errno values. It logs every request, write, release and close in order, so that tests
// check what the backend asked of the kernel and that it released each line once, before closing
// its chip. Linked instead of the real libgpiod (rig_gpiod_tests), never with it.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace fake_gpiod {

struct Line {
  std::string name;
  std::string other_consumer;  // held by another program or driver when not empty
  int request_errno = 0;       // gpiod_line_request() fails with this (e.g. EINVAL)
  int io_errno = 0;            // gpiod_line_get_value() / set_value() fail with this
  int value = 0;               // the logical value (as read back or last written)
  // Set by the backend's request:
  bool requested = false;
  std::string consumer;
  int request_type = 0;
  int flags = 0;
};

struct Chip {
  std::string name;  // "gpiochip0"
  std::string label;
  std::vector<Line> lines;
};

struct Kernel {
  std::map<std::string, Chip> chips;  // by /dev path
  int open_errno = 0;                 // every open fails with this when not 0
  std::vector<std::string> log;       // "request 17 glarecam", "set 17 1", "release 17", "close"
  int open_handles = 0;
};

// The simulated kernel, reset by each test.
Kernel& kernel();
void reset();
// A chip with `count` lines named "GPIO<offset>".
Chip& addChip(const std::string& path, const std::string& name, const std::string& label,
              unsigned count);

}  // namespace fake_gpiod
