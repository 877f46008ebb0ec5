#include "core/progress.h"

#include <unistd.h>

namespace glarecam {

namespace {
constexpr auto kQuietPeriod = std::chrono::seconds(1);  // operations shorter than this stay silent
}

Progress::Progress(std::string label, int total, bool enabled)
    : label_(std::move(label)),
      total_(total),
      enabled_(enabled),
      terminal_(::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_) {}

Progress::~Progress() { finish(); }

void Progress::advance(const std::string& message) {
  ++done_;
  message_ = message;
  auto now = std::chrono::steady_clock::now();
  if (!enabled_ || now - start_ < kQuietPeriod) return;
  if (terminal_ || now - last_print_ >= kQuietPeriod || done_ == total_) {
    last_print_ = now;
    print();
  }
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (printed_ && terminal_) std::fputc('\n', stderr);
}

void Progress::print() {
  double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stderr, "%s%s: %d/%d %s(%.1f s)%s", terminal_ ? "\r\033[K" : "", label_.c_str(),
               done_, total_, message_.empty() ? "" : (message_ + " ").c_str(), elapsed_s,
               terminal_ ? "" : "\n");
  std::fflush(stderr);
  printed_ = true;
}

}  // namespace glarecam
