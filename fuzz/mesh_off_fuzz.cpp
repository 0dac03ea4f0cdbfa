// Fuzz target: iris::geometry::parse_mesh on arbitrary bytes as .off (the reader behind
// load_mesh and scene files' "mesh" shapes). Property: mesh_fuzz_common.hpp.
#include "mesh_fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return iris::fuzz::check_mesh_bytes(data, size, iris::geometry::mesh_format::off);
}
