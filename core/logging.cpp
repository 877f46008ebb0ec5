#include "core/logging.h"

#include <spdlog/sinks/stdout_color_sinks.h>

namespace glarecam {

void initLogging(Verbosity verbosity) {
  auto logger = spdlog::stderr_color_mt("glarecam");
  logger->set_pattern("%^%l%$: %v");
  // Indexed by Verbosity: quiet, normal, verbose, debug.
  constexpr spdlog::level::level_enum kLevels[] = {spdlog::level::err, spdlog::level::warn,
                                                   spdlog::level::info, spdlog::level::debug};
  logger->set_level(kLevels[static_cast<int>(verbosity)]);
  spdlog::set_default_logger(logger);
}

}  // namespace glarecam
