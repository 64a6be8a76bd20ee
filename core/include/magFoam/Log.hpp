// Logging through spdlog: one process-wide logger writing to stdout, as
// OpenFOAM apps do (Allrun functions redirect it to log.<app>).
#pragma once

#include <spdlog/spdlog.h>

#include <string>

namespace mag::log {

// Set up the default logger; level is one of trace, debug, info, warn, error.
void init(const std::string& level = "info");

} // namespace mag::log
