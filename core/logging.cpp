#include "core/logging.h"

#include <spdlog/sinks/stdout_color_sinks.h>

#include <memory>

namespace glarecam {

namespace {

void installLogger(Verbosity verbosity, std::shared_ptr<spdlog::logger> logger) {
  // Indexed by Verbosity: quiet, normal, verbose, debug.
  constexpr spdlog::level::level_enum kLevels[] = {spdlog::level::err, spdlog::level::warn,
                                                   spdlog::level::info, spdlog::level::debug};
  logger->set_level(kLevels[static_cast<int>(verbosity)]);
  spdlog::set_default_logger(std::move(logger));
}

}  // namespace

void initLogging(Verbosity verbosity) {
  auto logger = spdlog::stderr_color_mt("glarecam");
  logger->set_pattern("%^%l%$: %v");
  installLogger(verbosity, std::move(logger));
}

void initLogging(Verbosity verbosity, spdlog::sink_ptr sink) {
  installLogger(verbosity, std::make_shared<spdlog::logger>("glarecam", std::move(sink)));
}

}  // namespace glarecam
