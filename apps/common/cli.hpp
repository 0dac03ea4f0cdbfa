#pragma once
/// \file
/// \brief What every iris app shares: bad input → one line on stderr and exit status 2.

#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace iris::app {

/// \brief Exit status for bad input (unknown names, out-of-range values, unwritable paths).
inline constexpr int exit_usage = 2;
/// \brief Exit status for a failure that is not the user's input (I/O, internal).
inline constexpr int exit_failure = 1;

/// \brief Thrown by an app for input it cannot accept; the message names the bad value
/// and what is accepted.
class usage_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// \brief Parse and run `app` (subcommand callbacks run inside). Help and version exit 0;
/// parse errors and `usage_error` print "NAME: error: …" and return 2; any other
/// exception prints the same and returns 1. Never lets an exception escape main.
int run(CLI::App& app, int argc, char** argv);

/// \brief Parse a finite number from `text`, or throw usage_error naming `what`.
double parse_number(const std::string& text, const std::string& what);

/// \brief The items of a comma-separated list ("hwss,paper" → {"hwss", "paper"}); empty
/// items are dropped, nothing is trimmed.
std::vector<std::string> split_list(const std::string& text);

}  // namespace iris::app
