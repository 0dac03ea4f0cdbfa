// The instantiations of the independent estimator, `render_bsdf_only<I>` (dispatch.hpp).
#include "core.hpp"

namespace iris::renderer::detail {
template void render_bsdf_only<isa::baseline>(const render_job&);
#if IRIS_ISA_DISPATCH
template void render_bsdf_only<isa::avx2>(const render_job&);
#endif
}  // namespace iris::renderer::detail
