#pragma once
/// \file
/// \brief `--tev [HOST:PORT]`, read the same way by every app that streams to tev. The
/// including app defines IRIS_HAVE_TEV=1 when it links iris::tev.

#include <string>

#include <fmt/core.h>

#include "cli.hpp"

#if IRIS_HAVE_TEV
#include <stdexcept>

#include <iris/tev/tev.hpp>
#endif

namespace iris::app {

#if IRIS_HAVE_TEV
/// \brief The viewer's address given to `--tev`, or usage_error naming the option.
inline iris::tev::address tev_option(const std::string& text) {
    try {
        return iris::tev::parse_address(text);
    } catch (const std::invalid_argument& e) {
        throw usage_error(fmt::format("--tev: {}", e.what()));
    }
}
#else
/// \brief This build has no tev client: asking for one is a usage error.
[[noreturn]] inline void tev_option(const std::string&) {
    throw usage_error("--tev: this build has no tev client");
}
#endif

}  // namespace iris::app
