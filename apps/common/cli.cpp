#include "cli.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <new>

#include <fmt/core.h>

namespace iris::app {

int run(CLI::App& app, int argc, char** argv) {
    try {
        app.parse(argc, argv);
        return 0;
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        fmt::print(stderr, "{}: error: {} (see --help)\n", app.get_name(), e.what());
        return exit_usage;
    } catch (const usage_error& e) {
        fmt::print(stderr, "{}: error: {}\n", app.get_name(), e.what());
        return exit_usage;
    } catch (const std::bad_alloc&) {
        fmt::print(stderr, "{}: error: out of memory (a buffer could not be allocated; try a smaller image)\n", app.get_name());
        return exit_failure;
    } catch (const std::exception& e) {
        fmt::print(stderr, "{}: error: {}\n", app.get_name(), e.what());
        return exit_failure;
    }
}

double parse_number(const std::string& text, const std::string& what) {
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v))
        throw usage_error(fmt::format("{} must be a finite number, got '{}'", what, text));
    return v;
}

std::vector<std::string> split_list(const std::string& text) {
    std::vector<std::string> out;
    std::string::size_type start = 0;
    while (start <= text.size()) {
        const auto comma = std::min(text.find(',', start), text.size());
        if (comma > start) out.push_back(text.substr(start, comma - start));
        start = comma + 1;
    }
    return out;
}

}  // namespace iris::app
