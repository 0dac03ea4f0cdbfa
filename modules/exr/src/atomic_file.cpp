#include <atomic>
#include <system_error>

#include <unistd.h>

#include "iris/exr/exr.hpp"

namespace iris::exr {

void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path&)>& write_to) {
    namespace fs = std::filesystem;
    // Unique per process and per call: concurrent writers of one target never share a temp.
    static std::atomic<unsigned> counter{0};
    fs::path tmp = target;
    tmp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    try {
        write_to(tmp);
    } catch (...) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw;
    }
    std::error_code ec;
    fs::rename(tmp, target, ec);
    if (ec) {
        const std::string why = ec.message();  // before the cleanup reuses `ec`
        fs::remove(tmp, ec);
        throw error("cannot replace '" + target.string() + "': " + why);
    }
}

}  // namespace iris::exr
