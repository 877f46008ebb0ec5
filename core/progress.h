// Progress of a long operation on stderr: "label: step 3/6 (message)". On a terminal the line
// is redrawn in place; otherwise (journald, CI logs) a line is printed at most once a second
// and at the end, so logs stay short. Silent for operations that finish within a second.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace glarecam {

class Progress {
 public:
  Progress(std::string label, int total, bool enabled = true);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(const std::string& message = {});  // one step done
  void setTotal(int total) { total_ = total; }    // when the work turns out larger
  void finish();

 private:
  void print();

  std::string label_;
  int total_;
  int done_ = 0;
  bool enabled_;
  bool terminal_;
  bool printed_ = false;
  bool finished_ = false;
  std::string message_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_print_;
};

}  // namespace glarecam
